"""The expression graph behind :mod:`lgraph.formula`: hash-consed nodes,
simplification and constant folding while building, and exact symbolic
differentiation whose results share nodes with what they differentiate.

A node is a tuple: ``("const", value)``, ``("var", name)``, ``("bool", flag)``
or an operation on earlier nodes by index (``("mul", 3, 5)``), so the indices
are a topological order and every walk below is a loop over sorted indices (no
recursion, however deep the formula).  Operations are named after the
functions of the language (``sin``, ``min``, ``where``, ...) plus ``add sub mul
div pow neg``, the comparisons ``lt le gt ge eq ne`` and ``and or not``.

>>> g = Graph()
>>> u = g.make("var", "u")
>>> g.make("mul", u, g.const(1.0)) == u, g.nodes[g.make("pow", g.const(2.0), g.const(10.0))]
(True, ('const', 1024.0))
>>> g.nodes[g.diff(g.make("sin", u), "u")]
('cos', 0)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from typing import Any

import attrs
import numpy as np

#: the numpy function of every operation (folding and evaluation use the same)
UFUNCS: dict[str, Callable[..., Any]] = {
    "add": np.add, "sub": np.subtract, "mul": np.multiply, "div": np.divide,
    "pow": np.power, "neg": np.negative,
    "sin": np.sin, "cos": np.cos, "tan": np.tan, "asin": np.arcsin, "acos": np.arccos,
    "atan": np.arctan, "atan2": np.arctan2, "sinh": np.sinh, "cosh": np.cosh,
    "tanh": np.tanh, "asinh": np.arcsinh, "acosh": np.arccosh, "atanh": np.arctanh,
    "exp": np.exp, "log": np.log, "log10": np.log10, "sqrt": np.sqrt, "cbrt": np.cbrt,
    "abs": np.absolute, "sign": np.sign, "floor": np.floor, "min": np.minimum,
    "max": np.maximum, "hypot": np.hypot, "where": np.where,
    "lt": np.less, "le": np.less_equal, "gt": np.greater, "ge": np.greater_equal,
    "eq": np.equal, "ne": np.not_equal,
    "and": np.logical_and, "or": np.logical_or, "not": np.logical_not,
}  # fmt: skip
#: operations whose value is a truth value (only in conditions of ``where``)
BOOLEAN = frozenset({"bool", "lt", "le", "gt", "ge", "eq", "ne", "and", "or", "not"})
LEAVES = frozenset({"const", "var", "bool"})
_LN10 = float(np.log(10.0))

Node = tuple[Any, ...]


class Graph:
    """A hash-consed expression graph: :meth:`make` returns the index of the
    (simplified, folded) node, the same index for the same expression."""

    def __init__(self) -> None:
        self.nodes: list[Node] = []
        self._index: dict[Node, int] = {}
        self._diff: dict[tuple[int, str], int] = {}

    def intern(self, node: Node) -> int:
        """The index of ``node`` as it is (added if new)."""
        key = ("const", node[1].hex()) if node[0] == "const" else node  # -0.0, nan apart
        i = self._index.get(key)
        if i is None:
            i = self._index[key] = len(self.nodes)
            self.nodes.append(node)
        return i

    def const(self, value: float) -> int:
        return self.intern(("const", float(value)))

    def value(self, i: int) -> float | None:
        """The value of a constant node, else None."""
        node = self.nodes[i]
        return node[1] if node[0] == "const" else None

    def make(self, op: str, *args: Any) -> int:
        """The node ``op(*args)``: folded if its operands are constants,
        simplified (``x + 0``, ``x * 1``, ``x * 0``, ``x ^ 1``, ``x ^ 0``,
        ``0 - x``, ``-(-x)``, ``x / 1``, ...) if it can be."""
        if op in LEAVES:
            return self.intern((op, *args))
        nodes = self.nodes
        if all(nodes[a][0] in ("const", "bool") for a in args):
            with np.errstate(all="ignore"):
                r = UFUNCS[op](*(np.float64(nodes[a][1]) for a in args))
            return self.intern(("bool", bool(r))) if op in BOOLEAN else self.const(r)
        s = self._simplified(op, args)
        return self.intern((op, *args)) if s is None else s

    def fold(self, op: str, args: Sequence[int]) -> int:
        """``op(op(a, b), c)...``: min, max, and, or of several operands."""
        out = args[0]
        for a in args[1:]:
            out = self.make(op, out, a)
        return out

    def _simplified(self, op: str, args: tuple[int, ...]) -> int | None:
        nodes, make = self.nodes, self.make
        if op in ("add", "sub", "mul", "div", "pow"):
            a, b = args
            va, vb = self.value(a), self.value(b)
            if (op in ("add", "sub") and vb == 0) or (op in ("mul", "div", "pow") and vb == 1):
                return a
            if op in ("add", "mul") and va == (0 if op == "add" else 1):
                return b
            if (op == "sub" and va == 0) or (op in ("mul", "div") and vb == -1):
                return make("neg", a if vb == -1 else b)
            if op in ("add", "sub") and nodes[b][0] == "neg":  # a + -x is a - x
                return make("sub" if op == "add" else "add", a, nodes[b][1])
            if op == "mul" and (va == 0 or vb == 0):
                return self.const(0.0)
            if op == "mul" and va == -1:
                return make("neg", b)
            if op == "div" and va == 0:
                return a
            return self.const(1.0) if op == "pow" and (vb == 0 or va == 1) else None
        if op == "neg":
            return nodes[args[0]][1] if nodes[args[0]][0] == "neg" else None
        if op == "where":
            c, a, b = args
            if nodes[c][0] == "bool":
                return a if nodes[c][1] else b
            return a if a == b else None
        if op in ("and", "or"):
            for x, y in (args, args[::-1]):
                if nodes[x][0] == "bool":
                    return y if nodes[x][1] == (op == "and") else x
        return None

    def load(self, nodes: Sequence[Node]) -> int:
        """Add the nodes of another graph (a topological list, root last);
        the index of its root here."""
        here: list[int] = []
        for node in nodes:
            if node[0] in LEAVES:
                here.append(self.intern(node))
            else:
                here.append(self.intern((node[0], *(here[a] for a in node[1:]))))
        return here[-1]

    def reachable(self, roots: Iterable[int], numeric: bool = False) -> list[int]:
        """The nodes ``roots`` depend on, in topological (index) order;
        ``numeric``: not the conditions of ``where`` (what derivatives need)."""
        seen: set[int] = set()
        stack = list(roots)
        nodes = self.nodes
        while stack:
            i = stack.pop()
            if i in seen:
                continue
            seen.add(i)
            node = nodes[i]
            if node[0] not in LEAVES:
                stack.extend(node[2:] if numeric and node[0] == "where" else node[1:])
        return sorted(seen)

    def export(self, root: int) -> tuple[Node, ...]:
        """The nodes ``root`` depends on as a topological tuple, root last."""
        order = self.reachable([root])
        new = {old: k for k, old in enumerate(order)}
        nodes = self.nodes
        return tuple(
            nodes[i] if nodes[i][0] in LEAVES else (nodes[i][0], *(new[a] for a in nodes[i][1:]))
            for i in order
        )

    def diff(self, root: int, var: str) -> int:
        """The node of the partial derivative of ``root`` by the variable ``var``."""
        memo = self._diff
        for i in self.reachable([root], numeric=True):
            if (i, var) not in memo:
                memo[i, var] = self._rule(i, var)
        return memo[root, var]

    def with_derivatives(self, roots: list[int], variables: Sequence[str], order: int) -> list[int]:
        """``roots``, then (``order >= 1``) their first derivatives by each
        variable in turn, then (``order == 2``) the second ones by each pair
        ``i <= j`` of variables in turn."""
        first = [[self.diff(r, v) for r in roots] for v in variables] if order else []
        out = roots + [d for ds in first for d in ds]
        for i in range(len(variables) if order == 2 else 0):
            for v in variables[i:]:
                out += [self.diff(d, v) for d in first[i]]
        return out

    def _rule(self, i: int, var: str) -> int:
        node = self.nodes[i]
        op, args = node[0], node[1:]
        zero = self.const(0.0)
        if op == "const":
            return zero
        if op == "var":
            return self.const(1.0 if node[1] == var else 0.0)
        numeric = args[1:] if op == "where" else args
        d = [self._diff[a, var] for a in numeric]
        if all(self.value(x) == 0 for x in d):
            return zero
        m, c = self.make, self.const
        a, da = args[0], d[0]
        b, db = (args[1], d[1]) if len(d) == 2 and op != "where" else (None, None)
        if op in ("add", "sub"):
            return m(op, da, db)
        if op == "neg":
            return m("neg", da)
        if op == "mul":
            return m("add", m("mul", da, b), m("mul", a, db))
        if op == "div":  # (a' - (a/b) b') / b
            return m("div", m("sub", da, m("mul", i, db)), b)
        if op == "pow":
            vb = self.value(b)
            if vb is not None:  # b a^(b-1) a'
                return m("mul", m("mul", b, m("pow", a, c(vb - 1.0))), da)
            log_term = m("mul", db, m("log", a))
            return m("mul", i, m("add", log_term, m("div", m("mul", b, da), a)))
        if op in ("atan2", "hypot"):
            if op == "hypot":  # (a a' + b b') / hypot(a, b)
                return m("div", m("add", m("mul", a, da), m("mul", b, db)), i)
            square = m("add", m("pow", a, c(2.0)), m("pow", b, c(2.0)))  # atan2(y=a, x=b)
            return m("div", m("sub", m("mul", b, da), m("mul", a, db)), square)
        if op in ("min", "max"):
            return m("where", m("le" if op == "min" else "ge", a, b), da, db)
        if op == "where":
            return m("where", a, d[0], d[1])
        return self._chain(op, a, da, i)

    def _chain(self, op: str, a: int, da: int, i: int) -> int:
        """``f(a)' = f'(a) a'`` for the functions of one argument (``i`` is ``f(a)``)."""
        m, c = self.make, self.const
        one = c(1.0)
        if op in ("sign", "floor"):
            return c(0.0)
        if op in _SIMPLE:
            outer = m(_SIMPLE[op], a)
            return m("mul", m("neg", outer) if op == "cos" else outer, da)
        if op in ("tan", "tanh"):  # 1 + tan^2, 1 - tanh^2
            return m("mul", m("add" if op == "tan" else "sub", one, m("pow", i, c(2.0))), da)
        if op == "exp":
            return m("mul", i, da)
        if op == "log":
            return m("div", da, a)
        if op == "log10":
            return m("div", da, m("mul", a, c(_LN10)))
        if op == "sqrt":
            return m("div", da, m("mul", c(2.0), i))
        if op == "cbrt":
            return m("div", da, m("mul", c(3.0), m("pow", i, c(2.0))))
        square = m("pow", a, c(2.0))
        if op in ("asin", "acos"):
            q = m("div", da, m("sqrt", m("sub", one, square)))
            return m("neg", q) if op == "acos" else q
        if op == "asinh":
            return m("div", da, m("sqrt", m("add", square, one)))
        if op == "acosh":
            return m("div", da, m("sqrt", m("sub", square, one)))
        if op == "atan":
            return m("div", da, m("add", one, square))
        if op == "atanh":
            return m("div", da, m("sub", one, square))
        raise AssertionError(f"no derivative rule for {op!r}")  # pragma: no cover


