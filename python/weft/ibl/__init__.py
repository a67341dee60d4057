"""Image-based lighting tools (SPEC §4): capture conversion, cube maps, irradiance, glossy
prefiltering, light extraction, the dome of shadow lights and an analytic daylight sky
(``sky``, ``sun_light``, ``SkyModel``: Preetham, Shirley & Smits 1999).

The numeric work is in C++ (``weft._core``); this package re-exports it and adds conveniences:

- :mod:`weft.ibl.capture`: sRGB decoding, environment files (also straight to a cube map:
  ``load_environment_cube``), cube crosses, the one-camera
  mirror-ball cut-out and frame-by-frame environments from an image sequence;
- :mod:`weft.ibl.video`: video files (PyAV, optional) as the same frame-by-frame source;
- :mod:`weft.ibl.lights`: light extraction as dataclasses, ``split_lights`` (lights + the sky
  without them) and median cut (Debevec 2005);
- :mod:`weft.ibl.cli`: ``python -m weft ibl ...``;
- :mod:`weft.ibl.files`: importers for the seed's scene / renderer / light text files.

Conventions: cube faces +X, -X, +Y, -Y, +Z, -Z with the Vulkan/OpenGL orientation (see
``weft/CubeMap.h``), arrays (6, S, S, 3) float32; irradiance is physical (constant radiance L gives
pi L); SH9 coefficients (9, 3) in the order Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, Y20, Y21, Y22 over
world x, y, z.
"""

from weft._core import (
    CubeMap,
    Environment,
    ShadowDome,
    SkyModel,
    coat_albedo,
    cube_coords,
    cube_texel_directions,
    cube_texel_solid_angles,
    cube_to_equirect,
    cube_to_sphere,
    dfg_lut,
    equirect_to_cube,
    fill_unseen,
    fisheye_to_cube,
    irradiance_box_blur,
    irradiance_exact,
    irradiance_exact_gpu,
    irradiance_from_sh,
    irradiance_rotational_blur,
    phong_exact,
    phong_sampled,
    prefilter_ggx,
    prefilter_ggx_gpu,
    project_sh9,
    sh_irradiance,
    sky,
    sphere_to_cube,
    sun_light,
)
from weft.ibl.capture import (
    cross_to_cube,
    cube_to_cross,
    cut_out_sphere,
    environments_from_frames,
    guess_source,
    load_environment,
    load_environment_cube,
    save_environment,
    sphere_rect,
    srgb_to_linear,
    to_cube,
)
from weft.ibl.lights import EnvLight, extract_lights, median_cut, split_lights
from weft.ibl.video import environments_from_video, read_video_frames

__all__ = [
    "CubeMap", "Environment", "ShadowDome", "EnvLight", "SkyModel", "sky", "sun_light",
    "coat_albedo", "cube_coords", "cube_texel_directions", "cube_texel_solid_angles",
    "cube_to_equirect",
    "cube_to_sphere", "dfg_lut", "equirect_to_cube", "fill_unseen", "fisheye_to_cube",
    "irradiance_box_blur", "irradiance_exact", "irradiance_exact_gpu", "irradiance_from_sh",
    "irradiance_rotational_blur", "phong_exact", "phong_sampled", "prefilter_ggx",
    "prefilter_ggx_gpu", "project_sh9", "sh_irradiance",
    "sphere_to_cube", "cross_to_cube", "cube_to_cross", "cut_out_sphere",
    "environments_from_frames", "environments_from_video", "read_video_frames",
    "guess_source", "load_environment", "load_environment_cube", "save_environment", "sphere_rect",
    "srgb_to_linear", "to_cube", "extract_lights", "median_cut", "split_lights",
]
