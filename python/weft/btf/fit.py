"""The BTF fitting pipeline (SPEC §3.2-3.5) over the compiled kernels, plus error figures.

    samples = load("UBO_WOOL256.zip")                     # frontal view, raw 8-bit values
    linear = fit_linear(samples)                          # T, n, I_A (eq. 4.22)
    spec = fit_specular(samples, linear)                  # specular map + exponent (eq. 4.30)
    bp = fit_blinn_phong(samples, spec.material)          # per-texel nonlinear Blinn-Phong
    deviation(samples, sample_errors(samples, spec.material))["total"]   # in %
"""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np

import weft
from weft import _core
from weft.btf.material import BtfMaterial

Views = Union[str, Sequence[Sequence[float]]]


def load(path: "str | os.PathLike[str]", views: Views = "frontal", gamma: str = "raw",
         threads: int = 0, jpeg_cells: bool = False) -> Any:
    """Reads a Bonn-layout folder or zip. ``views``: "frontal" (θ_v = 0, 81 images), "all", or a
    list of (θ_v, φ_v) degrees. ``gamma``: "raw" (value / 255, as the seed; value / 65535 for
    16-bit PNG) or "linear" ((value / 255)^2.2, (value / 65535)^2.2). File values are taken as
    stored: gAMA/sRGB chunks are ignored (as for JPEG), a PNG with any alpha below opaque is
    refused (IoError). EXR samples are used as stored. macOS ``__MACOSX/`` and ``._*`` entries
    are skipped. ``threads``: 0 = all cores, else 1..256. ``jpeg_cells``: for JPEG files
    (raw gamma, every image grey or YCbCr of one layout) also keep what the files store, the
    quantised DCT coefficients and tables (``samples.jpeg_cells``), which
    :func:`fit_blinn_phong` uses to refine the fit (:mod:`weft.btf.jpeg_cells`)."""
    try:
        path = os.fspath(path)
    except TypeError:
        raise weft.InvalidArgument(f"path must be a str or os.PathLike, got "
                                   f"{type(path).__name__}") from None
    if not isinstance(path, str):
        raise weft.InvalidArgument(f"path must be a str or os.PathLike, got {type(path).__name__}")
    if isinstance(views, str):
        if views not in ("frontal", "all"):
            raise weft.InvalidArgument(f"views must be 'frontal', 'all' or a list, got {views!r}")
        arg = None if views == "all" else np.zeros((1, 2), np.float32)
    else:
        arg = np.asarray(views, dtype=np.float64).reshape(-1, 2)
    return _core.btf_load(str(path), arg, gamma, int(threads), bool(jpeg_cells))


@dataclass
class LinearFit:
    """The seed's linear fit: T (texture), n (not normalised), I_A, and the dark texels."""

    texture: np.ndarray
    normal: np.ndarray
    ambient: np.ndarray
    dark: np.ndarray
    dark_texels: int
    dark_channels: int

    def core(self) -> Dict[str, Any]:
        return dict(texture=self.texture, normal=self.normal, ambient=self.ambient)

    def material(self, samples: Any) -> BtfMaterial:
        """The seed's maps as a material (ρ = T|n|, a = I_A/|n|, unit n; linear diffuse)."""
        return BtfMaterial.from_core(_core.btf_material_from_linear(samples, self.core()))

    def __repr__(self) -> str:
        h, w = self.texture.shape[:2]
        return (f"<weft.btf.LinearFit {w}x{h}, {self.dark_texels} dark texels, "
                f"{self.dark_channels} dark channels>")


def fit_linear(samples: Any, robust: bool = False, robust_iterations: int = 4,
               dark_threshold: float = 1e-4, threads: int = 0) -> LinearFit:
    """T = per-texel mean; n, I_A by least squares over all samples. ``robust``: IRLS with
    Tukey's biweight, samples with n.l <= 0 dropped (for cast shadows and highlights)."""
    return LinearFit(**_core.btf_fit_linear(samples, robust, int(robust_iterations),
                                            float(dark_threshold), int(threads)))


def solve_linear(samples: Any, texture: np.ndarray, threads: int = 0) -> LinearFit:
    """The same least squares with a given texture instead of the mean."""
    return LinearFit(**_core.btf_solve_linear(samples, texture, int(threads)))


@dataclass
class SpecularFit:
    material: BtfMaterial
    curve: np.ndarray        # total squared error for exponents 1..max (NaN = not evaluated)
    specular_sample: int

    @property
    def exponent(self) -> float:
        return self.material.exponent


