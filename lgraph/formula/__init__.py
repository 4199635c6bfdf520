"""Formulas: the small, safe expression language of scene files.

A formula such as ``"(1 + v/2*cos(u/2)) * cos(u)"`` is parsed with Python's
``ast`` and checked against a strict whitelist; nothing in the text is ever
executed (no ``eval``, ``exec`` or ``compile``).  It is compiled into a
hash-consed expression graph (equal subexpressions shared, constants folded,
trivial terms simplified, exact symbolic derivatives) and evaluated as a list
of numpy ufunc calls on whole arrays.

The language:

* numbers (``2``, ``0.5``, ``1e-3``), ``pi``, ``e``, the variables and the
  named constants the caller gives;
* ``+ - * /``, powers ``^`` or ``**`` (right-associative, binding tighter
  than unary minus: ``-x^2`` is ``-(x^2)``, ``2^3^2`` is 512), parentheses;
* the functions ``FUNCTIONS``: ``atan2(y, x)``, ``hypot(a, b)``,
  ``min``/``max`` of two or more arguments (elementwise), ``where(cond, a,
  b)``, the others of one argument;
* comparisons ``< <= > >= == !=`` and ``and``, ``or``, ``not`` only in the
  condition of ``where``.

Limits: ``MAX_FORMULA_LENGTH`` characters, parentheses nested at most
``MAX_FORMULA_DEPTH`` deep, ``MAX_FORMULA_NODES`` terms.  Any problem
is a :class:`FormulaError` that says what is wrong, where, and what is allowed.

>>> import numpy as np
>>> f = formula("x^2 - y^2", ("x", "y"))
>>> f(np.array([3.0, 1.0]), 2.0).tolist()
[5.0, -3.0]
>>> str(f.derivative("x")), formula("2*pi*r", constants={"r": 0.5}).value()
('2*x', 3.141592653589793)
"""

from __future__ import annotations

import ast
import keyword
import math
import numbers
import sys
import unicodedata
import warnings
from collections.abc import Callable, Mapping, Sequence
from types import MappingProxyType
from typing import Any

import attrs
import numpy as np

from ._graph import Graph, Node, program, render

__all__ = ["Formula", "FormulaError", "formula", "compile_formulas", "FUNCTIONS"]

#: the functions a formula may call, with their number of arguments (-2: two or more)
_ARITY = {f: 1 for f in "sin cos tan asin acos atan".split()} | {"atan2": 2}
_ARITY |= {f: 1 for f in "sinh cosh tanh asinh acosh atanh exp log log10 sqrt cbrt".split()}
_ARITY |= {"abs": 1, "sign": 1, "floor": 1, "min": -2, "max": -2, "hypot": 2, "where": 3}
FUNCTIONS: tuple[str, ...] = tuple(_ARITY)
MAX_FORMULA_LENGTH = 4000
MAX_FORMULA_DEPTH = 50
MAX_FORMULA_NODES = 1000

_NAMED = {"pi": math.pi, "e": math.e}
_BINARY = {ast.Add: "add", ast.Sub: "sub", ast.Mult: "mul", ast.Div: "div", ast.Pow: "pow"}
_COMPARE = {ast.Lt: "lt", ast.LtE: "le", ast.Gt: "gt", ast.GtE: "ge", ast.Eq: "eq"}
_COMPARE[ast.NotEq] = "ne"
_SYMBOLS = {ast.Mod: "%", ast.FloorDiv: "//", ast.MatMult: "@", ast.BitAnd: "&", ast.BitOr: "|"}
_SYMBOLS |= {ast.LShift: "<<", ast.RShift: ">>", ast.Invert: "~", ast.In: "in", ast.Is: "is"}
_SYMBOLS |= {ast.NotIn: "not in", ast.IsNot: "is not"}
_REFUSED = {  # "... are not allowed"
    ast.Attribute: "attributes", ast.Subscript: "subscripts (indexing)", ast.Slice: "slices",
    ast.Lambda: "lambdas", ast.JoinedStr: "f-strings", ast.NamedExpr: "assignments (:=)",
    ast.Tuple: "tuples", ast.List: "lists", ast.Dict: "dicts", ast.Set: "sets",
    ast.ListComp: "comprehensions", ast.SetComp: "comprehensions",
    ast.DictComp: "comprehensions", ast.GeneratorExp: "comprehensions",
    ast.Starred: "starred arguments (*args)",
    ast.IfExp: "conditional expressions (use where(cond, a, b))",
}  # fmt: skip
_OPERATORS = "the operators are + - * / ^ (or **)"
_CONDITION = "comparisons are only allowed in the condition of where(cond, a, b)"
_NOT_CONDITION = (
    "the condition of where(cond, a, b) must be a comparison such as u < v "
    "(combined with and, or, not)"
)


