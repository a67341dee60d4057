"""What a user does to a :class:`~weft.reference.cloth.ClothReference` between steps: pin and
unpin, grab and move, holes, wind and colliders (SPEC §2.2). A mixin of the solver's state
(``n``, ``nx``, ``ny``, ``pinned``, ``grabbed``, ``hole``, ``active``, ``a``, ``b``, ``wind``,
``colliders``) that calls its ``_changed()`` and ``wake()``."""

from __future__ import annotations

from typing import Any, Sequence, Union

import numpy as np

from weft.reference.cloth_colliders import WindSetting, _points, _vec
from weft.reference.cloth_grid import constraints_on_surface, grid_triangles, hole_mask_from_image

ArrayLike = Union[np.ndarray, Sequence[float], float]


class ClothInteraction:
    """Pins, grabs, holes, wind and colliders of the cloth reference."""

    def _indices(self, indices: ArrayLike) -> np.ndarray:
        idx = np.asarray(indices, dtype=np.int64).reshape(-1)
        if np.any((idx < 0) | (idx >= self.n)):
            raise ValueError(f"particle index out of range [0, {self.n})")
        return idx

    def pin(self, indices: ArrayLike) -> None:
        self.pinned[self._indices(indices)] = True
        self._changed()
        self.wake()

    def unpin(self, indices: ArrayLike) -> None:
        self.pinned[self._indices(indices)] = False
        self._changed()
        self.wake()

    def grab(self, indices: ArrayLike, targets: ArrayLike) -> None:
        """Grabbed particles get inverse mass 0 and follow ``targets`` exactly (SPEC §2.2)."""
        idx = self._indices(indices)
        t = _points(targets, "targets")
        if t.shape != (len(idx), 3) or not np.all(np.isfinite(t)):
            raise ValueError("targets must be finite (k, 3) for k indices")
        self.grabbed, self.grab_targets = idx, t.copy()
        self._changed()
        self.wake()

    def move_grab(self, targets: ArrayLike) -> None:
        t = _points(targets, "targets")
        if t.shape != (len(self.grabbed), 3) or not np.all(np.isfinite(t)):
            raise ValueError("targets must be finite (k, 3) for the k grabbed particles")
        self.grab_targets = t.copy()
        self.wake()

    def release(self) -> None:
        self.grabbed = np.zeros(0, dtype=np.int64)
        self.grab_targets = np.zeros((0, 3))
        self._changed()
        self.wake()

    def set_holes(self, mask: ArrayLike) -> None:
        """Hole mask (ny, nx), nonzero = hole; the particles and their constraints go (see
        :func:`hole_mask_from_image` for image masks)."""
        m = np.asarray(mask)
        if m.dtype == np.uint8:
            m = hole_mask_from_image(m, self.nx, self.ny)
        if m.shape != (self.ny, self.nx):
            raise ValueError(f"mask must be ({self.ny}, {self.nx}), got {m.shape}")
        self.hole = (m != 0).reshape(-1)
        # A constraint goes with its ends and with the faces it runs through (nothing spans
        # a hole); this reference does not tear faces, so the faces are those without holes.
        faces = grid_triangles(self.nx, self.ny, hole=self.hole)
        self.active = constraints_on_surface(self.nx, faces, self.a, self.b)
        self.active &= ~(self.hole[self.a] | self.hole[self.b])
        self._changed()
        self.wake()

    def set_wind(self, direction: ArrayLike = (1.0, 0.0, 0.0), strength: float = 0.0) -> None:
        self.wind = WindSetting(tuple(_vec(direction, 3, "direction")), float(strength))
        self.wake()

    def add_collider(self, shape: Any) -> int:
        """Adds a shape with ``distance(points) -> (s, n)`` and ``friction``; returns its id."""
        self.colliders.append(shape)
        self.wake()
        return len(self.colliders) - 1

    def set_collider(self, index: int, shape: Any) -> None:
        self.colliders[index] = shape
        self.wake()

    def clear_colliders(self) -> None:
        self.colliders = []
        self.wake()