#: f' of the functions whose derivative is another function (cos: its negative)
_SIMPLE = {"sin": "cos", "cos": "sin", "sinh": "cosh", "cosh": "sinh", "abs": "sign"}


def _number(v: float) -> tuple[str, int]:
    if math.isfinite(v) and v == int(v) and abs(v) < 1e16 and repr(v) != "-0.0":
        text = str(int(v))
    else:
        text = repr(v)
    return text, 7 if text.startswith("-") else 9


_INFIX = {"add": (" + ", 5), "sub": (" - ", 5), "mul": ("*", 6), "div": ("/", 6)}
_INFIX |= {"and": (" and ", 2), "or": (" or ", 1)}
_INFIX |= {
    op: (f" {s} ", 4)
    for op, s in zip(("lt", "le", "gt", "ge", "eq", "ne"), "< <= > >= == !=".split())
}


def render(nodes: Sequence[Node]) -> str:
    """Infix text of a graph (a topological tuple, root last) that parses back to it."""
    out: list[tuple[str, int]] = []
    flat: dict[int, list[str]] = {}  # min / max of more than two arguments

    def paren(k: int, wrap: bool) -> str:
        return f"({out[k][0]})" if wrap else out[k][0]

    for i, node in enumerate(nodes):
        op, args = node[0], node[1:]
        if op == "const":
            out.append(_number(node[1]))
        elif op == "var":
            out.append((node[1], 9))
        elif op == "bool":
            out.append(("(0 < 1)" if node[1] else "(1 < 0)", 9))
        elif op in _INFIX:
            symbol, p = _INFIX[op]
            a, b = args
            out.append((f"{paren(a, out[a][1] < p)}{symbol}{paren(b, out[b][1] <= p)}", p))
        elif op == "pow":
            a, b = args
            out.append((f"{paren(a, out[a][1] <= 8)}^{paren(b, out[b][1] < 7)}", 8))
        elif op == "neg":
            out.append((f"-{paren(args[0], out[args[0]][1] < 7)}", 7))
        elif op == "not":
            out.append((f"not {paren(args[0], out[args[0]][1] < 3)}", 3))
        else:
            parts = [out[k][0] for k in args]
            if op in ("min", "max"):
                if nodes[args[0]][0] == op:  # min(min(a, b), c) is min(a, b, c)
                    parts = [*flat[args[0]], parts[1]]
                flat[i] = parts
            out.append((f"{op}({', '.join(parts)})", 9))
    return out[-1][0]


