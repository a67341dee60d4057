"""The recommended BTF pipeline in one call (BENCHMARKS.md, btf: the row that meets issue 12's
targets on data the project had not tuned to): the linear fit, both specular seeds, per-texel
Blinn-Phong with both highlights (n_s = n, eq. 4.29; n_s = (0, 0, 1), eq. 4.30), the one drawn
better chosen (:func:`weft.btf.scoring.highlight_choice`), then that one fitted again with its
exponents pooled over the material (``exponent="pooled"``, :mod:`weft.btf.exponent_pool`).
JPEG data: normals and exponents from the luma, and with the files' quantisation cells
(``btf.load(path, jpeg_cells=True)``) the exponents pooled from the fit refined against them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, Optional

from weft.btf import fit as btf_fit
from weft.btf import scoring
from weft.reporting import Progress


@dataclass
class RecommendedFit:
    """What :func:`fit_recommended` found."""
    fit: btf_fit.NonlinearFit        # what to draw: ``fit.material.render_material()``
    per_texel: btf_fit.NonlinearFit  # the chosen highlight's fit before pooling
    flat_specular_normal: bool       # the chosen highlight: n_s = (0, 0, 1), else n
    rule: str                        # how it was chosen
    deviation: Dict[str, float]      # each highlight's deviation as drawn, % ("n", "flat")


def fit_recommended(samples: Any, *, jpeg: Optional[bool] = None, pooled: bool = True,
                    threads: int = 0, linear: Optional[btf_fit.LinearFit] = None,
                    progress: Optional[bool] = None) -> RecommendedFit:
    """Fits ``samples`` with the recommended pipeline (module doc). ``jpeg``: the samples came
    from JPEG files (None: when they were loaded with their quantisation cells); ``pooled``
    False stops at the chosen per-texel fit; ``linear``: :func:`weft.btf.fit_linear`'s result
    when it is already made; ``progress``: a bar on stderr over the fits (None: only on a
    terminal)."""
    cells = getattr(samples, "jpeg_cells", None) is not None
    jpeg = cells if jpeg is None else bool(jpeg)
    with Progress((linear is None) + 4 + pooled, enabled=progress) as bar:
        def run(label: str, fn: Any, *a: Any, **k: Any) -> Any:
            bar.update(label)
            out = fn(*a, **k)
            bar.step()
            return out

        if linear is None:
            linear = run("linear fit", btf_fit.fit_linear, samples)
        fits = {}
        for flat in (False, True):
            highlight = "n_s = (0,0,1)" if flat else "n_s = n"
            seed = run(f"specular seed, {highlight}", btf_fit.fit_specular, samples, linear,
                       flat).material
            fit = run(f"Blinn-Phong, {highlight}", btf_fit.fit_blinn_phong, samples, seed,
                      flat_specular_normal=flat, threads=threads, luminance_normals=jpeg)
            fits[flat] = (scoring.score(samples, "blinn_phong", fit.material), fit, seed)
        pick = scoring.highlight_choice(
            samples, {flat: (s, f.shadowed_fraction) for flat, (s, f, _) in fits.items()})
        chosen = bool(pick["chosen"])
        _, per_texel, seed = fits[chosen]
        final = per_texel
        if pooled:
            final = run("Blinn-Phong, pooled exponents", btf_fit.fit_blinn_phong, samples, seed,
                        flat_specular_normal=chosen, threads=threads, luminance_normals=jpeg,
                        jpeg_cells=jpeg and cells, exponent="pooled", per_texel=per_texel)
    return RecommendedFit(final, per_texel, chosen, pick["rule"],
                          {("flat" if flat else "n"): s.deviation
                           for flat, (s, _, _) in fits.items()})
