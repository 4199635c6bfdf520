"""Where a key of a scene file stands in its text (file:line for every error)."""

from __future__ import annotations

import bisect
import re
from typing import Any

from ._errors import Key


# -- locating keys in the file text ----------------------------------------------------
class _Locator:
    """Line numbers of keys in TOML text, including keys inside inline tables
    and elements of arrays (``("object", 1, "families", 0, "n1") -> 12``).

    A small lenient scanner: the text has already been parsed by tomllib, so
    it only needs to follow the structure, not to check it.
    """

    def __init__(self, text: str) -> None:
        self.text = text
        self.n = len(text)
        self.line_starts = [0] + [m.end() for m in re.finditer("\n", text)]
        self.lines: dict[Key, int] = {}
        self._aot: dict[tuple[str, ...], int] = {}
        try:
            self._scan()
        except (IndexError, ValueError):  # pragma: no cover - best effort only
            pass

    def line_of(self, key: Key) -> int | None:
        """The line of ``key``, or of its nearest enclosing key that was found."""
        for k in range(len(key), 0, -1):
            if key[:k] in self.lines:
                return self.lines[key[:k]]
        return None

    # scanner -------------------------------------------------------------------
    def _line(self, i: int) -> int:
        return bisect.bisect_right(self.line_starts, i)

    def _skip(self, i: int, newlines: bool = True) -> int:
        t = self.text
        while i < self.n:
            c = t[i]
            if c == "#":
                j = t.find("\n", i)
                i = self.n if j < 0 else j
            elif c in " \t\r" or (newlines and c == "\n"):
                i += 1
            else:
                break
        return i

    def _string(self, i: int) -> tuple[str, int]:
        t = self.text
        for q in ('"""', "'''"):
            if t.startswith(q, i):
                j = t.find(q, i + 3)
                while q == '"""' and j > 0 and _escaped(t, j):
                    j = t.find(q, j + 1)
                j = self.n if j < 0 else j + 3
                while j < self.n and t[j] == q[0]:
                    j += 1
                return t[i + 3 : j - 3], j
        q = t[i]
        j = i + 1
        while j < self.n and t[j] != q and t[j] != "\n":
            j += 2 if (q == '"' and t[j] == "\\") else 1
        return t[i + 1 : j], j + 1

    def _key(self, i: int) -> tuple[list[str], int]:
        """A dotted key ending before ``=`` or ``]``."""
        t = self.text
        parts: list[str] = []
        while i < self.n:
            i = self._skip(i, newlines=False)
            if t[i] in "\"'":
                s, i = self._string(i)
                parts.append(s)
            else:
                m = re.compile(r"[A-Za-z0-9_\-]+").match(t, i)
                if not m:
                    break
                parts.append(m.group())
                i = m.end()
            i = self._skip(i, newlines=False)
            if i < self.n and t[i] == ".":
                i += 1
                continue
            break
        return parts, i

    def _resolve(self, names: list[str]) -> Key:
        out: list[str | int] = []
        for k, part in enumerate(names):
            out.append(part)
            prefix = tuple(names[: k + 1])
            if prefix in self._aot:
                out.append(self._aot[prefix])
        return tuple(out)

    def _scan(self) -> None:
        t = self.text
        table: Key = ()
        i = self._skip(0)
        while i < self.n:
            start = i
            if t.startswith("[[", i):
                names, i = self._key(i + 2)
                prefix = tuple(names)
                self._aot[prefix] = self._aot.get(prefix, -1) + 1
                for k in list(self._aot):
                    if len(k) > len(prefix) and k[: len(prefix)] == prefix:
                        del self._aot[k]
                table = self._resolve(names)
                self.lines.setdefault(table, self._line(start))
                i = t.find("\n", i)
                i = self.n if i < 0 else i
            elif t[i] == "[":
                names, i = self._key(i + 1)
                table = self._resolve(names)
                self.lines.setdefault(table, self._line(start))
                i = t.find("\n", i)
                i = self.n if i < 0 else i
            else:
                parts, i = self._key(i)
                if not parts or i >= self.n or t[i] != "=":
                    j = t.find("\n", i)  # not a key line: skip it
                    i = self.n if j < 0 else j
                else:
                    key = table + tuple(parts)
                    self._record(key, start)
                    i = self._value(i + 1, key)
            i = self._skip(i)

    def _record(self, key: Key, i: int) -> None:
        line = self._line(i)
        for k in range(1, len(key) + 1):  # dotted keys also define their parents
            self.lines.setdefault(key[:k], line)

    def _value(self, i: int, key: Key) -> int:
        t = self.text
        i = self._skip(i, newlines=False)
        if i >= self.n:
            return i
        c = t[i]
        if c in "\"'":
            return self._string(i)[1]
        if c == "[":
            i += 1
            idx = 0
            while True:
                i = self._skip(i)
                if i >= self.n or t[i] == "]":
                    return i + 1
                self.lines.setdefault(key + (idx,), self._line(i))
                i = self._value(i, key + (idx,))
                i = self._skip(i)
                if i < self.n and t[i] == ",":
                    i += 1
                    idx += 1
        if c == "{":
            i += 1
            while True:
                i = self._skip(i)
                if i >= self.n or t[i] == "}":
                    return i + 1
                start = i
                parts, i = self._key(i)
                if not parts or i >= self.n or t[i] != "=":
                    return i + 1
                self._record(key + tuple(parts), start)
                i = self._value(i + 1, key + tuple(parts))
                i = self._skip(i)
                if i < self.n and t[i] == ",":
                    i += 1
        m = re.compile(r"[^,\]\}\n#]*").match(t, i)
        return m.end() if m else i + 1


