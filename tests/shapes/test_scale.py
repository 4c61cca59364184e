"""Scaled shapes: exact size, connected, constructible, deterministic, close to the form."""

from __future__ import annotations

import time

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from etswarm.errors import EtswarmError
from etswarm.shapes import LIBRARY_NAMES, load_shape, scale, scaled_gene
from etswarm.shapes.lattice import is_connected, is_constructible
from etswarm.shapes.scale import _field_cached, _scale_cached, geometric_shrink

from .helpers import any_bitmaps, grown_bitmaps


def check_valid(cells: np.ndarray, n: int) -> None:
    assert cells.dtype == np.int64 and cells.shape == (n, 2)
    assert len({tuple(c) for c in cells.tolist()}) == n
    order = np.lexsort((cells[:, 1], cells[:, 0]))
    assert np.array_equal(order, np.arange(n)), "sorted by (X, Y)"
    assert is_connected(cells)
    assert is_constructible(cells)


@settings(max_examples=60, deadline=None)
@given(grown_bitmaps(min_size=3, max_size=70), st.floats(0.0, 1.0))
def test_every_scaled_shape_is_valid(bitmap: np.ndarray, frac: float) -> None:
    big_n = int(bitmap.sum())
    n = 3 + round(frac * (big_n - 3))
    check_valid(scale(bitmap, n), n)


@settings(max_examples=60, deadline=None)
@given(any_bitmaps(max_side=10), st.floats(0.0, 1.0))
def test_any_bitmap_scales_to_a_valid_shape(bitmap: np.ndarray, frac: float) -> None:
    """Even a disconnected or unbuildable bitmap gives a valid scaled shape."""
    big_n = int(bitmap.sum())
    assume(big_n >= 3)
    n = 3 + round(frac * (big_n - 3))
    check_valid(scale(bitmap, n), n)


@pytest.mark.parametrize("name", LIBRARY_NAMES)
def test_library_shapes_scale_to_every_size(name: str) -> None:
    shape = load_shape(name)
    sizes = range(3, shape.n_cells + 1) if shape.n_cells <= 100 else range(3, shape.n_cells, 17)
    for n in sizes:
        check_valid(scale(shape, n), n)
    assert np.array_equal(scale(shape, shape.n_cells), shape.cells)


def test_deterministic_and_pure() -> None:
    shape = load_shape("starfish")
    first = [scale(shape, n).tobytes() for n in (5, 30, 60)]
    _scale_cached.cache_clear()
    _field_cached.cache_clear()
    again = [scale(shape.bitmap.copy(), n).tobytes() for n in (5, 30, 60)]
    assert first == again
    out = scale(shape, 30)
    out[0, 0] = 999  # callers get a copy, not the cached array
    assert scale(shape, 30)[0, 0] != 999


def test_stays_where_the_original_is() -> None:
    shape = load_shape("bigdisc")
    small = scale(shape, 100)
    assert np.abs(small.mean(axis=0) - shape.cells.mean(axis=0)).max() < 1.0


@pytest.mark.parametrize("n", [2, 0, -1, 46])
def test_out_of_range_n_is_a_one_line_error(n: int) -> None:
    with pytest.raises(EtswarmError) as info:
        scale(load_shape("T"), n)
    msg = str(info.value)
    assert f"N = {n}" in msg and "3 <= N <= 45" in msg and "'T'" in msg


def test_close_to_geometric_shrink() -> None:
    """Mean Jaccard with the geometric shrink over the library at 75/50/25 % (best shift)."""
    scores = []
    for name in LIBRARY_NAMES:
        shape = load_shape(name)
        for frac in (0.75, 0.5, 0.25):
            n = max(3, round(frac * shape.n_cells))
            ref = {tuple(t) for t in geometric_shrink(shape, n).tolist()}
            ours = scale(shape, n).tolist()
            best = 0.0
            for dx in range(-2, 3):
                for dy in range(-2, 3):
                    moved = {(x + dx, y + dy) for x, y in ours}
                    inter = len(ref & moved)
                    best = max(best, inter / (len(ref) + len(moved) - inter))
            scores.append(best)
    assert np.mean(scores) > 0.8
    assert min(scores) > 0.4


def test_fast_enough() -> None:
    shape = load_shape("bigdisc")  # 367 cells
    scale(shape, 200)  # field cached
    t0 = time.perf_counter()
    for n in range(100, 360, 13):
        _scale_cached.cache_clear()
        scale(shape, n)
    per_call = (time.perf_counter() - t0) / len(range(100, 360, 13))
    assert per_call < 0.02  # measured ~1 ms; generous for loaded CI machines


def test_scaled_gene_nn_counts_within_the_set() -> None:
    cells = scale(load_shape("T"), 20)
    g = scaled_gene(cells)
    ones = g.flag == 1
    assert int(ones.sum()) == 20
    got = np.stack([g.x[ones], g.y[ones]], axis=1)
    assert np.array_equal(got, cells)
    assert int(g.nn[ones].min()) >= 2


def test_pinned_outputs() -> None:
    """scale() is part of the protocol robots share: its outputs must never drift.

    If this fails after an intended change to the method, every robot changes together, but
    recorded runs and other machines running an older version will disagree: update the pin
    deliberately.
    """
    import hashlib

    assert scale(load_shape("T"), 12).tolist() == [
        [-2, -1], [-2, 0], [-2, 2], [-1, -1], [-1, 0], [-1, 1], [-1, 2], [-1, 3], [0, 1],
        [0, 2], [0, 3], [1, 2],
    ]
    h = hashlib.sha256()
    for name in ("T", "starfish", "bigdisc"):
        shape = load_shape(name)
        for n in (3, shape.n_cells // 4, shape.n_cells // 2, shape.n_cells - 1):
            h.update(scale(shape, n).astype("<i8").tobytes())
    assert h.hexdigest() == "3bb2ba02c36714c5e0d271ef0044d0059117face3a62b5aff3e6e92e549e1a95"