def fit_specular(samples: Any, linear: LinearFit, flat_specular_normal: bool = True,
                 max_exponent: int = 4096, per_texel: bool = False,
                 threads: int = 0) -> SpecularFit:
    """Specular map = residual of the θ_l = 0 sample; exponent search over 1..max_exponent.
    ``flat_specular_normal``: eq. 4.30 (n_s = (0,0,1)), else eq. 4.29 (fitted normal)."""
    r = _core.btf_fit_specular(samples, linear.core(), bool(flat_specular_normal),
                               int(max_exponent), bool(per_texel), int(threads))
    return SpecularFit(BtfMaterial.from_core(r["maps"]), r["curve"], int(r["specular_sample"]))


@dataclass
class NonlinearFit:
    material: BtfMaterial
    solver: str
    mean_iterations: float
    shadowed_fraction: float = 0.0  # samples left out as cast shadows / all samples
    noise: float = 0.0  # the data's noise the visibility pass used (0 without it)
    #: exponent="pooled": {"mean": the material's exponent, "spread": τ of ln e, "texels",
    #: "error_scale": the factor its error bars were widened by (exponent_pool.error_scale)}
    exponent_pool: Optional[Dict[str, float]] = None


#: fit_blinn_phong's choices for the exponent
EXPONENT_MODES = ("per_texel", "pooled", "fixed")


def fit_blinn_phong(samples: Any, seed: BtfMaterial, solver: str = "auto",
                    max_iterations: int = 30, min_exponent: float = 1.0,
                    max_exponent: Optional[float] = None, threads: int = 0,
                    flat_specular_normal: bool = False, visibility: bool = True,
                    luminance_normals: bool = False, jpeg_cells: bool = False,
                    noise: Optional[float] = None, exponent: str = "per_texel",
                    per_texel: Optional[NonlinearFit] = None) -> NonlinearFit:
    """Per-texel Blinn-Phong in the renderer's model, seeded by ``seed`` (normal, exponent):
    ``P = albedo (ambient + max(n.l, 0)) + specular [n.l > 0] max(n_s.h, 0)^e``.

    Every texel stays physically valid: albedo, ambient, specular >= 0, unit normals with
    n_z > 0, ``min_exponent <= e <= max_exponent`` (the solver searches inside that space);
    ``max_exponent`` None: :func:`resolvable_exponent` of the samples (519 for the Bonn
    frontal layout), the narrowest lobe the light directions can pin down. A texel whose fitted
    lobe no sample sees at >= 1% of its peak gets no highlight (k = 0): its k and e would
    be unconstrained by the data (needle lobes).
    ``flat_specular_normal``: the highlight around n_s = (0, 0, 1) (seed eq. 4.30) instead of
    the fitted normal. ``visibility``: samples far darker than the fit (cast shadows) are left
    out and the texel refitted; ``shadowed_fraction`` says how many. The test's noise level
    (at most twice ``noise``, the standard deviation of a sample's channel sum) is estimated from
    the samples when ``noise`` is None (:func:`shadow_noise`; returned as ``noise``): a dataset
    fitted in parts (bands of rows) passes the whole dataset's, so each part gives exactly its
    texels of the whole fit. ``luminance_normals``: the
    normal and exponent are fitted to the luma (BT.601), the colours to RGB at that fit: for
    JPEG data, whose chroma is stored at half resolution and coarser precision. ``solver``: "auto"
    (= "builtin", the fastest and as accurate), "builtin" (Levenberg-Marquardt by variable
    projection with non-negative least squares), "ceres" (when built with it).
    ``jpeg_cells``: for samples loaded from JPEG (``samples.jpeg_cells``), refine the fit against
    what the files store, the quantised DCT cells of each 8 x 8 luma block, jointly over the
    block's texels (:func:`weft.btf.jpeg_cells.refine`; samples left out as cast shadows stay
    out); no effect on other samples. Off by default: on JPEG q90 it lowers the normal error
    (by 4-41% on four random materials at 64²) but not always the exponent and k_s error, and
    costs ~1 ms per texel-block of 81 samples in NumPy.
    ``exponent``: "per_texel" (each texel's own), "pooled" (the per-texel fit, then its exponents
    pooled over the material by empirical Bayes, :mod:`weft.btf.exponent_pool`: one exponent
    where the texels' spread is what their errors explain, each its own where the material's
    exponents really differ; then n, ρ, a, k fitted again at those exponents; ``exponent_pool``
    says what was found; with ``jpeg_cells`` the exponents pooled are the cell-refined ones and
    the final fit is not refined again), or "fixed" (the seed's exponent map, else its
    exponent, kept). ``per_texel``: with "pooled", this fit of the same samples, seed and options
    with ``exponent="per_texel"`` when it is already made (``btf fit`` has it): it is pooled
    instead of fitting it again."""
    if exponent not in EXPONENT_MODES:
        raise weft.InvalidArgument(f"exponent must be 'per_texel', 'pooled' or 'fixed', got "
                                   f"{exponent!r}")
    if per_texel is not None and exponent != "pooled":
        raise weft.InvalidArgument("per_texel is the fit to pool: only with exponent='pooled'")

    def core_fit(start: BtfMaterial, fixed: bool, level: float) -> NonlinearFit:
        r = _core.btf_fit_blinn_phong(samples, start.core_maps(), solver, int(max_iterations),
                                      float(min_exponent),
                                      0.0 if max_exponent is None else float(max_exponent),
                                      int(threads), bool(flat_specular_normal), bool(visibility),
                                      bool(luminance_normals), level, fixed_exponent=fixed)
        return NonlinearFit(BtfMaterial.from_core(r["maps"]), r["solver"], r["mean_iterations"],
                            float(r["shadowed_fraction"]), float(r["noise"]))

    def refine_cells(f: NonlinearFit) -> None:
        from weft.btf import jpeg_cells as cells
        e_max = resolvable_exponent(samples) if max_exponent is None else float(max_exponent)
        mask = cells.shadow_mask(samples, f.material) if f.shadowed_fraction > 0 else None
        f.material, _ = cells.refine(samples, f.material, max_exponent=e_max, shadowed=mask)

    use_cells = jpeg_cells and getattr(samples, "jpeg_cells", None) is not None
    fit = per_texel if per_texel is not None else core_fit(seed, exponent == "fixed",
                                                           _noise(noise))
    if exponent == "pooled" and fit.material.specular is not None and \
            np.any(fit.material.specular > 0):
        from weft.btf import exponent_pool
        from weft.btf import jpeg_cells as cells

        # with the cells, the exponents pooled are the refined ones: the decoded values put
        # every coefficient at its cell's centre, which broadens highlights alike in all
        # texels and biases the per-texel exponents low together (random0.jpg at 64²: the
        # pooled exponent 69 -> 79 with the cells, truth 82), a bias no pooling removes
        pooled_from = dataclasses.replace(fit)
        if use_cells:
            refine_cells(pooled_from)
        m = pooled_from.material
        mask = cells.shadow_mask(samples, m) if fit.shadowed_fraction > 0 else None
        variance = exponent_pool.eta_variance(samples, m, bool(luminance_normals), mask)
        eta = np.log(m.exponent_map.astype(np.float64))
        scale = exponent_pool.error_scale(eta, variance)
        eta, info = exponent_pool.pool(eta, variance * scale)
        info["error_scale"] = float(np.sqrt(scale))
        start = dataclasses.replace(m, exponent_map=np.exp(eta).astype(np.float32))
        # the same cast-shadow threshold as the first pass (its noise, estimated or given)
        first = fit
        fit = core_fit(start, True, first.noise if visibility else _noise(noise))
        fit.mean_iterations += first.mean_iterations
        fit.exponent_pool = info
    elif use_cells:
        refine_cells(fit)
    return fit


