"""weft's picture against an independent truth (issue 18): Mitsuba 3's path tracer on the
reference scene set (FLIP + relative error, whole / covered / objects / edges) and the 4x4
supersampled anti-aliasing reference; plus the conventions the Mitsuba export rests on, each
checked against Mitsuba itself (a wrong convention would make the reference lie silently).

Tolerances are today's measured values plus a margin (numbers in the comments, measured at
this file's size: 128 x 96, 512 spp); they are ceilings for regressions, to be lowered towards
the issue's targets (FLIP <= 0.04 whole, <= 0.08 objects / edges) as the picture improves.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import weft
import weft.ibl
import weft.reference.ibl
import weft.scenes

mi = pytest.importorskip("mitsuba", reason="mitsuba (PyPI) is not installed: no path-traced "
                                           "reference")
pytest.importorskip("flip_evaluator", reason="flip-evaluator (PyPI) is not installed")

from weft.reference.picture import antialias as aa  # noqa: E402
from weft.reference.picture import compare as cmp  # noqa: E402
from weft.reference.picture import conventions as conv  # noqa: E402
from weft.reference.picture import environment as envmod  # noqa: E402
from weft.reference.picture import evaluate as ev  # noqa: E402
from weft.reference.picture import mitsuba_export as mx  # noqa: E402
from weft.reference.picture import scenes  # noqa: E402

pytestmark = pytest.mark.slow  # Mitsuba's reference renders (~30 s)

W, H, SPP = 128, 96, 512

#: Per scene and region: (FLIP ceiling, relative-error ceiling). Measured at 128 x 96, 512 spp
#: (`python -m weft.bench picture --size 128 96 --spp 512`), FLIP / rel, before the picture work
#: -> after the environment background, MSAA and the soft dome shadows -> after one bounce
#: (BounceProbes) -> after the casters' bounce in two rounds, the sky's reflection, soft sun
#: shadows and MSAA frames scored -> after the casters' proxies as a floor under the dome's
#: occlusion with the dome blur over the rest, the sky they hide blurred over their caps, the
#: casters' glossy reflections of their captures, a proxy inside another hidden -> the bounce
#: captures projected at 15 points over each caster, the casters' light from their surface's
#: irradiance, a glossy caster's reflection where its ray meets the receivers -> now (the
#: proxies as the ellipsoids of the casters' bounds filling the union of their caps, none
#: hidden; a caster reflects its capture under the ambient's sky too) -> now (the reference
#: scenes' glossy materials GGX coats, Material.specular_model = 'ggx': the lights' highlight
#: the coat's lobe, the reflection weighted by its albedo; the sky's reflection by that albedo):
#:   spheres_sky  whole 0.33 -> 0.099 -> 0.077 -> 0.050 -> 0.043 -> 0.037 -> 0.035  covered ...
#:                -> 0.058 -> 0.048 -> 0.047  objects 0.252 -> 0.199 -> 0.096 -> 0.078 -> 0.072
#:                -> 0.047 -> 0.040  edges ... -> 0.107 -> 0.077 -> 0.063 -> 0.067 -> 0.061
#:   spheres_sun  whole 0.34 -> 0.118 -> 0.088 -> 0.055 -> 0.049 -> 0.040 -> 0.041 -> 0.038
#:                (0.035 against 2048 spp)  covered ... -> 0.066 -> 0.054 -> 0.051
#:                objects 0.297 -> 0.260 -> 0.120 -> 0.093 -> 0.087 -> 0.053 -> 0.052 -> 0.043
#:                edges ... -> 0.108 -> 0.091 -> 0.071 -> 0.071 -> 0.064
#:                unlit bias -0.40 -> -0.17 -> -0.11 -> -0.107 -> -0.019 -> -0.016
#:   cloth        whole 0.29 -> 0.295 -> 0.081 -> 0.069 -> 0.062 -> 0.062 -> 0.048 -> 0.043
#:                (0.037 against 4096 spp)  covered ... -> 0.078 -> 0.078 -> 0.060 -> 0.053
#:                objects 0.284 -> 0.125 -> 0.102 -> 0.107 -> 0.095 -> 0.081 -> 0.067
#:                edges ... -> 0.138 -> 0.125 -> 0.118 -> 0.079 -> 0.069
#:                unlit bias -0.63 -> -0.34 -> -0.21 -> -0.245 -> -0.120 -> -0.026
#:   dome         whole 0.31 -> 0.057 -> 0.045 -> 0.031 -> 0.025 -> 0.025  covered ... -> 0.031
#:                -> 0.031  objects 0.280 -> 0.227 -> 0.048 -> 0.036 -> 0.039 -> 0.043
#:                edges ... -> 0.030 -> 0.032 -> 0.030
#: rel (covered / objects) now: 0.021 / 0.024, 0.026 / 0.027, 0.033 / 0.036, 0.014 / 0.019.
#: The reference's pair noise floor (two seeds) is 0.013-0.037 FLIP. Margin: +25% of the value
#: (a 128 x 96 frame's FLIP moves by a few % with the reference's noise). The issue's targets
#: (whole <= 0.04, objects and edges <= 0.08) are met by every scene against a quieter
#: reference (2048-4096 spp: 0.033 / 0.035 / 0.037 / 0.024 whole); against this one the
#: cloth's whole includes the reference's own noise (floor 0.028).
TOLERANCES = {
    "spheres_sky": {"whole": (0.044, None), "covered": (0.058, 0.027), "objects": (0.050, 0.030),
                    "edges": (0.076, None)},
    "spheres_sun": {"whole": (0.048, None), "covered": (0.064, 0.032), "objects": (0.054, 0.034),
                    "edges": (0.079, None)},
    "cloth": {"whole": (0.053, None), "covered": (0.066, 0.042), "objects": (0.084, 0.045),
              "edges": (0.087, None)},
    "dome": {"whole": (0.031, None), "covered": (0.039, 0.018), "objects": (0.054, 0.024),
             "edges": (0.038, None)},
}


@pytest.fixture(scope="module")
def renderer():
    return weft.Renderer(W, H)


@pytest.fixture(scope="module")
def evaluations(renderer):
    """Each reference scene rendered once by weft and once by Mitsuba."""
    return {name: ev.evaluate(scenes.build(name), renderer, SPP) for name in scenes.SCENES}


# ---------------------------------------------------------------------------------------------
# Conventions, each against Mitsuba itself
# ---------------------------------------------------------------------------------------------

def _plane_scene(material, light=None, ambient=(0.0, 0.0, 0.0)):
    scene = weft.Scene()
    scene.ambient = ambient
    scene.add_mesh(weft.Mesh.plane(6.0, 6.0), material)
    if light is not None:
        scene.add_light(light)
    return scene


TOP = weft.Camera(position=(0.0, 3.0, 0.01), target=(0.0, 0.0, 0.0), fov_y=0.3)


def test_directional_light_units_match_lambert():
    """weft's diffuse K_D T (n.l) L has no 1/pi: Mitsuba's irradiance pi L under a Lambertian
    K_D T gives the same radiance, also at a slant (n.l = cos 60 deg)."""
    for direction, cos in (((0.0, -1.0, 0.0), 1.0), ((0.0, -0.5, -math.sqrt(0.75)), 0.5)):
        light = weft.DirectionalLight(direction=direction, color=(1.0, 0.5, 0.25), intensity=0.8)
        scene = _plane_scene(weft.Material(kd=(0.6, 0.6, 0.6)), light)
        got = mx.render_mitsuba(scene, TOP, 8, 8, spp=16, integrator="direct")[4, 4]
        want = 0.6 * cos * 0.8 * np.array([1.0, 0.5, 0.25])
        np.testing.assert_allclose(got, want, rtol=2e-3)
        lin = weft.Renderer(8, 8).render_linear(scene, TOP)[4, 4, :3]
        np.testing.assert_allclose(lin, want, rtol=2e-3)


def test_glossy_lobe_adds_to_an_undiminished_lambertian():
    """The exported glossy material is Lambert K_D T + a GGX lobe whose normal-incidence peak is
    weft's K_S L (F0 = 8 K_S / (s + 2)): on a plane lit and seen from straight above, weft and
    Mitsuba agree to 1%."""
    light = weft.DirectionalLight(direction=(0.0, -1.0, 0.0), intensity=1.0)
    scene = _plane_scene(weft.Material(kd=(0.5, 0.5, 0.5), ks=(0.04,) * 3, shininess=12.0), light)
    got = mx.render_mitsuba(scene, TOP, 8, 8, spp=256, integrator="direct")[4, 4]
    lin = weft.Renderer(8, 8).render_linear(scene, TOP)[4, 4, :3]
    assert got[0] > 0.5 * 1.05  # the lobe is there
    np.testing.assert_allclose(got, lin, rtol=0.01)
    assert conv.highlight_f0(0.04, 12.0) == pytest.approx(8 * 0.04 / 14)
    assert conv.ior_from_f0(0.04) == pytest.approx(1.5)


@pytest.mark.parametrize("case", ["ground under the sun", "glossy, highlight in view"])
def test_ggx_highlight_is_the_reference_s_coat_under_a_light(case):
    """Material.specular_model = 'ggx' draws the GGX coat the export gives Mitsuba (GGX D, Smith
    masking, the dielectric's Fresnel): on a plane under a directional light, Mitsuba's direct
    light and weft's agree to 0.3% per band of rows (measured 0.03-0.05%), where the seed's
    Blinn-Phong highlight, matched to the coat at its peak, is 1% dark on a sunlit ground (its
    lobe lacks the GGX tail) and 30-70% dark on a glossy highlight seen at a slant. (With
    Schlick's Fresnel instead of the dielectric's the glossy case was 11-15% dark.)"""
    if case == "ground under the sun":  # the cloth scene's ground and sun
        make = lambda h: weft.Material(kd=(0.55, 0.55, 0.52), ks=(0.04,) * 3, shininess=12.0,
                                       specular_model=h)
        direction, blinn_phong_off = (-0.4, -1.0, -0.3), 0.006
    else:
        make = lambda h: scenes.glossy_material((0.3, 0.3, 0.3), 0.04, 60.0, specular_model=h)
        direction, blinn_phong_off = (0.0, -0.5, 0.9), 0.3
    camera = weft.scenes.cloth_camera()
    bands = (slice(14, 24), slice(24, 36), slice(36, 48))
    for model in ("ggx", "blinn_phong"):
        scene = weft.Scene()
        scene.ambient = (0.0, 0.0, 0.0)
        scene.add_mesh(weft.Mesh.plane(8.0, 8.0, 4, 4), make(model), cast_shadows=False)
        scene.add_light(weft.DirectionalLight(direction=direction, intensity=0.9))
        truth = mx.render_mitsuba(scene, camera, 64, 48, spp=256, integrator="direct")
        got = np.asarray(weft.Renderer(64, 48).render_linear(scene, camera))[..., :3]
        plane = truth[..., 0] > 0.0
        assert plane[14:].all()
        ratios = [got[rows][plane[rows]].mean() / truth[rows][plane[rows]].mean()
                  for rows in bands]
        if model == "ggx":
            np.testing.assert_allclose(ratios, 1.0, atol=0.003, err_msg=case)
        else:  # the test can tell the lobes apart
            assert max(abs(r - 1.0) for r in ratios) > blinn_phong_off, (case, ratios)


def _mitsuba_coat_albedo(cos_view: float, alpha: float, f0: float, spp: int = 4096) -> float:
    """What Mitsuba's GGX coat (roughconductor, k = 0: the dielectric's Fresnel) reflects of a
    uniform sky of radiance 1 towards a view at cos_view: its directional albedo."""
    s = math.sqrt(1.0 - cos_view * cos_view)
    scene = mi.load_dict({
        "type": "scene", "integrator": {"type": "direct"},
        "sensor": {"type": "perspective", "fov": 2.0,
                   "to_world": mi.ScalarTransform4f().look_at(
                       origin=[3.0 * s, 0.0, 3.0 * cos_view], target=[0, 0, 0], up=[0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": 4, "height": 4,
                            "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent", "sample_count": spp}},
        "plane": {"type": "rectangle", "to_world": mi.ScalarTransform4f().scale([50, 50, 1]),
                  "bsdf": {"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
                           "eta": conv.ior_from_f0(f0), "k": 0.0}},
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}}})
    return float(np.asarray(mi.render(scene, spp=spp))[..., 0].mean())


def test_coat_albedo_is_what_mitsuba_s_coat_reflects_of_a_uniform_sky():
    """weft.ibl.coat_albedo (the table a GGX coat's reflection is weighted with) against
    Mitsuba's coat under a uniform sky, from grazing to normal views, smooth to rough, F0 0.02 to
    0.5: within 0.6% (measured); the seed's Schlick weight F(n.v) is 10-70% off on the same
    cases, and Karis's Schlick split-sum (dfg_lut) 10-25% low at F0 0.02-0.05."""
    cases = ((0.2, 0.07, 0.04), (0.5, 0.3, 0.04), (0.9, 0.6, 0.1), (0.15, 0.5, 0.5),
             (0.05, 0.2, 0.02))
    schlick_off = []
    for cos_view, alpha, f0 in cases:
        truth = _mitsuba_coat_albedo(cos_view, alpha, f0)
        assert weft.ibl.coat_albedo(cos_view, alpha, f0) == pytest.approx(truth, rel=0.01)
        schlick = f0 + (1.0 - f0) * (1.0 - cos_view) ** 5
        schlick_off.append(abs(schlick / truth - 1.0))
    assert max(schlick_off) > 0.3  # the cases tell the weights apart
    assert weft.ibl.coat_albedo(1.0, 0.0, 0.04) == pytest.approx(0.04, abs=1e-9)  # a mirror
    for bad in ((1.5, 0.1, 0.04), (0.5, -0.1, 0.04), (0.5, 0.1, math.nan)):
        with pytest.raises(ValueError):
            weft.ibl.coat_albedo(*bad)


def test_a_ggx_coat_reflects_a_uniform_sky_as_mitsuba_s_does():
    """A black GGX-coated sphere (F0 0.04, s = 60) under a uniform environment shows only its
    reflection, the coat's albedo towards each pixel's view: weft within 1.5% of Mitsuba over
    rings of the sphere up to 0.95 of its radius (measured 0.2-1.4%; the outermost ring's pixels
    span a steep stretch of the albedo, which Mitsuba integrates and weft samples at the pixel's
    centre). The seed's Schlick-weighted reflection is 13% dark on the middle ring and 32%
    bright towards the rim; with the table interpolated linearly in sqrt(F0) the centre was 3%
    bright."""
    camera = weft.Camera(position=(0.0, 0.0, 3.0), target=(0.0, 0.0, 0.0), fov_y=0.75)
    y, x = np.mgrid[0:64, 0:64]
    radius_px = 32.0 / math.tan(0.375) / math.sqrt(8.0)  # the sphere's silhouette, in pixels
    ring_radius = np.hypot(x + 0.5 - 32.0, y + 0.5 - 32.0) / radius_px
    rings = ((0.0, 0.5), (0.5, 0.8), (0.8, 0.9), (0.9, 0.95))
    for model in ("ggx", "blinn_phong"):
        scene = weft.Scene()
        scene.ambient = (0.0, 0.0, 0.0)
        scene.add_mesh(weft.Mesh.uv_sphere(1.0, 96, 48),
                       scenes.glossy_material((0.0, 0.0, 0.0), 0.04, 60.0, specular_model=model),
                       cast_shadows=False)
        scene.set_environment(weft.ibl.CubeMap(np.ones((6, 16, 16, 3), np.float32)))
        truth = mx.render_mitsuba(scene, camera, 64, 64, spp=512, integrator="direct")
        got = np.asarray(weft.Renderer(64, 64).render_linear(scene, camera))[..., :3]
        ratios = [got[(ring_radius >= a) & (ring_radius < b)].mean()
                  / truth[(ring_radius >= a) & (ring_radius < b)].mean() for a, b in rings]
        if model == "ggx":
            np.testing.assert_allclose(ratios, 1.0, atol=0.015)
        else:
            assert max(abs(r - 1.0) for r in ratios) > 0.1, ratios


def test_environment_diffuse_is_lambert_under_the_radiance():
    """weft's environment diffuse K_D T E / pi is a Lambertian under the radiance: a plane facing
    up under a constant sky of radiance c shows K_D c in Mitsuba and in weft."""
    faces = np.full((6, 16, 16, 3), 0.7, np.float32)
    scene = _plane_scene(weft.Material(kd=(0.5, 0.5, 0.5), environment_diffuse=1.0))
    scene.set_environment(weft.ibl.CubeMap(faces))
    got = mx.render_mitsuba(scene, TOP, 8, 8, spp=1024, integrator="direct")[4, 4]
    lin = weft.Renderer(8, 8).render_linear(scene, TOP)[4, 4, :3]
    np.testing.assert_allclose(got, 0.35, rtol=0.02)  # upper hemisphere only: E = pi c
    np.testing.assert_allclose(lin, 0.35, rtol=0.02)


def test_mitsuba_envmap_axes():
    """The measured mapping: radiance from world direction d is the equirect at u = atan2(x, -z)
    / 2 pi, v = acos(y) / pi. Each axis direction evaluates to the texel our converter put
    there (a cube whose faces hold distinct colours)."""
    mx.import_mitsuba()
    faces = np.zeros((6, 8, 8, 3), np.float32)
    colours = np.eye(3)[[0, 0, 1, 1, 2, 2]] * np.array([1, 2, 1, 2, 1, 2])[:, None]
    faces[:] = colours[:, None, None, :]
    emitter = mi.load_dict(mx.environment_emitter(mi, faces))
    for face, d in enumerate([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1),
                              (0, 0, -1)]):
        d = np.array(d, float) + 0.05 * np.array([0.3, 0.2, 0.1])  # off the u seam
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*(-d / np.linalg.norm(d)))
        np.testing.assert_allclose(np.array(emitter.eval(si)), colours[face], atol=1e-5,
                                   err_msg=f"face {face}")


