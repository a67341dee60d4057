"""Figures and tables of a BTF fit report (SPEC §3.4): difference images, per-texel polar plots
(seed fig. 4.16), a histogram of per-sample errors, the fitted maps, and the seed's tables
4.1-4.3 for any dataset. Figures are drawn with matplotlib (Agg) with axes, labels and colour
bars; map previews are tone-mapped (value / scale, the scale printed in the report) so that
dark maps do not come out black.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

import weft
from weft.reporting import markdown_table, pyplot, save_figure

LUMA = np.array([0.2126, 0.7152, 0.0722])
PREVIEW_PERCENTILE = 98.0


def to_u8(img: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(np.asarray(img) * 255.0), 0, 255).astype(np.uint8)


def tone_scale(values: np.ndarray, percentile: float = PREVIEW_PERCENTILE) -> float:
    """The value shown as white: the 98th percentile of the finite |values|. Scaling by the
    maximum turned maps black: fits leave ~1% of texels far out (an ambient of 1000 where the
    albedo is ~0, one huge exponent), and the rest then rounds to 0-3 of 255. 1 for a zero map."""
    v = np.asarray(values, np.float64)
    v = np.abs(v[np.isfinite(v)])
    top = float(np.percentile(v, percentile)) if v.size else 0.0
    if top <= 0:
        top = float(v.max()) if v.size else 0.0
    return top if top > 0 else 1.0


def preview(name: str, value: np.ndarray) -> Tuple[np.ndarray, str]:
    """(8-bit RGB preview, how it was scaled): normals as (n + 1) / 2, other maps value / scale
    with the scale from :func:`tone_scale`."""
    value = np.asarray(value, np.float64)
    if value.ndim == 2:
        value = np.repeat(value[..., None], 3, axis=-1)
    if name == "normal":
        return to_u8((value + 1) * 0.5), "(n + 1) / 2"
    scale = tone_scale(value)
    return to_u8(value / scale), f"value / {scale:.4g}"


def write_previews(folder: str, maps: Dict[str, np.ndarray]) -> Dict[str, str]:
    """Writes ``<map>_preview.png`` per map into ``folder``; returns map -> scaling text."""
    os.makedirs(folder, exist_ok=True)
    scales = {}
    for name, value in maps.items():
        img, how = preview(name, value)
        weft.save_png(os.path.join(folder, f"{name}_preview.png"), img)
        scales[name] = how
    return scales


def model_maps(model: Any) -> Dict[str, np.ndarray]:
    """The maps of a BtfMaterial or LafortuneFit by name (lobe maps per lobe)."""
    if hasattr(model, "lobe_shape"):
        out = {"normal": model.normal, "diffuse": model.diffuse, "ambient": model.ambient}
        for j in range(model.lobe_shape.shape[2]):
            out[f"lobe{j}_albedo"] = model.lobe_albedo[:, :, j]
            out[f"lobe{j}_exponent"] = model.lobe_shape[:, :, j, 3]
        return out
    out = {"normal": model.normal, "albedo": model.albedo, "ambient": model.ambient}
    if model.specular is not None:
        out["specular"] = model.specular
        out["exponent"] = (model.exponent_map if model.exponent_map is not None
                           else np.full(model.shape, model.exponent, np.float32))
    return out


def plot_maps(path: str, title: str, maps: Dict[str, np.ndarray]) -> None:
    """One panel per map: colour maps tone-mapped (scale in the colour bar's label), scalar maps
    and the luminance of RGB maps with a colour bar, axes in texels."""
    plt = pyplot()
    fig, axes = plt.subplots(1, len(maps), figsize=(3.4 * len(maps), 3.3), squeeze=False)
    for ax, (name, value) in zip(axes[0], maps.items()):
        value = np.asarray(value, np.float64)
        if name == "normal":
            im = ax.imshow(np.clip((value + 1) * 0.5, 0, 1))
            ax.set_title("normal, (n + 1) / 2", fontsize=9)
            theta = np.degrees(np.arccos(np.clip(value[..., 2], -1, 1)))
            ax.set_xlabel(f"tilt mean {theta.mean():.1f}°, max {theta.max():.1f}°", fontsize=8)
        else:
            shown = value @ LUMA if value.ndim == 3 else value
            scale = tone_scale(shown)
            im = ax.imshow(shown, cmap="magma", vmin=0 if shown.min() >= 0 else None,
                           vmax=scale)
            fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04,
                         label=("luminance" if value.ndim == 3 else "value")
                         + f" (clipped at p{PREVIEW_PERCENTILE:g} = {scale:.3g})")
            ax.set_title(name, fontsize=9)
            ax.set_xlabel("x (texels)", fontsize=8)
        ax.set_ylabel("y (texels)", fontsize=8)
        ax.tick_params(labelsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=90)


def plot_differences(path: str, title: str, measured: np.ndarray, recon: np.ndarray,
                     theta_l: Sequence[float]) -> float:
    """|measurement - reconstruction| (luminance of [0, 1] values) for a few samples, one panel
    each, with a shared colour bar; returns the colour bar's top."""
    plt = pyplot()
    diff = np.abs(np.asarray(measured, np.float64) - recon)          # (k, 3, H, W)
    lum = np.einsum("kchw,c->khw", diff, LUMA)
    top = max(tone_scale(lum, 99.0), 1e-6)
    fig, axes = plt.subplots(1, len(theta_l), figsize=(2.6 * len(theta_l) + 1.2, 2.9),
                             squeeze=False)
    im = None
    for ax, img, t in zip(axes[0], lum, theta_l):
        im = ax.imshow(img, cmap="inferno", vmin=0, vmax=top)
        ax.set_title(f"θ_l = {t:g}°", fontsize=9)
        ax.set_xlabel("x (texels)", fontsize=8)
        ax.tick_params(labelsize=7)
    axes[0][0].set_ylabel("y (texels)", fontsize=8)
    fig.colorbar(im, ax=list(axes[0]), fraction=0.02, pad=0.02,
                 label="|measured − model| (luminance)")
    fig.suptitle(title, fontsize=10)
    save_figure(fig, path, dpi=90)
    return top


def _polar_scatter(ax: Any, angles: np.ndarray, colours: np.ndarray, title: str) -> None:
    ax.scatter(np.radians(angles[:, 1]), angles[:, 0], c=np.clip(colours, 0, 1), s=46,
               edgecolors="0.3", linewidths=0.3)
    ax.set_ylim(0, 90)
    ax.set_yticks([15, 30, 45, 60, 75])
    ax.set_yticklabels(["15°", "30°", "45°", "60°", "75°"], fontsize=6)
    ax.tick_params(labelsize=6)
    ax.set_title(title, fontsize=8)


def plot_polar(path: str, texel: Tuple[int, int], angles: np.ndarray, measured: np.ndarray,
               recons: Dict[str, np.ndarray]) -> float:
    """One texel's colour against the light direction (radius θ_l, angle φ_l; seed fig. 4.16):
    per model a row with the measurement, the model and |difference| (luminance, colour bar).
    Colours are value / scale (the scale, the brightest measurement, is in the title)."""
    plt = pyplot()
    scale = max(float(np.max(measured)), 1e-6)
    rows = len(recons)
    fig = plt.figure(figsize=(9.6, 3.0 * rows))
    for r, (name, rec) in enumerate(recons.items()):
        ax = fig.add_subplot(rows, 3, 3 * r + 1, projection="polar")
        _polar_scatter(ax, angles, measured / scale, "measurement")
        ax.set_ylabel(name, fontsize=8, labelpad=22)
        ax = fig.add_subplot(rows, 3, 3 * r + 2, projection="polar")
        _polar_scatter(ax, angles, rec / scale, "model")
        ax = fig.add_subplot(rows, 3, 3 * r + 3, projection="polar")
        diff = np.abs(measured - rec) @ LUMA
        sc = ax.scatter(np.radians(angles[:, 1]), angles[:, 0], c=diff, cmap="inferno", s=46,
                        vmin=0)
        ax.set_ylim(0, 90)
        ax.set_yticks([30, 60])
        ax.set_yticklabels(["30°", "60°"], fontsize=6)
        ax.tick_params(labelsize=6)
        ax.set_title("|difference| (luminance)", fontsize=8)
        fig.colorbar(sc, ax=ax, fraction=0.046, pad=0.1)
    fig.suptitle(f"texel (x={texel[0]}, y={texel[1]}): radius θ_l, angle φ_l; colours = value "
                 f"/ {scale:.3g}", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.35 / (3.0 * rows)))
    save_figure(fig, path, dpi=80)
    return scale


