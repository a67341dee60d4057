"""Independent truth for the dome's shadows (SPEC §4.5): a sphere above a ground plane under an
environment cube map. The ground's shadowed diffuse radiance is K_D / pi * integral of
L(w) V(x, w) cos(theta) dw, evaluated here by brute force over every cube texel (its direction and
exact solid angle) with ray-sphere visibility -- written from the equations, calling nothing of
weft. Also: the ghost metric (distinct minima of the shadow along circles around its centre)."""

from __future__ import annotations

from typing import Dict, Sequence, Tuple

import numpy as np
from scipy import ndimage, signal

LUMA = np.array([0.2126, 0.7152, 0.0722])
# Vulkan cube face selection: direction = major + u * s_axis + v * t_axis (faces +X -X +Y -Y +Z -Z)
FACES = np.array([
    [[1, 0, 0], [0, 0, -1], [0, -1, 0]], [[-1, 0, 0], [0, 0, 1], [0, -1, 0]],
    [[0, 1, 0], [1, 0, 0], [0, 0, 1]], [[0, -1, 0], [1, 0, 0], [0, 0, -1]],
    [[0, 0, 1], [1, 0, 0], [0, -1, 0]], [[0, 0, -1], [-1, 0, 0], [0, -1, 0]]], np.float64)


def texels(size: int) -> Tuple[np.ndarray, np.ndarray]:
    """Unit directions (6, S, S, 3) and exact solid angles (S, S) of the texels of a cube map:
    the solid angle of the face rectangle [0, u] x [0, v] at unit distance is
    atan(u v / sqrt(1 + u^2 + v^2)) (Girard / the standard cube-map result)."""
    edge = np.linspace(-1.0, 1.0, size + 1)
    c = 0.5 * (edge[1:] + edge[:-1])
    u, v = np.meshgrid(c, c, indexing="xy")
    d = FACES[:, 0, None, None] + u[None, ..., None] * FACES[:, 1, None, None] \
        + v[None, ..., None] * FACES[:, 2, None, None]
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    eu, ev = np.meshgrid(edge, edge, indexing="xy")
    a = np.arctan2(eu * ev, np.sqrt(1.0 + eu ** 2 + ev ** 2))
    omega = a[1:, 1:] - a[1:, :-1] - a[:-1, 1:] + a[:-1, :-1]
    return d, omega


def env_faces(env, size: int, supersample: int = 2) -> np.ndarray:
    """Cube faces (6, S, S, 3) float32: env averaged over ss x ss points per texel."""
    d, _ = texels(size * supersample)
    vals = env(d.reshape(-1, 3)).reshape(6, size, supersample, size, supersample, 3)
    return vals.mean(axis=(2, 4)).astype(np.float32)


def sky(d: np.ndarray) -> np.ndarray:
    up = np.clip(d[:, 1:2], -1.0, 1.0)
    zenith = np.array([0.4, 0.6, 1.0]) * (0.5 + 0.8 * np.maximum(up, 0.0)) + 0.1 * d[:, :1]
    return np.where(up > 0, zenith, np.array([0.25, 0.2, 0.15])) + 0.05


def with_sun(direction: Sequence[float], radius: float, radiance: float):
    s = np.asarray(direction, np.float64)
    s /= np.linalg.norm(s)

    def env(d: np.ndarray) -> np.ndarray:
        return (sky(d) + ((d @ s) >= np.cos(radius))[:, None] * radiance
                * np.array([1.0, 0.95, 0.85]))

    return env