def test_environment_direction_and_camera_agree_with_weft():
    """One bright patch of sky lights a diffuse sphere: the brightest pixel is the same in
    weft's frame and Mitsuba's (environment axes + camera: fov axis, look-at, no mirroring)."""
    d0 = np.array([0.8, 0.5, 0.33])
    d0 /= np.linalg.norm(d0)
    dirs = weft.reference.ibl.texel_directions(32)
    faces = (0.02 + 40.0 * ((dirs @ d0) > math.cos(math.radians(8.0)))[..., None]
             * np.ones(3)).astype(np.float32)
    scene = weft.Scene()
    scene.ambient = (0.0, 0.0, 0.0)
    scene.add_mesh(weft.Mesh.uv_sphere(1.0, 64, 32),
                   weft.Material(kd=(0.8, 0.8, 0.8), environment_diffuse=1.0))
    scene.set_environment(weft.ibl.CubeMap(faces))
    camera = weft.Camera(position=(0.4, 0.6, 4.0), target=(0.0, 0.0, 0.0), fov_y=0.6)
    ref = mx.render_mitsuba(scene, camera, 64, 48, spp=64, integrator="direct") @ cmp.LUMA
    got = weft.Renderer(64, 48).render_linear(scene, camera)[..., :3] @ cmp.LUMA
    peak = lambda img: np.array(np.unravel_index(np.argmax(img), img.shape))  # noqa: E731
    assert np.abs(peak(ref) - peak(got)).max() <= 3, (peak(ref), peak(got))
    # and the lit side is the +x, +y side (right, top) in both images
    assert peak(got)[1] > 32 and peak(got)[0] < 24