def histogram_rows(errors: Dict[str, np.ndarray], best: str) -> List[Any]:
    """The best model's (low, high, count) bins of :func:`plot_histogram`, without drawing."""
    every = np.concatenate([np.asarray(e, np.float64) for e in errors.values()])
    edges = np.histogram_bin_edges(every[np.isfinite(every)], bins=30)
    counts, _ = np.histogram(errors[best], bins=edges)
    return [(float(edges[i]), float(edges[i + 1]), int(c)) for i, c in enumerate(counts)]


def plot_histogram(path: str, errors: Dict[str, np.ndarray], best: str) -> List[Any]:
    """Per-sample deviation (mean squared error x 100, %) of every model as step histograms on
    shared bins, the best model filled; returns the best model's (low, high, count) bins."""
    plt = pyplot()
    every = np.concatenate([np.asarray(e, np.float64) for e in errors.values()])
    edges = np.histogram_bin_edges(every[np.isfinite(every)], bins=30)
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    rows: List[Any] = []
    for name, e in errors.items():
        if name == best:
            counts, _, _ = ax.hist(e, bins=edges, alpha=0.45, label=f"{name} (best)",
                                   zorder=1)
            rows = [(float(edges[i]), float(edges[i + 1]), int(c)) for i, c in enumerate(counts)]
        else:
            ax.hist(e, bins=edges, histtype="step", lw=1.2, label=name, zorder=2)
    ax.set_xlabel("per-sample deviation (mean squared error x 100, %)")
    ax.set_ylabel("samples")
    ax.set_title("Per-sample deviation of each model")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, path, dpi=90)
    return rows


def fmt(value: Optional[float], digits: int = 4) -> str:
    return "–" if value is None or not np.isfinite(value) else f"{value:.{digits}f}"


def seed_tables(results: Dict[str, Dict[str, Any]]) -> str:
    """The seed's tables 4.1-4.3 for this dataset: deviation (%) per θ_l group and in total for
    each model as drawn (Lafortune: as fitted, marked "not drawn"), the fitted model's own
    total, and the specular exponent where there is one."""
    names = list(results)
    first = results[names[0]]
    groups = list(first["deviation"]["groups"])
    header = ["θ_l group"] + [results[n].get("label", n) for n in names]
    rows = [[f"{g}°"] + [f"{results[n]['deviation']['groups'][g]:.4f}" for n in names]
            for g in groups]
    rows.append(["**total**"] + [f"**{results[n]['deviation']['total']:.4f}**" for n in names])
    rows.append(["total as fitted"] + [f"{results[n]['fitted_deviation']['total']:.4f}"
                                       for n in names])
    rows.append(["exponent n"] + [str(results[n].get("exponent", "–")) for n in names])
    return markdown_table(header, rows)
