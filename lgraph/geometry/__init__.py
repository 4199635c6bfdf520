"""Transforms, sampling and polyline utilities."""

from .transforms import IDENTITY, Transform, rotate, scale, translate

__all__ = ["IDENTITY", "Transform", "rotate", "scale", "translate"]