def ground_truth(faces: np.ndarray, points: np.ndarray, centre, radius: float,
                 normal=(0.0, 1.0, 0.0)) -> Tuple[np.ndarray, np.ndarray]:
    """Per point (N, 3): (integral of L V cos dw, integral of L cos dw), both RGB (N, 3); the
    diffuse radiance is K_D / pi times the first."""
    faces = np.asarray(faces, np.float64)
    d, omega = texels(faces.shape[1])
    d = d.reshape(-1, 3)
    w = np.broadcast_to(omega, faces.shape[:3]).reshape(-1)
    cos = d @ np.asarray(normal, np.float64)
    up = cos > 0.0
    d, lw = d[up], faces.reshape(-1, 3)[up] * (w[up] * cos[up])[:, None]
    full = lw.sum(axis=0)
    c = np.asarray(centre, np.float64)
    out = np.empty((len(points), 3))
    for k in range(0, len(points), 256):
        oc = c[None, :] - points[k:k + 256]                  # (n, 3)
        b = oc @ d.T                                          # (n, T): distance to closest approach
        far = np.einsum("nk,nk->n", oc, oc)[:, None] - radius * radius
        hit = (b > 0.0) & (b * b - far > 0.0)
        out[k:k + 256] = full[None, :] - hit.astype(np.float64) @ lw
    return out, np.broadcast_to(full, out.shape).copy()


def circle_minima(ratio: np.ndarray, pixel_of, centre_xz, radii, prominence: float = 0.01,
                  angles: int = 180, smooth: float = 3.0) -> Dict[str, np.ndarray]:
    """Samples `ratio` (H, W; shadowed / unshadowed) along circles on the ground (y = 0) around
    centre_xz; `pixel_of(x, z)` gives (row, col). Returns per circle the number of distinct local
    minima (prominence above `prominence`) of the samples smoothed along the circle (Gaussian,
    `smooth` samples), and the total variation of the unsmoothed samples around the circle.

    The smoothing (3 samples = 6 degrees) keeps the ghosts' copies, 22.5 degrees apart with 16
    dome lights, and removes the taps' pixel-to-pixel noise, whose minima depend on which hash
    each pixel's point draws: unsmoothed, the soft dome's excess over the truth went 5-9 over 12
    camera offsets of 1e-4 on lavapipe and 10 on an NVIDIA H200 (a different draw of the same
    noise); smoothed 4-5, against 19 for 16 hard one-tap copies (21-27 unsmoothed)."""
    t = np.linspace(0.0, 2.0 * np.pi, angles, endpoint=False)
    counts, tv = [], []
    for r in radii:
        x, z = centre_xz[0] + r * np.cos(t), centre_xz[1] + r * np.sin(t)
        rows, cols = pixel_of(x, z)
        s = ndimage.map_coordinates(ratio, [rows, cols], order=1, mode="nearest", cval=np.nan)
        # off the ground (the sphere's image; the same pixels in both images compared): as bright
        # as the brightest sample, so that no minimum is made there
        s = np.where(np.isfinite(s), s, np.nanmax(s))
        smoothed = ndimage.gaussian_filter1d(s, smooth, mode="wrap") if smooth > 0 else s
        wrapped = np.concatenate([smoothed, smoothed, smoothed])
        peaks, _ = signal.find_peaks(-wrapped, prominence=prominence)
        counts.append(int(np.sum((peaks >= angles) & (peaks < 2 * angles))))
        tv.append(float(np.abs(np.diff(np.append(s, s[0]))).sum()))
    return dict(minima=np.array(counts), tv=np.array(tv))


CENTRE, RADIUS = np.array([0.0, 0.8, 0.0]), 0.5


def scene_and_camera(weft, faces, lights: int, ground_casts: bool = False, **kw):
    """The sphere (a caster, K_D = 1) above a ground (K_D = 1, no specular, casts nothing) under
    `faces`, seen from straight above so that ground points map affinely to pixels."""
    import weft.ibl
    scene = weft.Scene()
    scene.ambient = (0.0, 0.0, 0.0)
    mat = weft.Material(kd=(1.0, 1.0, 1.0), ks=(0.0, 0.0, 0.0), environment_diffuse=1.0)
    scene.add_mesh(weft.Mesh.plane(8.0, 8.0), mat, cast_shadows=ground_casts)
    m = np.eye(4, dtype=np.float32)
    m[:3, :3] *= RADIUS
    m[:3, 3] = CENTRE
    scene.add_mesh(weft.Mesh.uv_sphere(1.0, 48, 24), mat, transform=m)
    scene.set_environment(weft.ibl.Environment(faces), dome_lights=lights, **kw)
    camera = weft.Camera(position=(0.0, 4.5, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0),
                         fov_y=0.8)
    return scene, camera


