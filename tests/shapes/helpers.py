"""Shared helpers and hypothesis strategies for the shape tests."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from etswarm.shapes.gene import cells_to_bitmap
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS

OFFS = [tuple(int(v) for v in o) for o in NEIGHBOUR_OFFSETS]


def grow_cells(size: int, choices: list[int]) -> np.ndarray:
    """A constructible, connected cell set of ``size`` cells grown from a seed triangle;
    ``choices`` pick among the addable sites (sorted) at each step."""
    placed = {(0, 0), (1, 0), (1, 1)}
    k = 0
    while len(placed) < size:
        addable = set()
        for x, y in placed:
            for ox, oy in OFFS:
                m = (x + ox, y + oy)
                if m in placed:
                    continue
                ring = [(m[0] + a, m[1] + b) in placed for a, b in OFFS]
                if any(ring[i] and ring[(i + 1) % 6] for i in range(6)):
                    addable.add(m)
        options = sorted(addable)
        pick = choices[k % len(choices)] if choices else 0
        placed.add(options[pick % len(options)])
        k += 1
    return np.array(sorted(placed), dtype=np.int64)


@st.composite
def grown_bitmaps(draw, min_size: int = 3, max_size: int = 60) -> np.ndarray:
    """Bitmaps of random constructible connected shapes."""
    size = draw(st.integers(min_size, max_size))
    choices = draw(st.lists(st.integers(0, 10_000), min_size=1, max_size=size))
    return cells_to_bitmap(grow_cells(size, choices))


@st.composite
def any_bitmaps(draw, max_side: int = 9) -> np.ndarray:
    """Arbitrary small bitmaps (any pattern of 0s and 1s)."""
    h = draw(st.integers(1, max_side))
    w = draw(st.integers(1, max_side))
    bits = draw(st.lists(st.booleans(), min_size=h * w, max_size=h * w))
    return np.array(bits, dtype=bool).reshape(h, w)


def text_of(bitmap: np.ndarray, on: str = "1", off: str = "0") -> str:
    return "\n".join("".join(on if v else off for v in row) for row in bitmap) + "\n"
