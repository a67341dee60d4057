"""Independent NumPy references for weft's GPU results.

``weft.reference.shading`` (with ``texture`` and ``shadow``) re-derives every covered pixel of a frame from the renderer's debug
outputs (SPEC §1.3 eq. 2.5, 2.8–2.10: ambient + Lambert + Blinn-Phong, and §1.5: shadow map
with normal offset, slope-scaled bias and PCF). Tests and benchmarks use it as the oracle;
later shading models add their own functions next to it. Nothing here calls the renderer.
"""

from weft.reference.shading import (
    LightDesc,
    OracleErrors,
    SurfaceMaterial,
    as_light,
    blinn_phong,
    compare_frame,
    first_shadow_light,
    material_maps,
    shade_debug_frame,
)
from weft.reference.shadow import ShadowLookup, pcf_visibility, shadow_lookup
from weft.reference.texture import (
    build_mip_chain,
    encode_u8,
    sample_bilinear_repeat,
    sample_trilinear_repeat,
    srgb_decode,
    srgb_encode,
    texture_lod,
    texture_to_linear,
)

__all__ = [
    "LightDesc",
    "OracleErrors",
    "ShadowLookup",
    "SurfaceMaterial",
    "as_light",
    "blinn_phong",
    "build_mip_chain",
    "compare_frame",
    "encode_u8",
    "first_shadow_light",
    "material_maps",
    "pcf_visibility",
    "sample_bilinear_repeat",
    "sample_trilinear_repeat",
    "shade_debug_frame",
    "shadow_lookup",
    "srgb_decode",
    "srgb_encode",
    "texture_lod",
    "texture_to_linear",
]