def measure(weft, renderer, faces, lights: int, truth=None, ground_casts: bool = False,
            **kw) -> Dict[str, object]:
    """Renders the scene; compares the ground's shadow ratio (dome-shadowed / unshadowed
    radiance, which cancels SH9's irradiance error) and its absolute radiance with the truth."""
    scene, camera = scene_and_camera(weft, faces, lights, ground_casts, **kw)
    debug = renderer.render_debug(scene, camera)
    stats = renderer.stats
    image = renderer.render_linear(scene, camera)[..., :3].astype(np.float64)
    plain = renderer.render_linear(scene_and_camera(weft, faces, 0)[0], camera)[..., :3]
    ground = debug["mask"] & (debug["instance"] == 0)
    pos = debug["position"].astype(np.float64)
    if truth is None:
        vis, full = ground_truth(faces, pos[ground], CENTRE, RADIUS)
        truth = dict(vis=vis, full=full, ground=ground)
    assert np.array_equal(truth["ground"], ground)
    want_ratio = np.ones(ground.shape)
    want_ratio[ground] = (truth["vis"] @ LUMA) / (truth["full"] @ LUMA)
    got_ratio = np.full(ground.shape, np.nan)
    want_ratio[~ground] = np.nan
    got_ratio[ground] = (image[ground] @ LUMA) / np.maximum(plain[ground] @ LUMA, 1e-12)
    shadow = ground & (want_ratio < 0.98)
    rel = np.abs(got_ratio - want_ratio)[shadow] / want_ratio[shadow]
    abs_rel = (np.abs(image[ground] @ LUMA - truth["vis"] @ LUMA / np.pi) /
               (truth["vis"] @ LUMA / np.pi))
    # affine pixel <-> ground map from the debug positions (camera straight down)
    rows, cols = np.nonzero(ground)
    a = np.c_[pos[ground][:, 0], pos[ground][:, 2], np.ones(len(rows))]
    fit_r = np.linalg.lstsq(a, rows, rcond=None)[0]
    fit_c = np.linalg.lstsq(a, cols, rcond=None)[0]
    pixel_of = lambda x, z: (fit_r[0] * x + fit_r[1] * z + fit_r[2],
                             fit_c[0] * x + fit_c[1] * z + fit_c[2])
    def core(ratio):  # centre (x, z) of the darker half of the shadow
        dark = np.where(ground, 1.0 - np.nan_to_num(ratio, nan=1.0), 0.0)
        dark = np.where(dark > 0.5 * dark.max(), dark, 0.0)
        if dark.sum() <= 0.0:
            return np.array([np.nan, np.nan])
        return np.array([np.sum(dark * pos[..., 0]), np.sum(dark * pos[..., 2])]) / dark.sum()

    centre = core(want_ratio)
    # circles outside the sphere's image (radius ~0.75 on the ground from this camera)
    radii = np.array([0.8, 1.0, 1.2, 1.5])
    g, w = (circle_minima(got_ratio, pixel_of, centre, radii),
            circle_minima(want_ratio, pixel_of, centre, radii))
    passes = [p for p in stats["passes"] if p["name"].startswith("dome")]
    return dict(truth=truth, got_ratio=got_ratio, want_ratio=want_ratio, image=image,
                mean_rel=float(rel.mean()), p95_rel=float(np.percentile(rel, 95)),
                abs_mean_rel=float(abs_rel.mean()), core=core(got_ratio), core_truth=centre,
                minima=g["minima"], minima_truth=w["minima"], tv=g["tv"], tv_truth=w["tv"],
                stats=stats, dome_passes=passes)