def test_cube_to_equirect_keeps_the_power_of_a_sun():
    """Supersampled nearest lookup: the equirect's integral (sin-theta weights) equals the
    cube's (texel solid angles) for the sky with its small sun, to 1%."""
    faces = envmod.sky_faces(32, sun=True)
    eq = envmod.cube_to_equirect(faces).astype(np.float64)
    h, w = eq.shape[:2]
    theta = (np.arange(h) + 0.5) / h * np.pi
    eq_power = (eq * (np.sin(theta) * (np.pi / h) * (2 * np.pi / w))[:, None, None]).sum((0, 1))
    omega = weft.reference.ibl.texel_solid_angles(32)
    cube_power = (faces * omega[None, ..., None]).sum((0, 1, 2))
    np.testing.assert_allclose(eq_power, cube_power, rtol=0.01)



def test_export_refuses_what_it_cannot_represent():
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(1.0, 1.0), weft.Material())
    scene.add_light(weft.SpotLight())
    with pytest.raises(weft.InvalidArgument, match="SpotLight"):
        mx.export_scene(scene, TOP, 8, 8)
    with pytest.raises(weft.InvalidArgument, match="integrator"):
        mx.export_scene(weft.Scene(), TOP, 8, 8, integrator="bdpt")
    tex = weft.Texture(np.full((2, 2, 4), 255, np.uint8))
    scene = weft.Scene()
    scene.add_mesh(weft.Mesh.plane(1.0, 1.0), weft.Material(texture=tex))
    with pytest.raises(weft.InvalidArgument, match="textured"):
        mx.export_scene(scene, TOP, 8, 8)
    with pytest.raises(weft.InvalidArgument, match="unknown reference scene"):
        scenes.build("teapot")