def _noise(noise: Optional[float]) -> float:
    if noise is None:
        return 0.0
    if isinstance(noise, bool) or not np.isfinite(noise) or not noise > 0:
        raise weft.InvalidArgument(f"noise must be a positive number or None, got {noise!r}")
    return float(noise)


def shadow_noise(samples: Any, seed: BtfMaterial, flat_specular_normal: bool = False,
                 min_exponent: float = 1.0, max_exponent: Optional[float] = None,
                 luminance_normals: bool = False, threads: int = 0) -> float:
    """The noise level :func:`fit_blinn_phong` estimates for its cast-shadow test with the same
    arguments and ``noise=None``: the median, over up to 1024 texels spread evenly over the
    image, of the robust standard deviation of their first fit's residuals (channel sums) under
    steep light (θ_l <= 31°, which cast shadows rarely reach)."""
    return float(_core.btf_blinn_phong_noise(
        samples, seed.core_maps(), float(min_exponent),
        0.0 if max_exponent is None else float(max_exponent), int(threads),
        bool(flat_specular_normal), bool(luminance_normals)))


def resolvable_exponent(samples: Any, fraction: float = 0.01) -> float:
    """The largest Blinn-Phong exponent the samples' directions resolve: a lobe cos^e centred
    on one sample's half vector keeps ``fraction`` of its peak at the nearest other half vector
    (median spacing δ over the samples): e_max = ln(1/fraction) / -ln cos δ. For the Bonn frontal
    layout δ = 7.6° (half the 15° light spacing), e_max = 519."""
    return float(_core.btf_resolvable_exponent(samples, float(fraction)))


