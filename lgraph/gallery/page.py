"""The gallery's web page: one card per figure (``index.html``)."""

from __future__ import annotations

import html
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["figure_title", "write_index"]


def figure_title(stem: str) -> str:
    """Human title from a script name.

    >>> figure_title("fig_7_2_ellipsoid")
    'Figure 7.2: ellipsoid'
    >>> figure_title("extra_hidden_dashed")
    'Hidden dashed'
    """
    m = re.fullmatch(r"fig_(\d+)_(\d+)_?(.*)", stem)
    if m:
        rest = m.group(3).replace("_", " ")
        return f"Figure {m.group(1)}.{m.group(2)}" + (f": {rest}" if rest else "")
    rest = stem[6:] if stem.startswith("extra_") else stem
    rest = rest.replace("_", " ").strip()
    return rest[:1].upper() + rest[1:]


_CSS = """
body { font-family: Georgia, 'Times New Roman', serif; margin: 0; background: #f6f6f3;
       color: #222; }
header { padding: 1.5em 2em 0.5em; }
header h1 { margin: 0 0 0.2em; font-weight: normal; }
header p { margin: 0.2em 0; color: #555; }
h2 { font-weight: normal; margin: 1.2em 2em 0.4em; border-bottom: 1px solid #ccc; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(320px, 1fr));
        gap: 1.2em; padding: 0.5em 2em 2em; }
figure { margin: 0; background: #fff; border: 1px solid #ddd; border-radius: 4px;
         padding: 0.8em; display: flex; flex-direction: column; }
figure a.thumb { display: flex; align-items: center; justify-content: center;
                 height: 240px; }
figure img { max-width: 100%; max-height: 240px; object-fit: contain; }
figcaption { font-size: 0.9em; line-height: 1.35; margin-top: 0.6em; flex: 1; }
figcaption b { display: block; margin-bottom: 0.25em; }
.links { font-size: 0.85em; margin-top: 0.5em; font-family: sans-serif; }
.links a { margin-right: 0.9em; color: #2a5db0; }
.failed { border-color: #c33; }
.failed pre { font-size: 0.75em; white-space: pre-wrap; color: #a00; max-height: 200px;
              overflow: auto; }
"""

# Marks each thumbnail data-loaded="1" / "0" once the page has loaded, and the
# body with the count, so that a headless browser's DOM dump shows the result.
_SCRIPT = """
window.addEventListener("load", function () {
  var imgs = document.querySelectorAll("img.thumbnail"), ok = 0;
  imgs.forEach(function (img) {
    var good = img.complete && img.naturalWidth > 0;
    img.setAttribute("data-loaded", good ? "1" : "0");
    if (good) { ok += 1; }
  });
  document.body.setAttribute("data-thumbnails", ok + "/" + imgs.length);
});
"""


def _card(item: dict[str, Any]) -> str:
    stem = item["stem"]
    e = html.escape
    title = e(figure_title(stem))
    caption = e(item.get("caption") or "")
    src = f'<a href="src/{e(stem)}.py">source</a>'
    if item.get("error"):
        last = item["error"].strip().splitlines()[-1] if item["error"].strip() else ""
        return (
            f'<figure class="failed" id="{e(stem)}"><figcaption><b>{title}</b>{caption}'
            f"<pre>build failed: {e(last)}</pre></figcaption>"
            f'<div class="links">{src}</div></figure>'
        )
    thumb = f"{e(stem)}.gif" if item.get("animation") else f"{e(stem)}.png"
    gif = f'<a href="{e(stem)}.gif">GIF</a>' if item.get("animation") else ""
    return (
        f'<figure id="{e(stem)}">'
        f'<a class="thumb" href="{e(stem)}.pdf"><img class="thumbnail" src="{thumb}" '
        f'alt="{title}"></a>'
        f"<figcaption><b>{title}</b>{caption}</figcaption>"
        f'<div class="links"><a href="{e(stem)}.pdf">PDF</a><a href="{e(stem)}.png">PNG</a>'
        f"{gif}{src}</div></figure>"
    )


def write_index(outdir: Path, items: Sequence[dict[str, Any]]) -> Path:
    """Write ``outdir/index.html`` for the built ``items`` (in order)."""
    from .. import __version__

    sections = [
        ("Figures of the paper", [i for i in items if i["stem"].startswith("fig_")]),
        ("Beyond the paper", [i for i in items if not i["stem"].startswith("fig_")]),
    ]
    body = []
    for heading, group in sections:
        if group:
            cards = "\n".join(_card(i) for i in group)
            body.append(f'<h2>{heading}</h2>\n<div class="grid">\n{cards}\n</div>')
    page = (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>lgraph gallery</title>\n<style>{_CSS}</style>\n"
        f"<script>{_SCRIPT}</script>\n</head>\n<body>\n<header><h1>lgraph gallery</h1>\n"
        "<p>Lines of curvature and other line families on surfaces, drawn with exact "
        "hidden-line removal. Click a picture for its PDF.</p>\n"
        f"<p>{len(items)} figures, lgraph {html.escape(__version__)}. Figure numbers follow "
        "V. Veli&#269;kovi&#263;, <i>Visualization of lines of curvature on quadratic "
        "surfaces</i>, Facta Univ. Ser. Math. Inform. 32 (2017) 11&ndash;29.</p></header>\n"
        + "\n".join(body)
        + "\n</body>\n</html>\n"
    )
    path = outdir / "index.html"
    path.write_text(page, encoding="utf-8")
    return path


# -- the command ----------------------------------------------------------------
