"""Hair under an environment is lit along its tangent (glsl/common/hair_lighting.glsl,
hairEnvironmentDiffuse), held against a converged numerical integration of the Kajiya-Kay diffuse
kernel over every cube texel with its solid angle: (1 / pi^2) sum L(w) sin(t, w) dw."""

from __future__ import annotations

import numpy as np
import weft
import weft.ibl as ibl
from weft.reference import ibl as ref

SIZE = 32


def side_light(d: np.ndarray) -> np.ndarray:
    """Dim all round, bright towards +x (a window), warm from above."""
    return (0.05 + 3.0 * np.maximum(d[:, :1], 0.0) ** 3 * np.array([1.0, 0.95, 0.9])
            + 0.6 * np.maximum(d[:, 1:2], 0.0) ** 2 * np.array([0.5, 0.6, 1.0]))


def env_faces() -> np.ndarray:
    return side_light(ref.texel_directions(SIZE).reshape(-1, 3)).reshape(6, SIZE, SIZE, 3) \
        .astype(np.float32)


def truth(faces: np.ndarray, tangents: np.ndarray) -> np.ndarray:
    d = ref.texel_directions(SIZE).reshape(-1, 3)
    w = np.broadcast_to(ref.texel_solid_angles(SIZE), (6, SIZE, SIZE)).reshape(-1)
    sin = np.sqrt(np.maximum(1.0 - (tangents @ d.T) ** 2, 0.0))
    return (sin * w) @ faces.reshape(-1, 3).astype(np.float64) / np.pi ** 2


def render(strand_dirs) -> dict:
    scene = weft.Scene()
    scene.ambient = (0.0, 0.0, 0.0)
    pts = []
    for k, a in enumerate(strand_dirs):  # straight strands through a column of points
        s = np.linspace(-0.3, 0.3, 7)[:, None]
        pts.append(np.array([0.0, 0.25 * (k - 1), 0.0]) + s * np.asarray(a, np.float64))
    strands = weft.HairStrands(np.concatenate(pts).astype(np.float32), default_segments=6)
    mat = weft.HairMaterial("kajiya_kay", diffuse=(0.6, 0.5, 0.4))
    mat.specular = (0.0, 0.0, 0.0)  # the environment lights the diffuse term only
    scene.add_hair(strands, mat)
    scene.set_environment(ibl.CubeMap(env_faces()))
    r = weft.Renderer(64, 64)
    r.hair_primitive = "ribbons"
    r.hair_width = 0.06  # thickness 1: 0.06 m, a few pixels wide
    return r.render_debug(scene, weft.Camera((0.3, 0.1, 1.6), (0, 0, 0), (0, 1, 0), 0.9))


def test_environment_lights_hair_along_its_tangent() -> None:
    # three strands: towards the bright side (+x), up (+y), and towards the camera-ish (+z)
    d = render([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.3, 1.0)])
    mask = d["hair"] >= 0
    assert mask.sum() > 60
    t = d["normal"][mask].astype(np.float64)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    albedo = d["albedo"][mask].astype(np.float64)
    got = d["linear"][mask][:, :3].astype(np.float64)
    faces = env_faces()
    want = truth(faces, t) * albedo
    sh = ref.project_sh9(faces)
    old = 0.5 / np.sqrt(np.pi) * sh[0] * albedo  # the former mean term: L_00 Y_00 per channel
    lum = np.array([0.2126, 0.7152, 0.0722])
    err_new = np.abs(got - want) @ lum / (want @ lum)
    err_old = np.abs(old - want) @ lum / (want @ lum)
    print(f"relative error vs numerical truth: directional max {err_new.max():.3%} mean "
          f"{err_new.mean():.3%}; mean-irradiance term max {err_old.max():.3%} mean "
          f"{err_old.mean():.3%}")
    assert err_new.max() < 0.03
    assert err_old.max() > 0.15  # the flat term is far off for some tangents
    # a strand pointing at the bright side sees it only at grazing: darker than one across it
    along_x = np.abs(t[:, 0]) > 0.95
    along_y = np.abs(t[:, 1]) > 0.95
    assert along_x.sum() > 10 and along_y.sum() > 10
    gx = (got[along_x] / albedo[along_x]) @ lum
    gy = (got[along_y] / albedo[along_y]) @ lum
    assert gx.mean() < 0.8 * gy.mean()


def test_funk_hecke_coefficients_of_the_fibre_kernel() -> None:
    # Lambda_l = 2 pi * integral of sqrt(1 - x^2) P_l(x) dx (the constants in the shader)
    x = np.linspace(-1.0, 1.0, 200001)
    k = np.sqrt(1.0 - x * x)
    lam0 = 2 * np.pi * np.trapezoid(k, x)
    lam1 = 2 * np.pi * np.trapezoid(k * x, x)
    lam2 = 2 * np.pi * np.trapezoid(k * 0.5 * (3 * x * x - 1), x)
    np.testing.assert_allclose([lam0, lam1, lam2], [np.pi ** 2, 0.0, -np.pi ** 2 / 8], atol=1e-5)