@attrs.frozen(eq=False)
class Program:
    """What :func:`compile_formulas` returns: ``f(*args) -> list of arrays``.

    ``program_length`` is its number of numpy calls (subexpressions shared
    between the formulas and their derivatives are computed once).
    """

    variables: tuple[str, ...]
    n_outputs: int
    _code: tuple[tuple[Callable[..., Any], int, tuple[int, ...], tuple[int, ...]], ...]
    _initial: tuple[Any, ...] = attrs.field(repr=False)
    _outputs: tuple[int, ...] = attrs.field(repr=False)

    @property
    def program_length(self) -> int:
        return len(self._code)

    def __call__(self, *args: Any) -> list[np.ndarray]:
        nv = len(self.variables)
        if len(args) != nv:
            names = ", ".join(self.variables)
            raise TypeError(f"the formulas take {nv} arguments ({names}), got {len(args)}")
        arrays = [np.asarray(a, dtype=np.float64) for a in args]
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
        regs = list(self._initial)
        regs[:nv] = arrays
        with np.errstate(all="ignore"):
            for func, out, ins, free in self._code:
                regs[out] = func(*[regs[k] for k in ins])
                for k in free:
                    regs[k] = None
        results: list[np.ndarray] = []
        for n, k in enumerate(self._outputs):
            x = regs[k]
            if (
                k < nv
                or k in self._outputs[:n]
                or not isinstance(x, np.ndarray)
                or x.shape != shape
            ):
                x = np.array(np.broadcast_to(x, shape), dtype=np.float64)  # own, full, writable
            results.append(x)
        return results


