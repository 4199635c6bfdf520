"""vpype-lgraph: a vpype command that renders an lgraph scene file into vpype layers.

Registered through the entry point group ``vpype.plugins`` (see
``pyproject.toml``), so after ``pip install vpype-lgraph``::

    vpype lgraph fig.toml linemerge linesort write out.svg
    vpype lgraph --hidden --layers surface fig.toml show

The scene file is rendered by lgraph (exact hidden-line removal) and every
lgraph layer (:mod:`lgraph.output.layers`: one per family, hidden parts in their own,
or one per surface) becomes one vpype layer with ``vp_name`` (``"2 contour"``,
as lgraph's SVG labels it), ``vp_color`` and ``vp_pen_width`` set.  The page
is lgraph's page (``[page]`` of the scene file), in vpype's units (CSS pixels,
1/96 in), y down.  Dashed layers (hidden lines) are split into their dashes,
since a plotter draws dashes as separate pen-down moves (``--no-dashes``
keeps them whole).  ``--clean`` runs lgraph's :meth:`Drawing.for_plotter`
first: it also removes strokes drawn twice, which vpype's ``linemerge`` keeps.

:func:`drawing_to_document` does the conversion for a drawing built in Python.

>>> import numpy as np
>>> from lgraph.output.drawing import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [72.0, 36.0]]), xyz=np.zeros((2, 3)), family="u1")
>>> doc = drawing_to_document(Drawing(strokes=(s,), page=Page(margin=0, extent=72)))
>>> doc.page_size, doc.layers[1].property("vp_name")
((96.0, 48.0), '1 u1')
>>> doc.layers[1].lines[0].tolist()  # (x, y) in px as x + iy, y down
[48j, (96+0j)]
"""

from __future__ import annotations

from typing import Any

import click
import vpype as vp
import vpype_cli

from lgraph.output.drawing import dash_polyline
from lgraph.output.layers import drawing_layers

__all__ = ["lgraph", "drawing_to_document", "PX_PER_PT"]
__version__ = "0.1.0"

#: vpype's unit (CSS pixel, 1/96 in) per PostScript point (1/72 in)
PX_PER_PT = 96.0 / 72.0


def drawing_to_document(
    drawing: Any,
    *,
    layers: str | None = "family",
    dashes: bool = True,
    document: vp.Document | None = None,
) -> vp.Document:
    """Add the layers of an lgraph ``drawing`` to a vpype document (a new one by default).

    Layers get the document's next free ids; ``vp_name`` is ``"<id> <name>"``,
    ``vp_color`` and ``vp_pen_width`` (px) the layer's style.  The page size
    grows to hold lgraph's page.
    """
    doc = vp.Document() if document is None else document
    _, ph = drawing.page_size()
    for layer in drawing_layers(drawing, layers):
        lc = vp.LineCollection()
        for pts, _ in layer.runs:
            pieces = dash_polyline(pts, layer.style.dash) if dashes and layer.style.dash else [pts]
            for piece in pieces:
                lc.append((piece[:, 0] + 1j * (ph - piece[:, 1])) * PX_PER_PT)
        lid = doc.free_id()
        doc.add(lc, lid)
        r, g, b = (round(255 * c) for c in layer.style.color)
        doc.layers[lid].set_property(vp.METADATA_FIELD_NAME, f"{lid} {layer.name}")
        doc.layers[lid].set_property(vp.METADATA_FIELD_COLOR, vp.Color(r, g, b))
        doc.layers[lid].set_property(vp.METADATA_FIELD_PEN_WIDTH, layer.style.width * PX_PER_PT)
    pw, ph = drawing.page_size()
    doc.extend_page_size((pw * PX_PER_PT, ph * PX_PER_PT))
    return doc


@click.command()
@click.argument("scene", type=click.Path(exists=True, dir_okay=False))
@click.option("--hidden", is_flag=True, help="Also draw hidden lines (their own layer).")
@click.option(
    "--layers",
    type=click.Choice(["family", "surface"]),
    default="family",
    show_default=True,
    help="One layer per family of curves or per surface.",
)
@click.option(
    "--dashes/--no-dashes",
    default=True,
    show_default=True,
    help="Split dashed layers (hidden lines) into their dashes.",
)
@click.option(
    "--clean",
    is_flag=True,
    help="Clean with lgraph first: remove duplicate strokes (which linemerge keeps), "
    "merge, drop fragments, sort (Drawing.for_plotter).",
)
@vpype_cli.global_processor
def lgraph(
    document: vp.Document, scene: str, hidden: bool, layers: str, dashes: bool, clean: bool
) -> vp.Document:
    """Render an lgraph scene file (TOML), one layer per family or surface.

    Hidden lines are removed exactly by lgraph; --hidden draws them too, in a
    layer of their own.  Example: vpype lgraph fig.toml linemerge linesort write out.svg
    """
    from lgraph.scenefile import SceneFileError, load_scene_file

    try:
        scn, projector, options = load_scene_file(scene)
    except SceneFileError as e:
        raise click.BadParameter(str(e), param_hint="SCENE") from None
    render = dict(options.get("render", {}))
    if hidden:
        render["hidden_lines"] = True
    drawing = scn.render(projector, **render)
    if clean:
        drawing = drawing.for_plotter(layers=layers)
    return drawing_to_document(drawing, layers=layers, dashes=dashes, document=document)


lgraph.help_group = "Plugins"
