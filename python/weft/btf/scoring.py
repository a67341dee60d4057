"""Scoring fitted BTF models the same way in the CLI report and the benchmark (issue 12).

A :class:`Scored` model is a :class:`BtfMaterial` (drawable: its deviation is taken as the renderer
draws it, ``sample_errors(..., drawn=True)``, and also as the float model claims it) or a
:class:`LafortuneFit` (not drawable by the renderer: scored by its own model and labelled
"not drawn"). Against a ground truth: normal angular error, albedo and ambient-term errors, median
relative errors of k_s and the exponent; and, without a truth, the number of texels whose
parameters lie outside the physical space.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from weft.btf import fit as btf_fit
from weft.btf.fit import LafortuneFit
from weft.btf.material import BtfMaterial

Model = Union[BtfMaterial, LafortuneFit]

#: The physical exponent range the fits are asked to stay in (fit_blinn_phong's defaults).
EXPONENT_RANGE = (1.0, 4096.0)
UNIT_TOLERANCE = 1e-3


@dataclass
class Scored:
    """One fitted model with its deviations (%, SPEC §3.4) and per-sample errors."""

    name: str
    model: Model
    seconds: float
    drawn: Optional[Dict[str, Any]]   # deviation() as drawn; None when not drawable
    fitted: Dict[str, Any]            # deviation() of the model as fitted (float, unclamped)
    drawn_errors: Optional[np.ndarray]
    fitted_errors: np.ndarray
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def drawable(self) -> bool:
        return self.drawn is not None

    @property
    def deviation(self) -> float:
        """The deviation that ranks models: as drawn, or the model's own when not drawable."""
        return float((self.drawn or self.fitted)["total"])

    @property
    def errors(self) -> np.ndarray:
        return self.drawn_errors if self.drawn_errors is not None else self.fitted_errors

    @property
    def label(self) -> str:
        return self.name if self.drawable else f"{self.name} (not drawn)"


def score(samples: Any, name: str, model: Model, seconds: float = 0.0,
          **extra: Any) -> Scored:
    """Deviation of ``model`` as drawn and as fitted (Lafortune: as fitted only)."""
    if isinstance(model, LafortuneFit):
        errors = np.asarray(model.errors(samples), np.float64)
        return Scored(name, model, seconds, None, btf_fit.deviation(samples, errors), None,
                      errors, dict(extra))
    drawn = np.asarray(btf_fit.sample_errors(samples, model, drawn=True), np.float64)
    fitted = np.asarray(btf_fit.sample_errors(samples, model, drawn=False), np.float64)
    return Scored(name, model, seconds, btf_fit.deviation(samples, drawn),
                  btf_fit.deviation(samples, fitted), drawn, fitted, dict(extra))


#: A Blinn-Phong fit that left out more than this share of its samples as cast shadows marks the
#: data as shadowed: the highlight models are then compared on the steep lights only.
SHADOWED_SHARE = 0.005
#: Cast shadows fall at grazing light; up to θ_l = 45° both highlight models see lit samples.
STEEP_THETA_DEG = 45.5


def highlight_choice(samples: Any, fits: Dict[str, Any]) -> Dict[str, Any]:
    """Picks the Blinn-Phong highlight model from ``fits`` (key -> (Scored, shadowed_fraction)):
    the lower deviation as drawn over every sample, or, where either fit found cast shadows
    (more than :data:`SHADOWED_SHARE` of its samples), over the samples with θ_l <= 45°: neither
    model draws cast shadows, and their share of the total (noise floor x 30 on shadowed data)
    would decide between the models instead of the highlight. Returns ``chosen``, ``rule`` and
    the deviation each was ranked by."""
    shadowed = any(float(f or 0.0) > SHADOWED_SHARE for _, f in fits.values())
    if shadowed:
        steep = np.asarray(samples.angles)[:, 0] <= STEEP_THETA_DEG
        ranked = {k: float(np.mean(sc.errors[steep]) * 100) for k, (sc, _) in fits.items()}
        rule = "lower deviation as drawn over θ_l <= 45° (cast shadows found)"
    else:
        ranked = {k: sc.deviation for k, (sc, _) in fits.items()}
        rule = "lower total deviation as drawn"
    return {"chosen": min(ranked, key=ranked.get), "rule": rule, "ranked_by": ranked}


def best_of(scored: Sequence[Scored], drawable_only: bool = True) -> Scored:
    """The model with the lowest deviation as drawn (only drawable models by default: the
    material a renderer can use)."""
    pool = [s for s in scored if s.drawable or not drawable_only]
    if not pool:
        raise ValueError("no model to choose from")
    return min(pool, key=lambda s: s.deviation)


def _bad_normals(n: np.ndarray) -> np.ndarray:
    length = np.linalg.norm(n, axis=-1)
    return ~np.isfinite(length) | (np.abs(length - 1) > UNIT_TOLERANCE) | ~(n[..., 2] > 0)