def _short(text: str, limit: int = 40) -> str:
    """``text`` with non-printable characters escaped, cut to ``limit`` characters."""
    pieces = [ch if ch.isprintable() else repr(ch)[1:-1] for ch in text[: limit + 1]]
    if len(text) <= limit and sum(map(len, pieces)) <= limit:
        return "".join(pieces)
    ends = np.cumsum([len(p) for p in pieces])
    return "".join(pieces[: int(np.searchsorted(ends, limit - 3, side="right"))]) + "..."


class FormulaError(ValueError):
    """A formula that is not allowed or cannot be evaluated.

    Attributes: ``text`` (the formula), ``column`` (0-based in ``text``, or
    None), ``reason`` (what is wrong and what is allowed) and ``excerpt`` (the
    offending part, shortened and escaped).

    >>> try:
    ...     formula("1 + foo(u)", ("u",))
    ... except FormulaError as exc:
    ...     print(exc.column, exc.excerpt, exc.reason[:31])
    4 foo unknown function 'foo'; allowed
    """

    def __init__(self, reason: str, text: str, column: int | None = None, end: int | None = None):
        self.reason, self.text, self.column, self._end = reason, text, column, end
        self.excerpt: str | None = None
        if column is not None:  # the offending part, else what comes before it
            segment = text[column:end] if end is not None and end > column else text[column:]
            self.excerpt = _short(segment.strip() or text[max(0, column - 20) :].strip())
        where = "" if column is None else f" at column {column + 1} of '{self.excerpt}'"
        super().__init__(reason + where)

    def __reduce__(self) -> Any:
        return (FormulaError, (self.reason, self.text, self.column, self._end))


