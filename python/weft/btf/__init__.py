"""BTF fitting (SPEC §3): Bonn-layout datasets, synthetic BTFs with ground truth, the seed's
linear + specular fit, nonlinear Blinn-Phong and Lafortune fits, reports and the
``python -m weft btf`` CLI.

Modules: :mod:`weft.btf.fit` (load, fits, error figures), :mod:`weft.btf.synth` (presets,
rendering, writing), :mod:`weft.btf.material` (:class:`BtfMaterial`), :mod:`weft.btf.report`
(maps, metrics, Markdown report with figures), :mod:`weft.btf.cli`.
"""

from weft._core import BtfSamples
from weft.btf.fit import (
    LafortuneFit,
    LinearFit,
    NonlinearFit,
    SpecularFit,
    angular_error_deg,
    deviation,
    fit_blinn_phong,
    fit_lafortune,
    fit_linear,
    fit_specular,
    have_ceres,
    load,
    normal_stats,
    resolvable_exponent,
    sample_errors,
    shadow_noise,
    solve_linear,
)
from weft.btf.material import BtfMaterial
from weft.btf.recommended import RecommendedFit, fit_recommended
from weft.btf.synth import PRESETS, SynthTruth, synthesize, write

__all__ = ["BtfMaterial", "BtfSamples", "LafortuneFit", "LinearFit", "NonlinearFit", "PRESETS",
           "RecommendedFit", "SpecularFit", "SynthTruth", "angular_error_deg", "deviation",
           "fit_blinn_phong", "fit_lafortune", "fit_linear", "fit_recommended", "fit_specular",
           "have_ceres", "load", "normal_stats", "resolvable_exponent", "sample_errors",
           "shadow_noise", "solve_linear", "synthesize", "write"]
