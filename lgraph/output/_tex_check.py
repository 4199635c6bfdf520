"""Label text as untrusted input: what it may not contain (control
characters, TeX that reaches files or the shell, defines commands or changes
how TeX reads text), its length and nesting, and how it is quoted in
messages.  Checked before anything parses the text (:mod:`lgraph.output._text`
lays it out)."""

from __future__ import annotations

import re
from collections.abc import Iterator

from .._tolerance import MAX_LABEL_DEPTH, MAX_LABEL_LENGTH

__all__ = ["QUOTE_LENGTH", "check_tex", "quote"]


#: Characters of a text quoted in a message (:func:`quote`).
QUOTE_LENGTH = 60

#: Characters a label must not contain: C0 controls (tab and line breaks too:
#: a label is one line), DEL and C1 controls, lone surrogates, U+FFFE and U+FFFF
#: (of which XML holds none but tab and line breaks, not even as ``&#...;``).
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")

#: A control word as TeX reads it (``@`` counted as a letter, as it is in
#: packages), or a control symbol (a backslash and any one other character).
_CONTROL_WORD = re.compile(r"\\(?:([A-Za-z@]+)|.)", re.S)

#: The environment name after ``\begin``/``\end``: plain characters in braces.
_ENVIRONMENT = re.compile(r"\s*\{([^{}\\]*)\}")

#: Tokens that open and close groups (:data:`MAX_LABEL_DEPTH`).
_GROUP_TOKEN = re.compile(r"\\sqrt\s*\[|\\[A-Za-z]+|\\.|[{}\]]", re.S)

_FILES = "it reads or writes files"
_PROGRAMS = "it runs programs"
_DEFINES = "it defines or changes commands"
_READING = "it changes how TeX reads text or makes commands from text"

#: TeX, LaTeX and package commands a label must not use, by what they do.  The
#: TikZ backend hands label text to TeX unchanged, so these would reach the
#: files and the shell of whoever compiles the figure.  A denylist, since
#: labels may use any document macro (``\vx``, ``\tfrac``); names are whole
#: control words (``\in put`` is ``\in`` and the letters ``put``).
_DENIED: dict[str, str] = {
    name: why
    for why, names in (
        (
            _FILES,
            "input include includeonly endinput InputIfFileExists IfFileExists openin openout "
            "closein closeout read readline write immediate newread newwrite usepackage "
            "RequirePackage RequirePackageWithOptions documentclass LoadClass "
            "LoadClassWithOptions usetikzlibrary usepgflibrary usepgfmodule "
            "usepgfplotslibrary font special shipout includegraphics graphicspath "
            "DeclareGraphicsRule DeclareGraphicsExtensions includepdf includestandalone "
            "includesvg lstinputlisting verbatiminput VerbatimInput BVerbatimInput "
            "LVerbatimInput VerbatimOut verbatimwrite filecontents import subimport inputfrom "
            "includefrom subinputfrom subincludefrom subfile subfileinclude bibliography "
            "addbibresource CatchFileDef CatchFileEdef DTLloaddb DTLloadrawdb csvreader "
            "csvautotabular csvautobooktabular externaldocument addtocontents addcontentsline "
            "makeindex makeglossaries filesize filemoddate filedump mdfivesum "
            "saveimageresource useimageresource tcbinputlisting tcbuselibrary addplot axis "
            "semilogxaxis semilogyaxis loglogaxis polaraxis groupplot",
        ),
        (
            _PROGRAMS,
            "ShellEscape DelayedShellEscape directlua latelua minted mint mintinline "
            "inputminted newminted newmint newmintinline setminted py pyc pys pyv pyb pycon "
            "pycode pyblock pyverbatim pyconsole sympy sympyc sympys sympyblock sympycode "
            "pylab pylabc pylabs pylabblock pylabcode sage sagestr sageplot sagesilent "
            "sageblock sageverbatim sagecommandline gnuplot epstopdfsetup "
            "epstopdfDeclareGraphicsRule",
        ),
        (
            _DEFINES,
            "def edef gdef xdef let futurelet chardef mathchardef countdef dimendef skipdef "
            "muskipdef toksdef newcommand renewcommand providecommand DeclareRobustCommand "
            "DeclareTextCommand DeclareTextCommandDefault ProvideTextCommand "
            "ProvideTextCommandDefault newenvironment renewenvironment NewDocumentCommand "
            "RenewDocumentCommand ProvideDocumentCommand DeclareDocumentCommand "
            "NewExpandableDocumentCommand RenewExpandableDocumentCommand "
            "ProvideExpandableDocumentCommand DeclareExpandableDocumentCommand "
            "NewDocumentEnvironment RenewDocumentEnvironment ProvideDocumentEnvironment "
            "DeclareDocumentEnvironment NewCommandCopy RenewCommandCopy DeclareCommandCopy "
            "NewEnvironmentCopy RenewEnvironmentCopy DeclareEnvironmentCopy newrobustcmd "
            "renewrobustcmd providerobustcmd robustify newif DeclareMathOperator "
            "DeclareUnicodeCharacter newunicodechar everypar everymath everydisplay everyhbox "
            "everyvbox everycr everyjob everyeof output csdef csgdef csedef csxdef cslet "
            "csletcs letcs csundef appto gappto eappto xappto preto gpreto epreto xpreto "
            "csappto csgappto cseappto csxappto cspreto csgpreto csepreto csxpreto apptocmd "
            "pretocmd patchcmd newtcolorbox renewtcolorbox DeclareTColorBox NewTColorBox "
            "RenewTColorBox ProvideTColorBox newtcblisting",
        ),
        (
            _READING,
            "catcode lccode uccode sfcode mathcode delcode endlinechar newlinechar escapechar "
            "makeatletter makeatother ExplSyntaxOn ExplSyntaxOff ProvidesExplPackage "
            "ProvidesExplClass ProvidesExplFile csname endcsname ifcsname begincsname "
            "lastnamedcs scantokens scantextokens string detokenize meaning csstring Uchar "
            "Ucharcat UseName ExpandArgs csuse",
        ),
    )
    for name in names.split()
}

