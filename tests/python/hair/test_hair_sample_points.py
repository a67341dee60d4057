"""The 128 sample points the anti-aliased opaque strands resolve visibility with, written out in
glsl/hair/hair_oit_main.glsl (one HAIR_POINT each), against their definition: the 2D Sobol
sequence in Gray code order, and the (0, m, 2)-net property the shader's comment promises."""

from __future__ import annotations

import re
from math import comb
from pathlib import Path

import pytest

SHADER = Path(__file__).resolve().parents[3] / "glsl" / "hair" / "hair_oit_main.glsl"
BITS = 7  # 128 = 2^7 points on a 128 x 128 grid


def shader_points():
    text = SHADER.read_text(encoding="utf-8")
    calls = re.findall(r"HAIR_POINT\((\d+), (\d+), (\d+), (\d+)\)", text)
    return {32 * int(k) + int(j): (int(x), int(y)) for k, j, x, y in calls}


def sobol_points():
    """Point i of the walk: the Sobol point of Gray code g = i ^ (i >> 1); X the van der Corput
    radical inverse of g, Y the XOR of the direction numbers of g's bits, direction number b
    being row b of Pascal's triangle mod 2 read from the top bit."""
    directions = [sum((comb(b, c) % 2) << (BITS - 1 - c) for c in range(b + 1))
                  for b in range(BITS)]
    points = []
    for i in range(2 ** BITS):
        g = i ^ (i >> 1)
        x = int(format(g, f"0{BITS}b")[::-1], 2)
        y = 0
        for b in range(BITS):
            if g >> b & 1:
                y ^= directions[b]
        points.append((x, y))
    return points


def test_the_shader_holds_the_sequence_in_order() -> None:
    got = shader_points()
    assert sorted(got) == list(range(128))
    assert [got[i] for i in range(128)] == sobol_points()


@pytest.mark.parametrize("count", [32, 128])
def test_the_first_points_are_a_net(count) -> None:
    # every 2^-a x 2^-b box of the pixel with 2^(a + b) = count holds exactly one point
    points = [shader_points()[i] for i in range(count)]
    m = count.bit_length() - 1
    for a in range(m + 1):
        b = m - a
        boxes = {(x >> (BITS - a), y >> (BITS - b)) for x, y in points}
        assert len(boxes) == count, (a, b)
