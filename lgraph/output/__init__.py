"""Output: from the display list to files.

``drawing.py`` the display list (:class:`~lgraph.Drawing`, strokes, placed
labels), ``page.py`` and ``units.py`` the page and its lengths, ``layers.py``,
``dashes.py``, ``halos.py``, ``bezier.py`` and ``plotter.py`` the geometry the
backends ask for, ``_text.py`` and ``_tex_check.py`` label text, ``_atomic.py``
atomic files, ``backends/`` the writers by file suffix (PDF, PNG, SVG; plugins
add more).
"""