def test_scene_getters_read_the_scene_back():
    scene, camera, cloth = weft.scenes.cloth_scene(resolution=8, steps=2)
    assert scene.mesh(0).vertex_count == 81 and scene.cloth(0) is None
    assert scene.mesh(2) is None and scene.cloth(2) is cloth
    assert scene.casts_shadows(0) is False and scene.casts_shadows(1) is True
    with pytest.raises(weft.InvalidArgument):
        scene.mesh(7)


# ---------------------------------------------------------------------------------------------
# The reference scenes
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", scenes.SCENES)
def test_picture_against_path_traced_reference(evaluations, name):
    e = evaluations[name]
    regions = e.result["regions"]
    assert np.isfinite(e.reference).all() and e.reference.mean() > 0.02
    for region, (flip_max, rel_max) in TOLERANCES[name].items():
        r = regions[region]
        assert 0.0 < r["flip"] <= flip_max, (name, region, r)
        if rel_max is not None:
            assert r["rel"] <= rel_max, (name, region, r)
    if "whole" in regions and e.info.get("background_drawn"):
        assert regions["whole"]["flip"] <= TOLERANCES[name]["covered"][0]


def test_reference_noise_floor_is_below_the_tolerances(evaluations):
    """A second Mitsuba frame (other seed) against the first: the pair's FLIP is what noise
    alone scores, well below every tolerance (0.014-0.022 at 512 spp against >= 0.063)."""
    ref = scenes.build("spheres_sky")
    e = evaluations["spheres_sky"]
    floor = ev.noise_floor(ref, W, H, SPP, e.reference, e.regions)
    for region, (flip_max, _) in TOLERANCES["spheres_sky"].items():
        assert floor[region] < 0.5 * flip_max, (region, floor)