def program(graph: Graph, roots: Sequence[int], variables: tuple[str, ...]) -> Program:
    """The numpy calls evaluating the nodes ``roots`` of ``graph`` (each node
    once, a register dropped after its last use) as a :class:`Program`."""
    nodes, reg = graph.nodes, {}
    initial: list[Any] = [None] * len(variables)
    for k, name in enumerate(variables):
        reg[graph.intern(("var", name))] = k
    code: list[tuple[Any, int, tuple[int, ...]]] = []
    for i in graph.reachable(roots):
        op, args = nodes[i][0], nodes[i][1:]
        if op == "var":
            continue
        reg[i] = len(initial)
        if op in LEAVES:
            initial.append(np.bool_(args[0]) if op == "bool" else np.float64(args[0]))
            continue
        initial.append(None)
        func = UFUNCS[op]
        if op == "pow" and graph.value(args[1]) in _POWERS:  # as numpy's ``x ** c``
            func, args = _POWERS[graph.value(args[1])], args[:1]
        code.append((func, reg[i], tuple(reg[a] for a in args)))
    outputs = tuple(reg[r] for r in roots)
    last = {k: n for n, (_, _, ins) in enumerate(code) for k in ins}
    steps = tuple(
        (f, out, ins, tuple(k for k in set(ins) if last[k] == n and k not in outputs))
        for n, (f, out, ins) in enumerate(code)
    )
    return Program(variables, len(roots), steps, tuple(initial), outputs)


_POWERS = {2.0: np.square, 0.5: np.sqrt, -1.0: np.reciprocal}