class _Source:
    """The text as ``ast.parse`` reads it (``^`` as ``**``, blanks as spaces),
    with the way back to columns of the original."""

    def __init__(self, text: str) -> None:
        if not isinstance(text, str):
            raise TypeError(f"formula: text must be a string, got {type(text).__name__}")
        self.text = text
        if len(text) > MAX_FORMULA_LENGTH:
            msg = f"formula too long: {len(text)} characters, at most {MAX_FORMULA_LENGTH}"
            raise FormulaError(msg, text)
        clean = text.translate({9: 32, 10: 32, 13: 32})  # TOML multi-line strings
        depth = 0
        for i, ch in enumerate(clean):
            if ch in "([{":
                depth += 1
                if depth > MAX_FORMULA_DEPTH:
                    msg = f"parentheses nested too deeply (more than {MAX_FORMULA_DEPTH})"
                    raise FormulaError(msg, text, i)
            elif ch in ")]}":
                depth -= 1
            elif not ch.isprintable() or ch in "#\\":
                what = "control" if unicodedata.category(ch) == "Cc" else "non-printable"
                reason = {"#": "comments (#) are not allowed", "\\": "backslashes are not allowed"}
                msg = reason.get(ch, f"{what} character {ch!r} is not allowed")
                raise FormulaError(msg, text, i, i + 1)
        if not clean.strip():
            raise FormulaError("the formula is empty", text)
        lead = len(clean) - len(clean.lstrip())  # eval mode refuses an indent
        self.code = clean[lead:].replace("^", "**")
        self._orig = [i for i, ch in enumerate(clean) if i >= lead for _ in range(1 + (ch == "^"))]
        self._orig.append(len(text))
        # ast columns count UTF-8 bytes: their characters
        self._char = [j for j, ch in enumerate(self.code) for _ in ch.encode()] + [len(self.code)]

    def column(self, code_column: int, byte: bool = True) -> int:
        """The column of the original text of a column of ``code``."""
        if byte:
            code_column = self._char[min(code_column, len(self._char) - 1)]
        return self._orig[max(0, min(code_column, len(self._orig) - 1))]

    def error(self, reason: str, node: Any) -> FormulaError:
        start = self.column(node.col_offset)
        end = self.column(node.end_col_offset - 1) + 1 if node.end_col_offset else None
        return FormulaError(reason, self.text, start, end)

    def parse(self) -> ast.expr:
        try:
            with warnings.catch_warnings():  # "invalid decimal literal" (1if): an error
                warnings.simplefilter("error")
                tree = ast.parse(self.code, mode="eval")
        except SyntaxError as exc:
            offset = exc.offset or len(self.code) + 1  # 0: at the end
            start = self.column(offset - 1, byte=False)
            end = exc.end_offset if exc.end_offset and exc.end_offset > offset else 0
            end_col = self.column(end - 2, byte=False) + 1 if end else None
            msg = _short(str(exc.msg), 100) + ("" if exc.offset else " (at the end)")
            raise FormulaError(f"syntax error: {msg}", self.text, start, end_col) from None
        except (RecursionError, MemoryError):
            raise FormulaError("formula too deeply nested to parse", self.text) from None
        except (ValueError, Warning) as exc:
            raise FormulaError(f"cannot parse: {_short(str(exc), 100)}", self.text) from None
        n = sum(isinstance(node, ast.expr) for node in ast.walk(tree))
        if n > MAX_FORMULA_NODES:
            msg = f"formula too complex: {n} terms (numbers, names, operations), at most "
            raise FormulaError(f"{msg}{MAX_FORMULA_NODES}", self.text)
        return tree.body


def _names(names: Sequence[str], limit: int = 12) -> str:
    return ", ".join([_short(n, 20) for n in names[:limit]] + ["..."] * (len(names) > limit))