def test_bounce_light_brings_the_unlit_side_towards_the_path_tracer(evaluations):
    """Where the key light does not reach, the path tracer adds light bounced off the ground.
    Without bounce weft is 41-57% too dark there; the bounce light (the receivers' SH9 captures
    at 15 points per caster, the casters' proxies, two rounds, a glossy caster's reflection of
    its capture) takes it to 2-3% (measured -0.016 and -0.026; the target is 10%; the cloth
    scene's was -0.120 while the sphere under the cloth reflected only the ambient's sky)."""
    for name, floor in (("spheres_sun", -0.08), ("cloth", -0.08)):
        e = evaluations[name]
        unlit = e.result["regions"]["unlit"]
        assert floor < unlit["bias"] < 0.05, (name, unlit)
        ref = scenes.build(name)
        without = ev.evaluate(ref, weft.Renderer(W, H, bounce=False), SPP, reference=e.reference)
        assert without.result["regions"]["unlit"]["bias"] < unlit["bias"] - 0.2, name

def test_the_ground_at_a_draped_sphere_s_foot_under_the_ambient_alone(renderer):
    """The cloth scene with its sun off: the constant ambient (a uniform sky) alone. Where the
    sphere under the cloth meets the ground, the sky is hidden by the sphere and the cloth's
    overhang together, each covering much of what the other does. Summing their proxies'
    cover left that ground no sky: 0.22-0.27 of Mitsuba's there, whole FLIP 0.046; with their
    caps' union 0.79 over the darkest ground (0.7-1.1 per pixel against 8192 spp) and 0.029."""
    ref = scenes.build("cloth")
    light = ref.scene.lights[0]
    light.intensity = 0.0
    ref.scene.set_light(0, light)
    e = ev.evaluate(ref, renderer, SPP)
    regions = e.result["regions"]
    assert regions["whole"]["flip"] < 0.04, regions["whole"]
    luma = np.array([0.2126, 0.7152, 0.0722])
    weft_y, truth_y = e.weft_linear @ luma, e.reference @ luma
    ground = e.debug["instance"] == 0
    ground &= e.debug["mask"] & ~e.regions["edges"]
    open_sky = np.median(truth_y[ground])
    contact = ground & (truth_y < 0.5 * open_sky)  # the darkest ground: at the sphere's foot
    assert contact.sum() > 30
    ratio = weft_y[contact].sum() / truth_y[contact].sum()
    assert 0.7 < ratio < 1.3, ratio
    assert abs(weft_y[ground].sum() / truth_y[ground].sum() - 1.0) < 0.05


