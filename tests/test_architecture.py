"""The package's import graph has no cycles (issue #12).

Every ``import`` inside lgraph counts, at module level or inside a function;
imports under ``if TYPE_CHECKING:`` (type hints only) do not.  Any cycle fails
this test.  With the type-only imports counted too, the graph has no cycles
either (issue #30; :data:`TYPE_ONLY_CYCLES` would list one with its reason).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "lgraph"


def _module_name(path: Path) -> str:
    parts = list(path.with_suffix("").relative_to(PACKAGE.parent).parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _type_checking_lines(tree: ast.AST) -> set[int]:
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If):
            test = node.test
            name = getattr(test, "id", None) or getattr(test, "attr", None)
            if name == "TYPE_CHECKING":
                for sub in node.body:
                    lines.update(range(sub.lineno, (sub.end_lineno or sub.lineno) + 1))
    return lines


def import_graph(type_only: bool = False) -> dict[str, set[str]]:
    """Module -> the lgraph modules it imports (function-level imports included;
    with ``type_only``, the imports under ``if TYPE_CHECKING:`` too)."""
    files = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in files.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        hints = set() if type_only else _type_checking_lines(tree)
        deps: set[str] = set()
        for node in ast.walk(tree):
            if getattr(node, "lineno", None) in hints:
                continue
            targets: list[str] = []
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
                    base = base[: len(base) - (node.level - 1)]
                    module = ".".join(base + ([node.module] if node.module else []))
                else:
                    module = node.module or ""
                targets = [module] + [f"{module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            deps.update(t for t in targets if t in files and t != name)
        graph[name] = deps
    return graph


def strongly_connected(graph: dict[str, set[str]]) -> list[set[str]]:
    """Components of more than one module (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    out: list[set[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = set()
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        comp.add(w)
                        if w == v:
                            break
                    if len(comp) > 1:
                        out.append(comp)
    return out


def test_the_cycle_finder_finds_a_cycle() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert strongly_connected(graph) == [{"a", "b", "c"}]


def test_the_import_graph_has_no_cycles() -> None:
    graph = import_graph()
    assert "lgraph.curvature" not in graph["lgraph.families.fieldlines"]  # fields carry their stop
    cycles = [sorted(c) for c in strongly_connected(graph)]
    assert not cycles, f"import cycles: {cycles}"


#: the cycles that only type-only imports close, each allowed with its reason
#: (a cycle not listed fails, and so does a listed one that is gone).  None is
#: left (issue #30): a cycle that only type hints close is cut by moving the
#: name below both modules or by a small protocol, and listed here only with
#: a reason why neither will do.
TYPE_ONLY_CYCLES: dict[str, set[str]] = {}


def test_the_graph_with_type_only_imports_has_no_cycles() -> None:
    """Small protocols cut the cycles (issue #30): the renderer's Renderable and
    RenderNode, the page's Laid, the display's Shown and Showable, the
    cache's HoldsSurface, the numeric defaults' Parametrized, the saddle's
    Saddle, the surface of revolution's Revolved; and a move: the parameter
    lines live below the families and the surface base class."""
    graph = import_graph(type_only=True)
    assert graph["lgraph.render"] >= import_graph()["lgraph.render"]
    cycles = strongly_connected(graph)
    allowed = list(TYPE_ONLY_CYCLES.values())
    new = [sorted(c) for c in cycles if not any(c <= a for a in allowed)]
    assert not new, f"type-only import cycles (type by a small protocol?): {new}"
    gone = [why for why, a in TYPE_ONLY_CYCLES.items() if not any(c & a for c in cycles)]
    assert not gone, f"allowed type-only cycles that are gone (remove them): {gone}"
    for cut in ("lgraph.render", "lgraph.output.page", "lgraph.notebook.display"):
        assert not any(cut in c for c in cycles)
    assert "lgraph.scene.graph" not in graph["lgraph.render"]
    assert "lgraph.surfaces._base" not in graph["lgraph.surfaces.parametric._hits"]
    # the base class's defaults draw with the parameter lines that live below
    # it and the families both (a move: Family.batches keeps its Surface)
    assert not graph["lgraph.families._lines"] & {"lgraph.families", "lgraph.surfaces._base"}
    # the helpers of a surface of revolution type it by what they read of it
    helpers = [m for m in graph if m.startswith("lgraph.surfaces.revolution._")]
    assert len(helpers) >= 7
    assert not any("lgraph.surfaces.revolution" in graph[m] for m in helpers)


MAP = PACKAGE.parent / "docs" / "architecture.rst"
MAX_LINES = 500


def _modules() -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def mapped_modules(block: str) -> set[str]:
    """The module paths the map's tree names: a line ending a name in ``/`` opens
    a folder (to the lines indented deeper), every ``name.py`` on a line lies in
    the folder open there."""
    folders: list[tuple[int, str]] = []
    found: set[str] = set()
    for line in block.splitlines():
        if not line.strip() or not line.startswith("   "):
            continue
        indent = len(line) - len(line.lstrip())
        while folders and folders[-1][0] >= indent:
            folders.pop()
        first = line.split()[0]
        if first.endswith("/") and first.rstrip("/").isidentifier():
            parent = folders[-1][1] if folders else None
            name = first.rstrip("/")
            folders.append((indent, name if parent in (None, "lgraph") else f"{parent}/{name}"))
            if parent is None:  # the root: lgraph/
                folders[-1] = (indent, "lgraph")
        here = folders[-1][1] if folders else "lgraph"
        prefix = "" if here == "lgraph" else here.removeprefix("lgraph/") + "/"
        found.update(prefix + m for m in re.findall(r"\b\w+\.py\b", line))
    return found


def test_the_map_reader_places_modules_in_their_folders() -> None:
    lines = ["   lgraph/", "     a.py  x", "     sub/  y", "       b.py  c.py", "          d.py"]
    lines.append("     e.py")
    block = "\n".join(lines)
    assert mapped_modules(block) == {"a.py", "sub/b.py", "sub/c.py", "sub/d.py", "e.py"}


def test_every_module_is_on_the_module_map() -> None:
    """docs/architecture.rst names every module in its folder of the map's tree."""
    text = MAP.read_text(encoding="utf-8")
    block = text[text.index("The module map") : text.index("How things plug in")]
    mapped = mapped_modules(block)
    missing = [
        str(p.relative_to(PACKAGE))
        for p in _modules()
        if p.relative_to(PACKAGE).as_posix() not in mapped
    ]
    assert not missing, f"modules missing from the map in docs/architecture.rst: {missing}"


#: issue #30: the top of the package keeps at most about a dozen modules
MAX_TOP_MODULES = 12


def test_the_top_of_the_package_keeps_about_a_dozen_modules() -> None:
    top = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert len(top) <= MAX_TOP_MODULES, f"{len(top)} modules at the top of lgraph/: {top}"


def test_every_folder_is_a_package_that_says_what_it_is_for() -> None:
    folders = [
        d
        for d in PACKAGE.rglob("*")
        if d.is_dir() and d.name != "__pycache__" and any(d.glob("*.py"))
    ]
    bare = [str(d.relative_to(PACKAGE)) for d in folders if not (d / "__init__.py").is_file()]
    assert not bare, f"folders without an __init__.py (namespace packages): {bare}"


def test_every_module_says_what_it_is_for() -> None:
    bare = [
        str(p.relative_to(PACKAGE))
        for p in _modules()
        if not ast.get_docstring(ast.parse(p.read_text(encoding="utf-8")))
    ]
    assert not bare, f"modules without a docstring: {bare}"


def test_no_module_is_longer_than_the_limit() -> None:
    long = {
        str(p.relative_to(PACKAGE)): n
        for p in _modules()
        if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_LINES
    }
    assert not long, f"modules over {MAX_LINES} lines (split them along a seam): {long}"