class _Builder:
    """The checks of the whitelist and the graph of a parsed formula, in one
    walk with an explicit stack (no recursion, however deep the text nests)."""

    def __init__(self, source: _Source, variables: Sequence[str], constants: Mapping[str, float]):
        self.source, self.variables, self.constants = source, variables, constants
        self.graph = Graph()

    def _children(self, node: ast.AST, cond: bool) -> list[tuple[ast.AST, bool]]:
        """The operands of ``node`` (each with: is it a condition), after the checks."""
        err = self.source.error
        kind = type(node)
        if kind in _REFUSED:
            raise err(f"{_REFUSED[kind]} are not allowed", node)
        if isinstance(node, ast.Constant):
            v = node.value
            what = {str: "strings", bytes: "bytes", complex: "complex numbers"}.get(type(v))
            if what or not isinstance(v, (int, float)) or isinstance(v, bool):
                raise err(f"{what or repr(v)} {'are' if what else 'is'} not allowed", node)
        elif isinstance(node, ast.Name):
            if node.id not in self.variables and node.id not in self.constants:
                if node.id in _ARITY:
                    raise err(f"'{node.id}' is a function; call it as {node.id}(...)", node)
                if node.id not in _NAMED:
                    v = f"the variables are {_names(self.variables)} and " if self.variables else ""
                    c = _names(["pi", "e", *self.constants])
                    msg = f"unknown name '{_short(node.id, 30)}'; {v or 'no variables; '}"
                    raise err(f"{msg}the constants {c}", node)
        elif isinstance(node, ast.UnaryOp):
            if type(node.op) in _SYMBOLS:
                raise err(f"'{_SYMBOLS[type(node.op)]}' is not allowed; {_OPERATORS}", node)
            if isinstance(node.op, ast.Not):
                if not cond:
                    raise err(f"'not': {_CONDITION}", node)
                return [(node.operand, True)]
            if not cond:
                return [(node.operand, False)]
        elif isinstance(node, ast.BinOp):
            if type(node.op) not in _BINARY:
                symbol = _SYMBOLS.get(type(node.op), type(node.op).__name__)
                raise err(f"'{symbol}' is not allowed; {_OPERATORS}", node)
            if not cond:
                return [(node.left, False), (node.right, False)]
        elif isinstance(node, ast.Compare):
            for op in node.ops:
                if type(op) not in _COMPARE:
                    msg = "the comparisons are < <= > >= == !="
                    raise err(f"'{_SYMBOLS.get(type(op))}' is not allowed; {msg}", node)
            if not cond:
                raise err(_CONDITION, node)
            return [(node.left, False)] + [(c, False) for c in node.comparators]
        elif isinstance(node, ast.BoolOp):
            if not cond:
                raise err(f"'and', 'or': {_CONDITION}", node)
            return [(v, True) for v in node.values]
        elif isinstance(node, ast.Call):
            return self._call(node, cond)
        else:
            raise err(f"{type(node).__name__} expressions are not allowed", node)
        if cond:
            raise err(_NOT_CONDITION, node)
        return []

    def _call(self, node: ast.Call, cond: bool) -> list[tuple[ast.AST, bool]]:
        err = self.source.error
        allowed = f"allowed: {', '.join(FUNCTIONS)}"
        if not isinstance(node.func, ast.Name):
            if type(node.func) in _REFUSED:  # (lambda: 1)(), os.system(...)
                raise err(f"{_REFUSED[type(node.func)]} are not allowed", node.func)
            raise err(f"only the functions {', '.join(FUNCTIONS)} can be called", node)
        name = node.func.id
        if name not in _ARITY:
            what = "variable" if name in self.variables else "constant"
            if name in self.variables or name in self.constants or name in _NAMED:
                raise err(f"'{name}' is a {what}, not a function; {allowed}", node.func)
            raise err(f"unknown function '{_short(name, 30)}'; {allowed}", node.func)
        for a in node.args:
            if isinstance(a, ast.Starred):
                raise err(f"{_REFUSED[ast.Starred]} are not allowed", a)
        if node.keywords:
            raise err("keyword arguments are not allowed", node.keywords[0])
        n, arity = len(node.args), _ARITY[name]
        if n != arity and not (arity < 0 and n >= -arity):
            want = f"at least {-arity} arguments" if arity < 0 else f"{arity} argument"
            want += "s" * (arity > 1) + " (cond, a, b)" * (name == "where")
            raise err(f"{name} takes {want}, got {n}", node)
        if cond:
            raise err(_NOT_CONDITION, node)
        return [(a, name == "where" and k == 0) for k, a in enumerate(node.args)]

    def _node(self, node: Any, kids: list[int]) -> int:
        g = self.graph
        if isinstance(node, ast.Constant):
            big = isinstance(node.value, int) and node.value > sys.float_info.max
            if big or not math.isfinite(value := float(node.value)):
                raise self.source.error("the number is too large (not a finite float64)", node)
            return g.const(value)
        if isinstance(node, ast.Name):
            if node.id in self.variables:
                return g.make("var", node.id)
            return g.const(self.constants.get(node.id, _NAMED.get(node.id)))
        if isinstance(node, ast.UnaryOp):
            op = {ast.USub: "neg", ast.Not: "not"}.get(type(node.op))
            return g.make(op, kids[0]) if op else kids[0]
        if isinstance(node, ast.BinOp):
            return g.make(_BINARY[type(node.op)], *kids)
        if isinstance(node, ast.Compare):
            parts = [g.make(_COMPARE[type(o)], a, b) for o, a, b in zip(node.ops, kids, kids[1:])]
            kids, node = parts, ast.BoolOp(op=ast.And())
        if isinstance(node, ast.BoolOp):
            op = "and" if isinstance(node.op, ast.And) else "or"
        else:
            op = node.func.id
            if op not in ("min", "max"):
                return g.make(op, *kids)
        return g.fold(op, kids)

    def build(self, root: ast.expr) -> tuple[Node, ...]:
        done: dict[int, int] = {}
        stack: list[tuple[Any, bool, list[Any] | None]] = [(root, False, None)]
        while stack:
            node, cond, kids = stack.pop()
            if kids is None:
                children = self._children(node, cond)
                stack.append((node, cond, [c for c, _ in children]))
                stack.extend((c, k, None) for c, k in reversed(children))
                continue
            i = done[id(node)] = self._node(node, [done[id(k)] for k in kids])
            value = self.graph.value(i)
            if value is not None and not math.isfinite(value):
                segment = self.source.error("", node).excerpt or ""
                raise self.source.error(f"'{segment}' is not a finite number", node)
        return self.graph.export(done[id(root)])