def _negative(a: Optional[np.ndarray], axes: Sequence[int] = (-1,)) -> np.ndarray:
    a = np.asarray(a)
    return np.any(~np.isfinite(a) | (a < 0), axis=tuple(axes))


def physical_violations(model: Model) -> Dict[str, int]:
    """Texels outside the physical space, per reason and in total ("texels"): normals not unit
    or n_z <= 0; negative (or non-finite) albedo, ambient, specular; exponent outside
    :data:`EXPONENT_RANGE` where there is a specular term; Lafortune lobes with C_z <= 0."""
    lo, hi = EXPONENT_RANGE
    if isinstance(model, LafortuneFit):
        shape = np.asarray(model.lobe_shape)
        e = shape[..., 3]
        masks = {"normal": _bad_normals(np.asarray(model.normal)),
                 "diffuse": _negative(model.diffuse), "ambient": _negative(model.ambient),
                 "lobe_albedo": _negative(model.lobe_albedo, (-2, -1)),
                 "lobe_c_z": np.any(~(shape[..., 2] > 0), axis=-1),
                 "exponent": np.any(~np.isfinite(e) | (e < lo) | (e > hi), axis=-1)}
    else:
        masks = {"normal": _bad_normals(model.normal), "albedo": _negative(model.albedo),
                 "ambient": _negative(model.ambient)}
        if model.specular is not None:
            masks["specular"] = _negative(model.specular)
            e = (model.exponent_map if model.exponent_map is not None
                 else np.full(model.shape, model.exponent))
            masks["exponent"] = ~np.isfinite(e) | (e < lo) | (e > hi)
    out = {k: int(np.count_nonzero(v)) for k, v in masks.items()}
    out["texels"] = int(np.count_nonzero(np.any(np.stack(list(masks.values())), axis=0)))
    return out


def _median_relative(fitted: np.ndarray, truth: np.ndarray) -> Optional[float]:
    ok = truth > 0
    if not np.any(ok):
        return None
    return float(np.median(np.abs(fitted[ok] - truth[ok]) / truth[ok]))


def exponent_map(m: BtfMaterial) -> np.ndarray:
    return m.exponent_map if m.exponent_map is not None else np.full(m.shape, m.exponent,
                                                                     np.float32)


def truth_errors(model: Model, truth: BtfMaterial) -> Dict[str, Any]:
    """Against the generator's truth: normals (mean / p95 °), mean |albedo| and |ambient term|
    errors (ambient term = albedo x ambient for a BtfMaterial, the additive constant it
    contributes; Lafortune's ambient is that constant), and for specular models the median
    relative errors of k_s (mean of RGB) and of the exponent (None when not comparable)."""
    if np.shape(model.normal)[:2] != truth.shape:
        raise ValueError(f"the truth is {truth.shape}, the model {np.shape(model.normal)[:2]}")
    out: Dict[str, Any] = btf_fit.normal_stats(model.normal, truth.normal)
    true_ambient = truth.albedo * truth.ambient
    if isinstance(model, LafortuneFit):
        albedo, ambient = np.asarray(model.diffuse), np.asarray(model.ambient)
    else:
        albedo, ambient = model.albedo, model.albedo * model.ambient
    out["albedo_abs_error"] = float(np.mean(np.abs(albedo - truth.albedo)))
    out["ambient_abs_error"] = float(np.mean(np.abs(ambient - true_ambient)))
    out["k_s_median_rel_error"] = None
    out["exponent_median_rel_error"] = None
    if isinstance(model, BtfMaterial) and model.specular is not None and \
            truth.specular is not None:
        out["k_s_median_rel_error"] = _median_relative(model.specular.mean(-1),
                                                       truth.specular.mean(-1))
        out["exponent_median_rel_error"] = _median_relative(exponent_map(model),
                                                            exponent_map(truth))
    return out


def lafortune_reconstruction(fit: LafortuneFit, samples: Any,
                             indices: Optional[List[int]] = None) -> np.ndarray:
    """(len(indices), 3, H, W) values of the Lafortune model (LafortuneFit's docstring) for the
    given samples (all by default): the figures need images, LafortuneFit only gives errors."""
    lights = np.asarray(samples.light_dirs, np.float64)
    views = np.asarray(samples.view_dirs, np.float64)
    idx = list(range(len(lights))) if indices is None else list(indices)
    n = np.asarray(fit.normal, np.float64)
    out = np.empty((len(idx), 3, n.shape[0], n.shape[1]), np.float32)
    for k, s in enumerate(idx):
        l, v = lights[s], views[s]
        value = np.asarray(fit.diffuse) * np.maximum(n @ l, 0)[..., None] + fit.ambient
        for j in range(fit.lobe_shape.shape[2]):
            c = np.asarray(fit.lobe_shape[:, :, j], np.float64)
            dot = c[..., 0] * l[0] * v[0] + c[..., 1] * l[1] * v[1] + c[..., 2] * l[2] * v[2]
            value = value + fit.lobe_albedo[:, :, j] * (np.maximum(dot, 0) ** c[..., 3])[..., None]
        out[k] = np.moveaxis(value, -1, 0)
    return out
