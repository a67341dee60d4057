"""Independent NumPy references for weft's GPU results.

``weft.reference.shading`` (with ``texture`` and ``shadow``) re-derives every covered pixel of
a frame from the renderer's debug outputs (SPEC §1.3 eq. 2.5, 2.8–2.10: ambient + Lambert +
Blinn-Phong, and §1.5: shadow map with normal offset, slope-scaled bias and PCF). Tests and
benchmarks use it as the oracle; later shading models add their own functions next to it.
Nothing here calls the renderer.

``weft.reference.cloth`` is the cloth solver of SPEC §2 in NumPy (float64):
:class:`ClothReference` runs the same algorithm as ``weft.Cloth`` (same constraint batches,
Verlet, XPBD, tethers, collisions), and the literal formulas the tests check against
(:func:`project_distance` = eq. 3.3/3.4, collider distances, free fall, pendulum period).
"""

from weft.reference.cloth import (
    BoxShape,
    CapsuleShape,
    ClothReference,
    HeightFieldShape,
    PlaneShape,
    SphereShape,
    WindSetting,
    box_distance,
    capsule_distance,
    constraint_pattern,
    free_fall,
    grid_normals,
    grid_positions,
    grid_triangles,
    height_field_distance,
    hole_mask_from_image,
    pendulum_period,
    plane_distance,
    project_distance,
    sphere_distance,
    strain,
)
from weft.reference.shading import (
    LINEAR_STORAGE_RTOL,
    LightDesc,
    OracleErrors,
    SurfaceMaterial,
    as_light,
    attenuation,
    blinn_phong,
    compare_frame,
    first_shadow_light,
    incident,
    material_maps,
    shade_debug_frame,
    spot_basis,
    storage_excess,
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
    "BoxShape",
    "CapsuleShape",
    "ClothReference",
    "HeightFieldShape",
    "PlaneShape",
    "SphereShape",
    "WindSetting",
    "box_distance",
    "capsule_distance",
    "constraint_pattern",
    "free_fall",
    "grid_normals",
    "grid_positions",
    "grid_triangles",
    "height_field_distance",
    "hole_mask_from_image",
    "pendulum_period",
    "plane_distance",
    "project_distance",
    "sphere_distance",
    "strain",
    "LINEAR_STORAGE_RTOL",
    "LightDesc",
    "OracleErrors",
    "ShadowLookup",
    "SurfaceMaterial",
    "as_light",
    "attenuation",
    "incident",
    "spot_basis",
    "storage_excess",
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
