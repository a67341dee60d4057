"""The independent truth for weft's rendered picture (issue 18, "The picture").

- :mod:`~weft.reference.picture.conventions`: how weft's light units and Blinn-Phong / GGX
  materials map onto a physically based renderer, and what does not map;
- :mod:`~weft.reference.picture.environment`: the synthetic HDR sky, cube map -> equirect;
- :mod:`~weft.reference.picture.mitsuba_export`: a weft.Scene + Camera as a Mitsuba 3 scene,
  rendered path-traced (``scalar_rgb``);
- :mod:`~weft.reference.picture.scenes`: the reference scene set;
- :mod:`~weft.reference.picture.compare`: exposure + clamp + sRGB, FLIP and relative error over
  the whole image, the objects and the geometric edges;
- :mod:`~weft.reference.picture.antialias`: the 4x4-supersampled anti-aliasing reference.

Nothing here re-implements weft's shading: the truth is Mitsuba's path tracer or weft's own
frame at 16x the samples.
"""
