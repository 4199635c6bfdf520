"""The table of output backends by file suffix, shared by :mod:`lgraph.output.backends`
(which looks writers up) and :mod:`lgraph.plugins` (which adds the plugins'
writers): kept apart so that neither imports the other's package.

>>> {".pdf", ".png", ".svg"} <= set(BACKENDS)  # plugins may have added more
True
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["BACKENDS", "Writer"]

Writer = Callable[..., None]

#: suffix -> "module:function" (imported lazily) or a callable
BACKENDS: dict[str, str | Writer] = {
    ".pdf": "lgraph.output.backends.pdf:write_pdf",
    ".png": "lgraph.output.backends.png:write_png",
    ".svg": "lgraph.output.backends.svg:write_svg",
}