def test_a_glossy_ground_alone_reflects_the_ambient_sky():
    """A glossy ground with nothing on it (so nothing casts a shadow and no dome is built)
    under the ambient read as a uniform sky: it reflects that sky as it does beside a caster.
    Before, only a frame with a dome reflected it, and the lone ground came out 5-9% too dark
    against Mitsuba (0.914 / 0.928 / 0.953 over three bands of rows); 0.99-1.005 with Karis's
    analytic DFG (Schlick's Fresnel), 0.996-0.999 with the coat's albedo table."""
    scene = weft.Scene()
    ground = weft.Material(kd=(0.55, 0.55, 0.52), ks=(0.04,) * 3, shininess=12.0)
    ground.ka = ground.kd  # the ambient as a sky's light (conventions)
    scene.add_mesh(weft.Mesh.plane(8.0, 8.0, 4, 4), ground, cast_shadows=False)
    scene.ambient = (0.15, 0.17, 0.2)
    scene.background = scene.ambient
    ref = scenes.ReferenceScene("ground", scene, weft.scenes.cloth_camera(), ground=(0,))
    e = ev.evaluate(ref, weft.Renderer(64, 48), 256)
    ground_px = e.debug["instance"] == 0
    for rows in (slice(14, 24), slice(24, 36), slice(36, 48)):
        band = np.zeros_like(ground_px)
        band[rows] = True
        band &= ground_px
        ratio = e.weft_linear[band].mean() / e.reference[band][..., :3].mean()
        assert abs(ratio - 1.0) < 0.01, (rows, ratio)


