"""Entry-point discovery for plugins (surfaces, families, backends)."""

from __future__ import annotations


def load_backends() -> None:
    """Register backends from the ``lgraph.backends`` entry-point group (placeholder)."""
    return None
