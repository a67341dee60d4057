"""The Warp peer of the cloth benchmark (optional): the standard scene's algorithm as NVIDIA
Warp CPU kernels, the batches, tethers and XPBD of :class:`weft.reference.cloth.ClothReference`,
one kernel launch per batch. Used by :mod:`weft.bench.cloth` when ``import warp`` works."""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

import numpy as np

from weft.bench.cloth import DT, Engine, Setting, scene_kwargs

_WARP_KERNELS: Optional[Dict[str, Any]] = None


def _warp_kernels() -> Dict[str, Any]:
    """Builds the Warp kernels once (Warp compiles them for the CPU on first launch)."""
    global _WARP_KERNELS
    if _WARP_KERNELS is not None:
        return _WARP_KERNELS
    import warp as wp

    @wp.kernel
    def integrate(x: wp.array(dtype=wp.vec3), xp: wp.array(dtype=wp.vec3),
                  w: wp.array(dtype=float), g: wp.vec3, damping: float, h: float):
        i = wp.tid()
        if w[i] == 0.0:
            xp[i] = x[i]
            return
        xi = x[i]
        x[i] = xi + damping * (xi - xp[i]) + g * (h * h)
        xp[i] = xi

    @wp.kernel
    def project(x: wp.array(dtype=wp.vec3), w: wp.array(dtype=float),
                a: wp.array(dtype=int), b: wp.array(dtype=int), rest: wp.array(dtype=float),
                lam: wp.array(dtype=float), alpha: float):
        c = wp.tid()
        ia = a[c]
        ib = b[c]
        wsum = w[ia] + w[ib]
        if wsum <= 0.0:
            return
        d = x[ib] - x[ia]
        length = wp.length(d)
        if length < 1e-12:
            return
        dl = (-(length - rest[c]) - alpha * lam[c]) / (wsum + alpha)
        lam[c] = lam[c] + dl
        corr = d * (dl / length)
        x[ia] = x[ia] - w[ia] * corr
        x[ib] = x[ib] + w[ib] * corr

    @wp.kernel
    def tether(x: wp.array(dtype=wp.vec3), p: wp.array(dtype=int), q: wp.array(dtype=int),
               length: wp.array(dtype=float)):
        t = wp.tid()
        ip = p[t]
        d = x[ip] - x[q[t]]
        dist = wp.length(d)
        if dist > length[t]:
            x[ip] = x[q[t]] + d * (length[t] / dist)

    _WARP_KERNELS = {"wp": wp, "integrate": integrate, "project": project, "tether": tether}
    return _WARP_KERNELS


class WarpCloth:
    """The standard scene's solver in Warp (CPU): the batches, tethers and XPBD of
    :class:`weft.reference.cloth.ClothReference`, each batch one kernel launch."""

    def __init__(self, n: int, setting: Setting) -> None:
        from weft.reference.cloth import ClothReference

        k = _warp_kernels()
        wp = k["wp"]
        self.k = k
        self.setting = setting
        layout = ClothReference(**scene_kwargs(n), **setting.kwargs())
        layout.pin([0, n - 1])
        self.layout = layout
        self.device = "cpu"
        self.x = wp.array(layout.x.astype(np.float32), dtype=wp.vec3, device=self.device)
        self.xp = wp.array(layout.x.astype(np.float32), dtype=wp.vec3, device=self.device)
        self.w = wp.array(layout.inverse_masses.astype(np.float32), dtype=float,
                          device=self.device)
        self.batches = []
        for fam, a, b, rest, _, _ in layout._solve_batches():
            self.batches.append((layout._compliance(fam),
                                 wp.array(a.astype(np.int32), dtype=int, device=self.device),
                                 wp.array(b.astype(np.int32), dtype=int, device=self.device),
                                 wp.array(rest.astype(np.float32), dtype=float, device=self.device),
                                 wp.zeros(len(a), dtype=float, device=self.device)))
        self.tethers = []
        if setting.tethers:
            for p, q, length in layout._tether_data():
                self.tethers.append((wp.array(p.astype(np.int32), dtype=int, device=self.device),
                                     wp.array(q.astype(np.int32), dtype=int, device=self.device),
                                     wp.array(length.astype(np.float32), dtype=float,
                                              device=self.device)))
        self.g = wp.vec3(0.0, -9.81, 0.0)
        self.last_h = DT

    def step(self, dt: float) -> None:
        k, wp = self.k, self.k["wp"]
        h = dt / self.setting.substeps
        damping = 0.99 ** (h * 60.0)
        n = self.layout.n
        for _ in range(self.setting.substeps):
            wp.launch(k["integrate"], dim=n, inputs=[self.x, self.xp, self.w, self.g, damping, h],
                      device=self.device)
            for _, _, _, _, lam in self.batches:
                lam.zero_()
            for _ in range(self.setting.iterations):
                for compliance, a, b, rest, lam in self.batches:
                    wp.launch(k["project"], dim=a.shape[0],
                              inputs=[self.x, self.w, a, b, rest, lam, compliance / (h * h)],
                              device=self.device)
                for p, q, length in self.tethers:
                    wp.launch(k["tether"], dim=p.shape[0], inputs=[self.x, p, q, length],
                              device=self.device)
        wp.synchronize_device(self.device)
        self.last_h = h

    def numpy_positions(self) -> np.ndarray:
        return self.x.numpy().astype(np.float64)

    def stats(self) -> Dict[str, float]:
        from weft.reference.cloth import strain

        mean, mx = strain(self.numpy_positions(), self.layout.a, self.layout.b, self.layout.rest)
        return {"mean_strain": mean, "max_strain": mx}

    def kinetic_energy(self) -> float:
        v = (self.numpy_positions() - self.xp.numpy()) / self.last_h
        return float(0.5 / self.layout.n * np.sum(v * v))


class WarpEngine(Engine):
    name = "warp"

    def make(self, n: int, setting: Setting) -> Any:
        return WarpCloth(n, setting)

    def positions(self, cloth: Any) -> np.ndarray:
        return cloth.numpy_positions()


def warp_status() -> Tuple[bool, str]:
    """Whether the Warp peer can run, and what to say about it."""
    try:
        import warp as wp

        wp.config.quiet = True  # no banner on stdout
        wp.init()
        _warp_kernels()
        return True, f"warp {getattr(wp, '__version__', '?')} (CPU kernels)"
    except Exception as exc:  # not installed, or no usable CPU backend
        return False, f"not run: import warp failed ({type(exc).__name__}: {exc})"
