"""The task kinds of a BTF fit split by bands of texel rows, on the code of ``btf fit``.

1. :func:`prepare` (whole dataset): load, the linear and specular fits of
   :func:`weft.btf.fit_report.seed_fits` (one pass each; the specular exponent is chosen over all
   texels, so it cannot be split) and the cast-shadow test's noise level
   (:func:`weft.btf.fit_report.shadow_noise_levels`, likewise), then the samples and seed maps
   cut into bands of rows;
2. :func:`fit_tile` with ``"blinn_phong"`` (one band): the per-texel Blinn-Phong fits
   (:func:`weft.btf.fit_report.blinn_phong_fits`) — every texel is fitted on its own, so a
   band's maps are exactly those rows of a whole-dataset fit;
3. :func:`choose` (whole dataset, only with Lafortune after Blinn-Phong): the Blinn-Phong bands
   stitched and scored on all samples to pick the highlight model, which seeds Lafortune;
4. :func:`fit_tile` with ``"lafortune"`` (one band): the Lafortune fits from that seed;
5. :func:`assemble` (whole dataset): the bands stitched back, every model scored on all
   samples and the maps, metrics, report and figures written by
   :func:`weft.btf.fit_report.write_fit`, returned as file bytes (the driver writes them, so
   a remote node needs no shared output folder).

Scoring runs on the assembled maps with the CLI's own code, so the outputs are those of
``python -m weft btf fit`` with the same options (times aside).
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import tempfile
import time
from dataclasses import dataclass, field, replace
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

import weft
from weft.batch.manifest import where

#: Options of ``btf fit`` a batch job takes (defaults as the CLI's).
FIT_DEFAULTS: Dict[str, Any] = dict(views="frontal", gamma="raw", robust=False,
                                    max_exponent=None, per_texel_exponent=False, nonlinear=True,
                                    solver="builtin", luminance_normals=False, visibility=True,
                                    pooled_exponent=False, lafortune=[1], figures=True,
                                    threads=0)

#: How many times a task's memory is its samples' float bytes: the samples, one copy of
#: their values (``BtfSamples.values``), one reconstruction (scoring, figures) and the
#: fitted maps; measured 3.4x at 128x128 texels, imports included.
MEMORY_FACTOR = 4.0


@dataclass
class BtfJob:
    """One dataset to fit: ``path`` (Bonn folder or zip), its output folder ``name`` (relative
    to the batch's output), the ``btf fit`` options, bands of rows ``tiles``, and
    ``memory`` bytes a task may hold (a dataset that needs more fails with a clear error)."""

    name: str
    path: str
    options: Dict[str, Any] = field(default_factory=dict)
    tiles: int = 4
    memory: int = 2 << 30
    times: bool = True

    def args(self, out: str = "") -> argparse.Namespace:
        unknown = set(self.options) - set(FIT_DEFAULTS)
        if unknown:
            raise weft.InvalidArgument(f"unknown BTF fit options {sorted(unknown)}; known: "
                                       f"{sorted(FIT_DEFAULTS)}")
        opts = {**FIT_DEFAULTS, **self.options}
        return argparse.Namespace(path=self.path, out=out, truth=None, progress=False, **opts)


def _timer(times: bool):
    def run(label: str, fn: Any, *a: Any, **k: Any) -> Tuple[Any, float]:
        t0 = time.perf_counter()
        out = fn(*a, **k)
        return out, (time.perf_counter() - t0) if times else math.nan
    return run


def _check_memory(job: BtfJob, nbytes: int, what: str) -> None:
    need = int(nbytes * MEMORY_FACTOR)
    if need > job.memory:
        raise weft.InvalidArgument(
            f"{job.name}: {what} needs about {need / 2**30:.2f} GiB ({MEMORY_FACTOR:g} x the "
            f"float samples), more than the {job.memory / 2**30:.2f} GiB a task may use: split "
            "by views, or raise the memory per task")


def bands(height: int, tiles: int) -> List[Tuple[int, int]]:
    """``tiles`` bands of rows as even as possible (empty ones when tiles > height)."""
    edges = [height * k // tiles for k in range(tiles + 1)]
    return list(zip(edges[:-1], edges[1:]))


def _crop(m: Any, y0: int, y1: int) -> Any:
    """Rows y0:y1 of a BtfMaterial."""
    return replace(m, normal=m.normal[y0:y1], albedo=m.albedo[y0:y1], ambient=m.ambient[y0:y1],
                   specular=None if m.specular is None else m.specular[y0:y1],
                   exponent_map=None if m.exponent_map is None else m.exponent_map[y0:y1])


def load(job: BtfJob) -> Tuple[Any, float]:
    from weft.btf import fit as btf_fit
    from weft.btf.fit_report import parse_views

    args = job.args()
    t0 = time.perf_counter()
    samples = btf_fit.load(job.path, parse_views(args.views), args.gamma,
                           threads=int(args.threads))
    return samples, (time.perf_counter() - t0) if job.times else math.nan


def prepare(job: BtfJob) -> Tuple[Any, ...]:
    """Returns (header, band 0, ..., band tiles-1): the header holds the whole-dataset fits,
    each band its rows of the samples and of the two specular seeds."""
    from weft.btf.fit_report import seed_fits, shadow_noise_levels

    t0 = time.perf_counter()
    samples, load_s = load(job)
    _check_memory(job, 4 * samples.count * 3 * samples.width * samples.height, "the dataset")
    seeds = seed_fits(samples, job.args(), _timer(job.times))
    # the cast-shadow test's noise level is the whole dataset's, as for the specular exponent
    noise = shadow_noise_levels(samples, seeds.flat.material, seeds.fitted.material, job.args())
    values, angles = samples.values, samples.angles
    header = dict(models=seeds.models, linear=seeds.linear, load_s=load_s,
                  size=(samples.width, samples.height), count=samples.count, worker=where())
    out: List[Any] = [header]
    for y0, y1 in bands(samples.height, job.tiles):
        if y1 <= y0:
            out.append(None)
            continue
        out.append(dict(rows=(y0, y1), angles=angles,
                        values=np.ascontiguousarray(values[:, :, y0:y1, :]),
                        flat=_crop(seeds.flat.material, y0, y1),
                        fitted=_crop(seeds.fitted.material, y0, y1), noise=noise))
    header["seconds"] = time.perf_counter() - t0
    return tuple(out)


def fit_tile(job: BtfJob, band: Optional[Dict[str, Any]], kind: str,
             seed: Optional[Tuple[Any, bool]] = None) -> Optional[Dict[str, Any]]:
    """The per-texel fits of one band (None for an empty band): ``kind`` "blinn_phong" (from
    the band's specular seeds) or "lafortune" (from ``seed`` = (band of the seed material,
    keep its normal); None: the band's eq. 4.30 specular fit, as without Blinn-Phong)."""
    if band is None:
        return None
    from weft.btf.fit_report import blinn_phong_fits, lafortune_fits

    _check_memory(job, band["values"].nbytes, f"a band of {band['rows'][1] - band['rows'][0]} "
                  "rows")
    samples = weft.BtfSamples(band["values"], band["angles"])
    t0 = time.perf_counter()
    if kind == "blinn_phong":
        models = blinn_phong_fits(samples, band["flat"], band["fitted"], job.args(),
                                  _timer(job.times), band.get("noise"))
    else:
        material, fixed = seed if seed is not None else (band["flat"], False)
        models = lafortune_fits(samples, material, fixed, job.args(), _timer(job.times))
    return dict(rows=band["rows"], models=models, seconds=time.perf_counter() - t0,
                texels=samples.width * samples.height, worker=where())


def _stitch_all(tiles: Sequence[Optional[Dict[str, Any]]], count: int) -> List[Any]:
    """The whole-dataset Fitted models of bands, in the bands' model order."""
    tiles = sorted((t for t in tiles if t is not None), key=lambda t: t["rows"])
    if not tiles:
        return []
    return [_stitch(f.name, [(t["texels"], t["models"][k]) for t in tiles], count)
            for k, f in enumerate(tiles[0]["models"])]


def choose(job: BtfJob, header: Dict[str, Any], *tiles: Optional[Dict[str, Any]]
           ) -> Tuple[Any, ...]:
    """Picks the Blinn-Phong highlight model on all samples, as ``btf fit`` does; returns
    ({"choice", "seconds"}, the seed of each band's Lafortune fits)."""
    from weft.btf.fit_report import blinn_phong_choice, lafortune_seed, score_all

    t0 = time.perf_counter()
    samples, _ = load(job)
    scored = score_all(samples, _stitch_all(tiles, samples.count))
    choice = blinn_phong_choice(samples, scored)
    flat = next(m.model for m in header["models"] if m.name == "specular_eq4.30")
    seed, fixed = lafortune_seed(flat, scored, choice)
    seeds = [None if y1 <= y0 else (_crop(seed, y0, y1), fixed)
             for y0, y1 in bands(samples.height, job.tiles)]
    return (dict(choice=choice, seconds=time.perf_counter() - t0, worker=where()), *seeds)


# Per-texel counts behind a band's means (iterations, samples left out as shadowed): the
# whole-dataset mean is their sum over all texels, as the C++ fit sums them (integers in
# doubles, so the sums are exact and the stitched mean equals the serial one bit for bit).
_COUNTS = {"mean_iterations": 1, "shadowed_fraction": 0}


def _stitch(name: str, parts: Sequence[Tuple[int, Any]], count: int) -> Any:
    """One model's bands (texels, Fitted) as the whole-dataset Fitted."""
    from weft.btf.fit import LafortuneFit
    from weft.btf.fit_report import Fitted

    first = parts[0][1]
    texels = sum(n for n, _ in parts)
    seconds = sum(f.seconds for _, f in parts)
    extra = dict(first.extra)
    for k, per_texel in _COUNTS.items():
        if extra.get(k) is None:
            continue
        scale = 1 if per_texel else count
        total = sum(round(f.extra[k] * n * scale) for n, f in parts)
        extra[k] = total / (texels * scale)
    models = [f.model for _, f in parts]

    def cat(attr: str) -> Optional[np.ndarray]:
        arrays = [getattr(m, attr) for m in models]
        return None if arrays[0] is None else np.concatenate(arrays, axis=0)

    if isinstance(first.model, LafortuneFit):
        model = LafortuneFit(normal=cat("normal"), diffuse=cat("diffuse"),
                             ambient=cat("ambient"), lobe_albedo=cat("lobe_albedo"),
                             lobe_shape=cat("lobe_shape"), mean_iterations=extra.get(
                                 "mean_iterations", first.model.mean_iterations))
    else:
        if len({m.exponent for m in models}) != 1:
            raise weft.Error(f"{name}: bands disagree on the scalar exponent")
        model = replace(first.model, normal=cat("normal"), albedo=cat("albedo"),
                        ambient=cat("ambient"), specular=cat("specular"),
                        exponent_map=cat("exponent_map"))
    return Fitted(name, model, seconds, extra)


def assemble(job: BtfJob, header: Dict[str, Any], chosen: Optional[Dict[str, Any]],
             *tiles: Optional[Dict[str, Any]]) -> Dict[str, Any]:
    """Stitches the bands (Blinn-Phong and Lafortune tiles, any order), scores every model on
    all samples and writes the ``btf fit`` outputs; returns {"files": {relative path: bytes},
    "best", "deviation", ...}."""
    from weft.btf.fit_report import blinn_phong_choice, pooled_fits, score_all, write_fit

    t0 = time.perf_counter()
    done = [t for t in tiles if t is not None]
    samples, _ = load(job)
    bp = [t for t in done if t["models"] and t["models"][0].name.startswith("blinn_phong")]
    laf = [t for t in done if t["models"] and t["models"][0].name.startswith("lafortune")]
    scored = score_all(samples, list(header["models"]) + _stitch_all(bp, samples.count))
    choice = blinn_phong_choice(samples, scored)
    if chosen is not None and chosen["choice"] != choice:
        raise weft.Error(f"{job.name}: the highlight choice changed between stages")
    # pooling needs every texel: fitted here, on the whole dataset, as btf fit does
    scored += score_all(samples, pooled_fits(samples, scored, choice, job.args(),
                                             _timer(job.times)))
    scored += score_all(samples, _stitch_all(laf, samples.count))
    tmp = tempfile.mkdtemp(prefix="weft-batch-")
    try:
        args = job.args(out=tmp)
        best, _ = write_fit(args, samples, scored, choice, header["linear"], header["load_s"])
        files: Dict[str, bytes] = {}
        for root, _, names in os.walk(tmp):
            for n in names:
                full = os.path.join(root, n)
                with open(full, "rb") as f:
                    files[os.path.relpath(full, tmp)] = f.read()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    stage_seconds = [header["seconds"]] + [t["seconds"] for t in done] + \
        ([chosen["seconds"]] if chosen else [])
    workers = [header["worker"]] + [t["worker"] for t in done] + \
        ([chosen["worker"]] if chosen else []) + [where()]
    return dict(files=files, best=best.name, deviation=best.deviation,
                task_seconds=sum(stage_seconds) + time.perf_counter() - t0,
                texels=samples.width * samples.height, samples=samples.count,
                tile_seconds=[t["seconds"] for t in done], worker=where(), workers=workers)