def _check_name(name: Any, what: str) -> str:
    ok = isinstance(name, str) and name.isidentifier() and not keyword.iskeyword(name)
    if not ok or name.startswith("_") or unicodedata.normalize("NFKC", name) != name:
        raise ValueError(f"formula: a {what} needs a name like u or r_1, got {name!r}")
    if name in _ARITY or name in _NAMED:
        raise ValueError(f"formula: {name!r} cannot name a {what}: it is a function or pi / e")
    return name


def _variables(value: Any) -> tuple[str, ...]:
    if isinstance(value, str):
        raise ValueError(f"formula: variables must be a sequence of names, got {value!r}")
    return tuple(_check_name(v, "variable") for v in value)


def _constants(value: Any) -> Mapping[str, float]:
    out = {}
    for name, v in dict(value or {}).items():
        if not isinstance(v, numbers.Real) or isinstance(v, bool) or not math.isfinite(v):
            raise ValueError(f"formula: constant {name!r} must be a finite number, got {v!r}")
        out[_check_name(name, "constant")] = float(v)
    return MappingProxyType(out)


@attrs.frozen(eq=False, repr=False)
class Formula:
    """A checked formula of ``variables`` (see :func:`formula`).

    Calling it evaluates it on arrays (one per variable, broadcast together);
    :meth:`derivative` is its exact partial derivative, another Formula.

    >>> f = Formula("(1 + v/2*cos(u/2)) * cos(u)", ("u", "v"))
    >>> float(f(0.0, 1.0)), sorted(f.names), f.is_constant
    (1.5, ['u', 'v'], False)
    >>> print(f.derivative("v"))
    0.5*cos(u/2)*cos(u)
    """

    _source: str | None = attrs.field(alias="text")
    variables: tuple[str, ...] = attrs.field(default=(), converter=_variables)
    constants: Mapping[str, float] = attrs.field(default=None, converter=_constants)
    _nodes: tuple[Node, ...] = attrs.field(init=False)
    _cache: dict[str, Any] = attrs.field(init=False, factory=dict)

    def __attrs_post_init__(self) -> None:
        names = [*self.variables, *self.constants]
        if len(set(names)) < len(names):
            raise ValueError(f"formula: variables and constants need different names, got {names}")
        source = _Source(self._source)  # type: ignore[arg-type]
        nodes = _Builder(source, self.variables, self.constants).build(source.parse())
        object.__setattr__(self, "_nodes", nodes)

    @classmethod
    def _of(cls, nodes: tuple[Node, ...], variables: Any, constants: Any) -> Formula:
        f = cls.__new__(cls)
        values = {"_source": None, "variables": variables, "constants": constants}
        for name, v in (values | {"_nodes": nodes, "_cache": {}}).items():
            object.__setattr__(f, name, v)
        return f

    @property
    def text(self) -> str:
        """The formula as written (a derivative: as ``str`` writes it)."""
        return self._source if self._source is not None else str(self)

    def __str__(self) -> str:
        if "str" not in self._cache:
            self._cache["str"] = render(self._nodes)
        return self._cache["str"]

    def __repr__(self) -> str:
        c = f", constants={dict(self.constants)!r}" if self.constants else ""
        return f"Formula({self.text!r}, variables={self.variables!r}{c})"

    def __reduce__(self) -> Any:
        nodes = self._nodes if self._source is None else None
        return (_restore, (self._source, self.variables, dict(self.constants), nodes))

    @property
    def names(self) -> frozenset[str]:
        """The variables the formula uses (after simplification: ``u*0`` uses none)."""
        return frozenset(n[1] for n in self._nodes if n[0] == "var")

    @property
    def is_constant(self) -> bool:
        """Whether the formula uses no variable."""
        return self._nodes[-1][0] == "const"

    def value(self) -> float:
        """The value of a constant formula (``"2*pi"``)."""
        if not self.is_constant:
            names = ", ".join(sorted(self.names))
            raise FormulaError(f"not a constant: the formula uses {names}", self.text)
        return float(self._nodes[-1][1])

    def derivative(self, variable: str) -> Formula:
        """The exact partial derivative by ``variable``, simplified.

        >>> print(formula("sin(u)^2 + u*v", ("u", "v")).derivative("u"))
        2*sin(u)*cos(u) + v
        """
        if variable not in self.variables:
            names = ", ".join(self.variables) or "none"
            raise ValueError(f"Formula.derivative: use one of {names}, not {variable!r}")
        g = Graph()
        d = g.diff(g.load(self._nodes), variable)
        return Formula._of(g.export(d), self.variables, self.constants)

    def __call__(self, *args: Any) -> np.ndarray:
        program = self._cache.get("program")
        if program is None:
            program = self._cache["program"] = compile_formulas([self])
        return program(*args)[0]