#: Prefixes of denied control words: engine primitives (``\pdfobj file``,
#: ``\XeTeXpdffile`` read files; ``\luaexec`` runs Lua) and TikZ/PGF code
#: (``plot file``, ``\tikzexternalize``, ``\pgfplothandlerrecord``).
_DENIED_PREFIXES = {
    "pdf": "it is a pdfTeX or LuaTeX primitive, some of which read files",
    "XeTeX": "it is a XeTeX primitive, some of which read files",
    "lua": _PROGRAMS,
    "tikz": "it runs TikZ code, which can read and write files",
    "pgf": "it runs PGF code, which can read and write files",
}


def quote(text: str, limit: int = QUOTE_LENGTH) -> str:
    r"""``text`` quoted for a message, escaped as :func:`repr` escapes it.

    A text whose ``repr`` is longer than ``limit`` characters is cut, and its
    length given: a message never copies a control character or a megabyte.

    >>> print(quote("bell\x07"))
    'bell\x07'
    >>> print(quote("x" * 1000, 10))
    'xxxxxxxx'... (1000 characters)
    """
    if len(text) <= limit:
        r = repr(text)
        if len(r) <= limit + 2:
            return r
    out: list[str] = []
    width = 0
    for c in text:
        e = {"\\": "\\\\", "'": "\\'"}.get(c) or (c if c.isprintable() else repr(c)[1:-1])
        if width + len(e) > limit - 2:
            break
        out.append(e)
        width += len(e)
    return "'" + "".join(out) + f"'... ({len(text)} characters)"


def _why_denied(name: str) -> str | None:
    if "@" in name:
        return None if name == "@" else "it is a LaTeX internal, a name with @"
    if name in _DENIED:
        return _DENIED[name]
    return next((why for p, why in _DENIED_PREFIXES.items() if name.startswith(p)), None)


def _commands(text: str) -> Iterator[tuple[int, str, str | None]]:
    r"""``(position, shown, why)`` of each control word of ``text`` (``why``
    None when it may be used); ``\begin{name}``/``\end{name}`` are judged by
    the environment's name, which must be plain characters."""
    for m in _CONTROL_WORD.finditer(text):
        name = m.group(1)
        if not name:  # a control symbol: \{, \\, \,, \$
            continue
        if name in ("begin", "end"):
            env = _ENVIRONMENT.match(text, m.end())
            if env is None:
                why = "it must be followed by an environment name in braces, without commands"
                yield m.start(), f"\\{name}", why
                continue
            yield m.start(), f"\\{name}{{{env.group(1)}}}", _why_denied(env.group(1).rstrip("*"))
        else:
            yield m.start(), f"\\{name}", _why_denied(name)


