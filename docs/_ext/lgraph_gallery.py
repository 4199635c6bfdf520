"""Sphinx extension: embed the lgraph gallery.

``.. lgraph-gallery::`` puts one card per gallery script (title, caption,
thumbnail, links to the PDF and the source) into the page; after an html build
the extension runs :func:`lgraph.gallery.build_gallery` into ``OUTDIR/gallery``,
so the thumbnails, PDFs, sources and the stand-alone ``gallery/index.html``
exist next to the page.

Configuration: ``lgraph_gallery_build`` (bool, default True; ``-D
lgraph_gallery_build=0`` skips the rendering), ``lgraph_gallery_only``
(comma-separated name parts, default all), ``lgraph_gallery_tolerance``
(chord tolerance override, 0 = each figure's default).
"""

from __future__ import annotations

import html
import io
from pathlib import Path
from typing import Any

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

from lgraph import gallery

logger = logging.getLogger(__name__)


def _only(config: Any) -> list[str] | None:
    parts = [p.strip() for p in str(config.lgraph_gallery_only or "").split(",") if p.strip()]
    return parts or None


def _scripts(config: Any) -> list[Path]:
    scripts = gallery.discover_scripts()
    only = _only(config)
    if only:
        scripts = [p for p in scripts if any(s in p.stem for s in only)]
    return scripts


class GalleryDirective(SphinxDirective):
    """Cards for every gallery script, linking into ``gallery/``."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        scripts = _scripts(self.config)
        depth = self.env.docname.count("/")
        base = "../" * depth + "gallery/"
        cards = []
        for p in scripts:
            self.env.note_dependency(str(p))
            e = html.escape
            stem = e(p.stem)
            title = e(gallery.figure_title(p.stem))
            caption = e(gallery.script_caption(p))
            thumb = "gif" if gallery.script_animation(p) else "png"
            cards.append(
                f'<div class="lg-card" id="fig-{stem}"><a href="{base}{stem}.pdf">'
                f'<img src="{base}{stem}.{thumb}" alt="{title}" loading="lazy"></a>'
                f'<p class="lg-title">{title}</p><p class="lg-caption">{caption}</p>'
                f'<p class="lg-links"><a href="{base}{stem}.pdf">PDF</a> '
                f'<a href="{base}{stem}.png">PNG</a> <a href="{base}src/{stem}.py">source</a>'
                f"</p></div>"
            )
        markup = (
            '<div class="lg-gallery">' + "\n".join(cards) + "</div>"
            if cards
            else "<p>(no gallery scripts found)</p>"
        )
        return [nodes.raw("", markup, format="html")]


def _build(app: Sphinx, exception: Exception | None) -> None:
    if exception is not None or app.builder.format != "html":
        return
    if not app.config.lgraph_gallery_build or str(app.config.lgraph_gallery_build) == "0":
        logger.info("lgraph gallery: not rendered (lgraph_gallery_build is off)")
        return
    out = Path(app.outdir) / "gallery"
    log = io.StringIO()
    tol = float(app.config.lgraph_gallery_tolerance or 0) or None
    logger.info(f"lgraph gallery: rendering into {out}")
    status = gallery.build_gallery(out, only=_only(app.config), tolerance=tol, stream=log)
    for line in log.getvalue().splitlines():
        logger.info(line)
    if status != 0:
        logger.warning(f"lgraph gallery: build failed (status {status}); see the log above")


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_config_value("lgraph_gallery_build", True, "html", [bool, str, int])
    app.add_config_value("lgraph_gallery_only", "", "html", [str])
    app.add_config_value("lgraph_gallery_tolerance", 0.0, "html", [float, str, int])
    app.add_directive("lgraph-gallery", GalleryDirective)
    app.add_css_file("lgraph_gallery.css")
    app.connect("build-finished", _build)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