def _restore(text: str | None, variables: Any, constants: dict, nodes: Any) -> Formula:
    if nodes is None:
        return Formula(text, variables, constants)
    return Formula._of(nodes, tuple(variables), MappingProxyType(constants))


def formula(
    text: str, variables: Sequence[str] = (), constants: Mapping[str, float] | None = None
) -> Formula:
    """The :class:`Formula` ``text`` of ``variables`` and named ``constants``.

    Raises :class:`FormulaError` for anything outside the language (the
    module's docstring), ``ValueError`` for a bad variable or constant name.

    >>> formula("where(u < 0, -u, u^2)", ["u"])([-2.0, 3.0]).tolist()
    [2.0, 9.0]
    >>> formula("u.__class__", ["u"])
    Traceback (most recent call last):
    ...
    lgraph.formula.FormulaError: attributes are not allowed at column 1 of 'u.__class__'
    """
    return Formula(text, variables, constants)


def compile_formulas(
    formulas: Sequence[Formula], derivatives: int = 0
) -> Callable[..., list[np.ndarray]]:
    """One program evaluating ``formulas`` (all of the same variables) and,
    with ``derivatives`` 1 or 2, their first and second partial derivatives.

    The program returns a list of arrays of the broadcast shape of its
    arguments: the values of the formulas; then (``derivatives >= 1``) for each
    variable in order the first partial derivatives of all formulas; then
    (``derivatives == 2``) for each pair ``i <= j`` of variables in order
    (``uu, uv, vv``) the second ones.  Subexpressions shared between the
    formulas and their derivatives are computed once; the program's
    ``program_length`` is its number of numpy calls.

    >>> f = compile_formulas([formula("u*v", ("u", "v")), formula("u", ("u", "v"))], 1)
    >>> [float(x) for x in f(2.0, 3.0)], f.program_length
    ([6.0, 2.0, 3.0, 1.0, 2.0, 0.0], 1)
    """
    formulas = list(formulas)
    if not formulas or not all(isinstance(f, Formula) for f in formulas):
        raise TypeError(f"compile_formulas: formulas must be Formula objects, got {formulas!r}")
    variables = formulas[0].variables
    if any(f.variables != variables for f in formulas):
        got = sorted({f.variables for f in formulas})
        raise ValueError(f"compile_formulas: the formulas must have the same variables, got {got}")
    if derivatives not in (0, 1, 2):
        raise ValueError(f"compile_formulas: derivatives must be 0, 1 or 2, got {derivatives!r}")
    g = Graph()
    roots = [g.load(f._nodes) for f in formulas]
    return program(g, g.with_derivatives(roots, variables, derivatives), variables)
