"""Fur on a mesh instance in one call: :func:`weft.generate_fur` + :meth:`weft.Scene.add_hair`."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np


def add_fur(scene: Any, mesh: Any, material: Optional[Any] = None,
            transform: Optional[np.ndarray] = None, cast_shadows: bool = True,
            **fur: Any) -> int:
    """Grows fur on ``mesh`` (``weft.generate_fur(mesh, **fur)``: level, density, segments,
    length, length_jitter, direction_jitter, down, texture, seed, threads) and adds it to
    ``scene`` with ``material`` (a ``weft.HairMaterial``) and the mesh instance's ``transform``
    (4x4, object -> world). Returns the hair id; the strands are ``scene``'s from then on."""
    from weft._core import generate_fur

    strands = generate_fur(mesh, **fur)
    return scene.add_hair(strands, material, transform, cast_shadows)


__all__ = ["add_fur"]
