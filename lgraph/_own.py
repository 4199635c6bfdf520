"""Codes telling :meth:`Surface.hits` how a ray's origin relates to the surface."""

#: the origin is not on this surface
OFF = 0
#: the origin lies on this surface
ON = 1
#: the origin lies on this surface's contour for the current view
CONTOUR = 2