# ---------------------------------------------------------------------------------------------
# Anti-aliasing reference
# ---------------------------------------------------------------------------------------------

def test_box_downsample_and_edge_masks():
    img = np.arange(16, dtype=float).reshape(4, 4, 1)
    np.testing.assert_allclose(aa.box_downsample(img, 2)[..., 0], [[2.5, 4.5], [10.5, 12.5]])
    ids = np.zeros((5, 5), int)
    ids[2, 2] = 1
    assert cmp.edge_mask(ids).sum() == 9


def test_aa_reference_measures_todays_aliasing():
    """Without MSAA, silhouettes of the default scene are off by several levels against the
    4x4 supersampled frame (today 6.8/255 at 160 x 120, 7.0 at 128 x 96; ~1/255 in the
    interior)."""
    scene, camera = weft.default_scene()
    out = aa.aa_edge_error(scene, camera, weft.Renderer(160, 120, msaa=1))
    assert out["mesh_edges_pixels"] > 300
    assert out["interior"] < 2.0
    assert 4.0 < out["mesh_edges"] < 10.0, out["mesh_edges"]


def test_aa_targets_at_default_settings():
    """Issue 18's mesh target for the renderer's defaults (4x MSAA): <= 4/255 on mesh edges
    against the point-sampled 4x4 supersampled frame (measured 3.52 at 160 x 120; 6.86 without
    MSAA)."""
    scene, camera = weft.default_scene()
    mesh = aa.aa_edge_error(scene, camera, weft.Renderer(160, 120))
    assert mesh["mesh_edges"] <= 4.0, mesh["mesh_edges"]