@dataclass
class LafortuneFit:
    """Diffuse term plus 1-2 Lafortune lobes per texel (seed eq. 4.10/4.11, C_z = 1):
    P = diffuse max(n.l, 0) + ambient + Σ_j lobe_albedo_j max(C_x l_x v_x + C_y l_y v_y +
    C_z l_z v_z, 0)^e; ``lobe_shape`` (H, W, lobes, 4) holds (C_x, C_y, C_z, e)."""

    normal: np.ndarray
    diffuse: np.ndarray
    ambient: np.ndarray
    lobe_albedo: np.ndarray
    lobe_shape: np.ndarray
    mean_iterations: float

    def errors(self, samples: Any, threads: int = 0) -> np.ndarray:
        """Per-sample mean squared error (S,)."""
        fit = dict(normal=self.normal, diffuse=self.diffuse, ambient=self.ambient,
                   lobe_albedo=self.lobe_albedo, lobe_shape=self.lobe_shape)
        return _core.btf_lafortune_errors(samples, fit, int(threads))

    def __repr__(self) -> str:
        h, w, lobes = self.lobe_shape.shape[:3]
        return f"<weft.btf.LafortuneFit {w}x{h}, {lobes} lobe(s)>"


def fit_lafortune(samples: Any, seed: BtfMaterial, lobes: int = 1, max_iterations: int = 30,
                  threads: int = 0, visibility: bool = False,
                  fixed_normal: bool = False) -> LafortuneFit:
    """Per-texel diffuse + ``lobes`` Lafortune lobes (built-in LM), seeded by the normal and
    exponent of ``seed`` (the Blinn-Phong fit is the best seed under cast shadows).
    ``visibility``: cast shadows estimated per sample and left out, as in
    :func:`fit_blinn_phong` (off by default: with a Blinn-Phong normal kept it only raises the
    deviation over all samples; with a free normal it helps on some cast-shadow data and hurts
    on other). ``fixed_normal``: keep the seed's normal (with a frontal view the
    lobe depends on l_z only and trades off with the diffuse term, so the normal is poorly
    determined by this model; a Blinn-Phong seed pins it down)."""
    return LafortuneFit(**_core.btf_fit_lafortune(samples, seed.core_maps(), int(lobes),
                                                  int(max_iterations), int(threads),
                                                  bool(visibility), bool(fixed_normal)))


def have_ceres() -> bool:
    """True when weft was built with Ceres Solver."""
    return bool(_core.btf_have_ceres())


def sample_errors(samples: Any, material: BtfMaterial, reconstruct: bool = False,
                  threads: int = 0, drawn: bool = True) -> Any:
    """Per-sample mean squared error (S,) over texels and channels of the material against the
    samples; with ``reconstruct`` also the reconstruction (S, 3, H, W). ``drawn`` (default):
    the material as the renderer draws it, :meth:`BtfMaterial.as_drawn` (8-bit maps with
    their scales, decoded normals, n.l clamped at 0 with no highlight where n.l <= 0, the
    exponent map drawn); False: the float model as given (its own ``clamp_diffuse``)."""
    maps = material.as_drawn() if drawn else material
    return _core.btf_sample_errors(samples, maps.core_maps(), bool(reconstruct), int(threads))


def deviation(samples: Any, errors: np.ndarray) -> Dict[str, Any]:
    """SPEC §3.4: total deviation (mean squared difference over samples, texels, channels of
    [0, 1] values, x 100, in %), per θ_l group and per view."""
    errors = np.asarray(errors, dtype=np.float64)
    angles = np.asarray(samples.angles)
    if errors.shape != (len(angles),):
        raise weft.InvalidArgument(
            f"errors must hold one value per sample, shape ({len(angles)},) "
            f"(sample_errors), got shape {errors.shape}")
    if not np.all(np.isfinite(errors)):
        raise weft.InvalidArgument("errors must be finite")
    groups = {f"{int(t)}": float(errors[angles[:, 0] == t].mean() * 100)
              for t in np.unique(angles[:, 0])}
    views: Dict[str, float] = {}
    for tv, pv in np.unique(angles[:, 2:4], axis=0):
        sel = (angles[:, 2] == tv) & (angles[:, 3] == pv)
        views[f"tv{int(tv):03d}_pv{int(pv):03d}"] = float(errors[sel].mean() * 100)
    return {"total": float(errors.mean() * 100), "groups": groups, "views": views}


def angular_error_deg(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle in degrees between two normal maps (normalised here), per texel."""
    a = np.asarray(a, np.float64)
    b = np.asarray(b, np.float64)
    a = a / np.maximum(np.linalg.norm(a, axis=-1, keepdims=True), 1e-300)
    b = b / np.maximum(np.linalg.norm(b, axis=-1, keepdims=True), 1e-300)
    cross = np.linalg.norm(np.cross(a, b), axis=-1)
    return np.degrees(np.arctan2(cross, np.sum(a * b, axis=-1)))


def normal_stats(fitted: np.ndarray, truth: np.ndarray) -> Dict[str, float]:
    """Mean and 95th percentile angular error (degrees)."""
    err = angular_error_deg(fitted, truth)
    return {"mean_deg": float(err.mean()), "p95_deg": float(np.percentile(err, 95))}