def check_tex(owner: str, text: str) -> str:
    r"""Refuse TeX that reaches files or the shell, defines commands or
    changes how TeX reads text; returns ``text``.

    Checked on every label (the TikZ backend passes label text to TeX as it
    is): control characters, ``^^`` (TeX reads ``^^5c`` as a backslash), the
    control words of a denylist (``\input``, ``\write``, ``\catcode``,
    ``\def``, ``\csname``, ...; names with ``@``; the prefixes ``pdf``,
    ``XeTeX``, ``lua``, ``tikz``, ``pgf``) and environments of those names
    (``\begin{filecontents}``).  Control words are whole, as TeX reads them:
    ``\in put`` is ``\in`` and the letters ``put``.  Mathematics and document
    macros (``\vx_1``, ``\tfrac12``) stay allowed.  A denylist cannot know
    every package: compile figures from untrusted scene files without shell
    escape (``-no-shell-escape``) and with ``openout_any = p``.

    >>> check_tex("Label", r"$\vx_1 + \tfrac12$")
    '$\\vx_1 + \\tfrac12$'
    >>> check_tex("Label", r"\immediate\write18{rm -rf ~}")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: Label: text must not use the TeX command \immediate (it reads or writes files), ...
    """
    bad = _CONTROL.search(text)
    if bad:
        raise ValueError(
            f"{owner}: text must not contain control characters (labels are one line of "
            f"printable text), got {bad.group()!r} at position {bad.start()} of {quote(text)}"
        )
    i = text.find("^^")
    if i >= 0:
        raise ValueError(
            f"{owner}: text must not contain '^^' (TeX reads ^^5c as a backslash and ^^M "
            f"as a line end), found at position {i} of {quote(text)}"
        )
    for pos, shown, why in _commands(text):
        if why is not None:
            shown = shown if len(shown) <= 40 else shown[:37] + "..."
            raise ValueError(
                f"{owner}: text must not use the TeX command {shown} ({why}), at position "
                f"{pos} of {quote(text)}; labels may use mathematics and document macros, not "
                "commands that reach files or the shell, define commands or change how TeX "
                "reads text"
            )
    return text


def _depth(text: str) -> tuple[int, int]:
    r"""The deepest nesting of groups in ``text`` (:data:`MAX_LABEL_DEPTH`)
    and the position of the group that first reaches it.

    >>> _depth(r"$\sqrt{x^{2}} + \left(\frac{a}{b}\right) \{ \sqrt[3]{y}$")
    (2, 9)
    """
    closers: list[str] = []
    best = where = 0
    for m in _GROUP_TOKEN.finditer(text):
        tok = m.group()
        if tok == "{" or tok == "\\left" or tok.endswith("["):
            closers.append({"{": "}", "\\left": "\\right"}.get(tok, "]"))
            if len(closers) > best:
                best, where = len(closers), m.start()
        elif closers and tok == closers[-1]:
            closers.pop()
    return best, where


def _check_size(owner: str, text: str) -> None:
    """Length and nesting (:data:`MAX_LABEL_LENGTH`, :data:`MAX_LABEL_DEPTH`),
    checked before anything parses ``text``."""
    if len(text) > MAX_LABEL_LENGTH:
        raise ValueError(
            f"{owner}: text must be at most {MAX_LABEL_LENGTH} characters long "
            f"(MAX_LABEL_LENGTH), got {len(text)}: {quote(text)}"
        )
    depth, where = _depth(text)
    if depth > MAX_LABEL_DEPTH:
        raise ValueError(
            f"{owner}: text must not nest groups ({{...}}, \\left...\\right, \\sqrt[...]) more "
            f"than {MAX_LABEL_DEPTH} deep (MAX_LABEL_DEPTH), got {depth} at position {where} "
            f"of {quote(text)}"
        )