def test_hair_aa_target():
    """Issue 18's hair target at the default 4x MSAA: dense plain 1-pixel ribbons within 6/255 on
    hair edges against the point-sampled 4x4 supersampled frame. Hair anti-aliases itself with
    coverage (it is drawn after the MSAA resolve): measured 5.17 at 160 x 120 (5.21 at 128 x 96;
    9.2 when a partly covered pixel's points went to its strands in drawing order, 27 drawn
    aliased, one strand per pixel, as msaa=1 still draws them). The 4x4 reference is itself
    4.3/255 from a 16x16 one here (this frame 2.9), which bounds what any frame can score."""
    hscene, hcamera, width = aa.hair_scene(160, 120)
    r = weft.Renderer(160, 120)
    r.hair_primitive = "ribbons"
    r.hair_width = width
    hair = aa.aa_edge_error(hscene, hcamera, r)
    assert hair["hair_edges_pixels"] > 300
    assert hair["hair_edges"] <= 6.0, hair["hair_edges"]
    r.msaa = 1
    aliased = aa.aa_edge_error(hscene, hcamera, r)
    assert aliased["hair_edges"] > 4.0 * hair["hair_edges"], aliased["hair_edges"]


def test_fur_aa_target():
    """The demo's fur ball (transparent: WBOIT with coverage) meets the issue's hair target at
    the default 4x MSAA: <= 6/255 on hair edges against the point-sampled 4x4 supersampled
    frame (measured 5.19 at 320 x 240, 5.38 at 160 x 120; drawn aliased 9.2 and 8.2)."""
    fscene, fcamera, width = aa.fur_scene(320, 240)
    r = weft.Renderer(320, 240)
    r.hair_primitive = "ribbons"
    r.hair_width = width
    fur = aa.aa_edge_error(fscene, fcamera, r)
    assert fur["hair_edges_pixels"] > 3000
    assert fur["hair_edges"] <= 6.0, fur["hair_edges"]
