"""Sphinx configuration of the lgraph documentation.

Build with ``python -m sphinx -W -b html docs OUT`` (the html build also
renders the gallery into ``OUT/gallery``; set ``-D lgraph_gallery_build=0`` to
skip that) and check the pages' examples with ``python -m sphinx -W -b doctest
docs OUT``.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))  # lgraph from this checkout
sys.path.insert(0, str(HERE / "_ext"))

import lgraph  # noqa: E402

project = "lgraph"
author = "the lgraph authors"
copyright = "2024, the lgraph authors"  # noqa: A001
version = release = lgraph.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.doctest",
    "lgraph_gallery",
]

exclude_patterns = ["_build"]
templates_path: list[str] = []
html_static_path = ["_static"]
html_theme = "alabaster"
html_theme_options = {
    "description": "Line graphics of surfaces with exact hidden-line removal",
    "fixed_sidebar": True,
}
html_title = f"lgraph {release}"

# autodoc: document what the public API says, in source order
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options: dict[str, object] = {}
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_ivar = True  # "Attributes" sections as fields (attrs fields are documented once)

# doctest builder: the examples of these pages run as ``.. doctest::`` blocks
# (docstring examples run under pytest --doctest-modules).
doctest_test_doctest_blocks = ""
doctest_global_setup = """
import numpy as np
import lgraph as lg
"""

# the gallery extension (docs/_ext/lgraph_gallery.py)
lgraph_gallery_build = True
lgraph_gallery_only = ""
lgraph_gallery_tolerance = 0.0  # 0: each figure's own default

# nitpicky builds (-n) must be clean too.  Free-form numpy-style parameter
# types ("(lo, hi)", "array (n, 3)", "callable, optional") and classes of other
# libraries (numpy.ndarray, pathlib.Path, ...: no intersphinx, the docs build
# offline) are not lgraph objects: only references to lgraph's own classes are
# checked.
nitpick_ignore_regex = [("py:class", r"(?!lgraph\.).*")]

# numpy-style parameter types such as "(width, height)" become cross-references;
# names shared by several classes (width, height) are ambiguous, not errors.
suppress_warnings = ["ref.python"]

# literal blocks (``::``) hold formulas, not code: no syntax colouring
highlight_language = "none"