def _escaped(text: str, j: int) -> bool:
    k = j - 1
    n = 0
    while k >= 0 and text[k] == "\\":
        n += 1
        k -= 1
    return n % 2 == 1


def _key_text(key: Key) -> str:
    out = ""
    for part in key:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + part
    return out


#: Characters of a value quoted in a message (:func:`_show`).
SHOW_LENGTH = 60


def _show(value: Any, limit: int = SHOW_LENGTH) -> str:
    r"""A short, single-line description of a value of the file for messages.

    Strings are quoted as :func:`repr` quotes them (control characters
    escaped: a message never copies one to the terminal) and, like arrays,
    cut at about ``limit`` characters with their length: a value of
    megabytes gives a line of a hundred characters.

    >>> print(_show("\x1b[31m red"))
    a string '\x1b[31m red'
    >>> print(_show([1.5, "a", [2], {}, True]))
    an array [1.5, 'a', [...], {...}, true]
    >>> print(_show([1] * 10**6))
    an array [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, ...] (1000000 items)
    """
    from ..output._text import quote

    if isinstance(value, str):
        return f"a string {quote(value, limit)}"
    if isinstance(value, bool):
        return f"a boolean ({str(value).lower()})"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        shown: list[str] = []
        width = 0
        for item in value:
            if isinstance(item, (list, dict)):
                r = "[...]" if isinstance(item, list) else "{...}"
            elif isinstance(item, str):
                r = quote(item, 20)
            elif isinstance(item, bool):
                r = str(item).lower()
            else:
                r = _plain(repr(item), 20)
            if width + len(r) > limit:
                return f"an array [{', '.join(shown)}, ...] ({len(value)} items)"
            shown.append(r)
            width += len(r) + 2
        return f"an array [{', '.join(shown)}]"
    return _plain(repr(value), limit)


def _plain(text: str, limit: int) -> str:
    """``text`` (a repr) with any non-printable character escaped, cut at ``limit``."""
    out = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text[:limit])
    return out if len(text) <= limit else f"{out}... ({len(text)} characters)"
