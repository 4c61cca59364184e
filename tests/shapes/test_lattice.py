"""The skewed lattice: offsets, embedding, connectivity, constructibility."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from etswarm.shapes.lattice import (
    NEIGHBOUR_OFFSETS,
    are_adjacent,
    construction_order,
    depths,
    edge_count,
    enclosed_cells,
    is_connected,
    is_constructible,
    lattice_distance,
    neighbour_counts,
    seed_triangles,
    squared_distance,
    tags_to_xy,
    unconstructible_cells,
    xy_to_nearest_tag,
)

from .helpers import grow_cells


def test_offsets_are_the_design_order_and_cyclic() -> None:
    assert NEIGHBOUR_OFFSETS.tolist() == [[0, 1], [1, 1], [1, 0], [0, -1], [-1, -1], [-1, 0]]
    for k in range(6):
        a, b = NEIGHBOUR_OFFSETS[k], NEIGHBOUR_OFFSETS[(k + 1) % 6]
        assert are_adjacent(tuple(a), tuple(b))


def test_embedding_puts_all_six_neighbours_at_spacing() -> None:
    xy = tags_to_xy(NEIGHBOUR_OFFSETS, 40.0)
    assert np.allclose(np.hypot(xy[:, 0], xy[:, 1]), 40.0)
    assert np.allclose(tags_to_xy([[3, 2]], 10.0), [[10 * (3 - 1), 10 * 2 * math.sqrt(3) / 2]])
    # second ring: sqrt(3) d and 2 d
    assert squared_distance([0, 0], [1, 2]) == 3
    assert squared_distance([0, 0], [2, 0]) == 4


@given(st.integers(-50, 50), st.integers(-50, 50), st.floats(-0.3, 0.3), st.floats(-0.3, 0.3))
def test_nearest_tag_inverts_the_embedding(x: int, y: int, dx: float, dy: float) -> None:
    xy = tags_to_xy([[x, y]], 40.0) + np.array([[dx, dy]]) * 40.0
    assert xy_to_nearest_tag(xy, 40.0).tolist() == [[x, y]]


def test_lattice_distance() -> None:
    assert lattice_distance(np.array([0, 0]), NEIGHBOUR_OFFSETS).tolist() == [1] * 6
    assert int(lattice_distance(np.array([0, 0]), np.array([1, -1]))) == 2
    assert int(lattice_distance(np.array([0, 0]), np.array([3, 3]))) == 3


def test_diagonal_touching_pixels_are_not_connected() -> None:
    # (i, j) and (i+1, j+1) in the bitmap are tags differing by (1, -1): not neighbours
    assert not is_connected(np.array([[0, 0], [1, -1]]))
    assert is_connected(np.array([[0, 0], [1, 1]]))
    assert not is_connected(np.zeros((0, 2)))


def test_one_wide_line_is_unconstructible_and_two_wide_strip_is() -> None:
    line = np.array([[x, 0] for x in range(6)])
    assert not is_constructible(line)
    assert len(unconstructible_cells(line)) == 6
    strip = np.array([[x, y] for x in range(6) for y in (0, 1)])
    assert is_constructible(strip)
    assert len(unconstructible_cells(strip)) == 0


def test_dangling_tip_is_reported() -> None:
    tri = [[0, 0], [1, 0], [1, 1]]
    shape = np.array([*tri, [2, 1], [3, 2]])  # (2,1) touches (1,0),(1,1); (3,2) only (2,1)
    assert unconstructible_cells(shape).tolist() == [[3, 2]]


def test_bowtie_halves_cannot_build_each_other() -> None:
    # two fat blobs meeting only at (0,0), through non-consecutive neighbours of it
    upper = {(x, y) for x in range(0, 3) for y in range(1, 4)} | {(0, 0)}
    lower = {(x, y) for x in range(-4, 0) for y in range(-4, 0)} | {(0, -1), (0, 0)}
    cells = np.array(sorted(upper | lower))
    assert is_connected(cells)
    bad = {tuple(t) for t in unconstructible_cells(cells).tolist()}
    assert bad == upper - {(0, 0)}  # the smaller blob cannot be reached from the larger
    assert not is_constructible(cells)


def test_construction_order_is_valid() -> None:
    cells = grow_cells(40, [7, 3, 11, 2])
    seeds = seed_triangles(cells)
    assert len(seeds) > 0
    order = construction_order(cells, seeds[0])
    assert len(order) == len(cells)
    placed = {tuple(t) for t in order[:3].tolist()}
    for t in order[3:].tolist():
        nbrs = [(t[0] + a, t[1] + b) in placed for a, b in NEIGHBOUR_OFFSETS.tolist()]
        assert any(nbrs[k] and nbrs[(k + 1) % 6] for k in range(6))
        placed.add(tuple(t))


def test_construction_order_rejects_bad_seeds() -> None:
    cells = np.array([[0, 0], [1, 0], [2, 0], [1, 1]])
    with pytest.raises(ValueError):
        construction_order(cells, [[0, 0], [1, 0], [2, 0]])
    with pytest.raises(ValueError):
        construction_order(cells, [[0, 0], [1, 0], [5, 5]])


@settings(max_examples=60, deadline=None)
@given(st.integers(3, 80), st.lists(st.integers(0, 1000), min_size=1, max_size=20))
def test_grown_sets_build_from_every_reported_seed(size: int, choices: list[int]) -> None:
    cells = grow_cells(size, choices)
    assert is_connected(cells) and is_constructible(cells)
    seeds = seed_triangles(cells)
    for tri in seeds[:: max(1, len(seeds) // 5)]:
        assert len(construction_order(cells, tri)) == len(cells)
    assert edge_count(cells) * 2 == int(neighbour_counts(cells).sum())


def test_depths_of_a_hexagon_count_the_rings_in_from_its_rim() -> None:
    # Every site within 3 steps of (0, 0): the rim is ring 3, depth 1; the centre depth 4.
    cells = np.array(
        [(x, y) for x in range(-4, 5) for y in range(-4, 5) if lattice_distance(
            np.array([x, y]), np.array([0, 0])) <= 3], dtype=np.int64
    )
    ring = lattice_distance(cells, np.zeros(2, dtype=np.int64))
    assert np.array_equal(depths(cells), 4 - ring)
    assert depths(np.zeros((0, 2), dtype=np.int64)).shape == (0,)


def hex_ring_shape(inner: int, outer: int) -> np.ndarray:
    """The sites from ``inner`` to ``outer`` lattice steps from (0, 0), (P, 2) tags."""
    span = range(-outer - 1, outer + 2)
    return np.array(
        [(x, y) for x in span for y in span
         if inner <= lattice_distance(np.array([x, y]), np.zeros(2, dtype=np.int64)) <= outer],
        dtype=np.int64,
    )


def test_the_holes_of_a_ring_are_the_sites_it_encloses() -> None:
    ring = hex_ring_shape(3, 5)
    holes = enclosed_cells(ring)
    inside = lattice_distance(holes, np.zeros(2, dtype=np.int64))
    assert len(holes) == 19 and inside.max() == 2  # the 1 + 6 + 12 sites within 2 steps
    # A filled hexagon has none, nor does a ring cut open by a one-site-wide slot: the
    # slot's sites join the middle to the outside.
    assert len(enclosed_cells(hex_ring_shape(0, 5))) == 0
    slot = (ring[:, 1] == 0) & (ring[:, 0] > 0)
    assert len(enclosed_cells(ring[~slot])) == 0
    # A gap that touches the outside only corner to corner (no lattice step) does not
    # open it: the skewed lattice's neighbours are the six offsets, not the eight pixels.
    corner = np.array([(x, y) for x in range(-3, 4) for y in range(-3, 4)
                       if max(abs(x), abs(y)) == 3 and (x, y) != (3, -3)], dtype=np.int64)
    assert len(enclosed_cells(corner)) == 25


@settings(max_examples=40, deadline=None)
@given(st.integers(3, 80), st.lists(st.integers(0, 1000), min_size=1, max_size=20))
def test_a_cell_deeper_than_the_rim_has_a_neighbour_one_step_shallower(
    size: int, choices: list[int]
) -> None:
    cells = grow_cells(size, choices)
    depth = depths(cells)
    index = {tuple(c): k for k, c in enumerate(cells.tolist())}
    for k, (x, y) in enumerate(cells.tolist()):
        around = [index.get((x + ox, y + oy)) for ox, oy in NEIGHBOUR_OFFSETS.tolist()]
        assert (depth[k] == 1) == (None in around)
        inside = [depth[m] for m in around if m is not None]
        assert all(abs(v - depth[k]) <= 1 for v in inside)
        if depth[k] > 1:
            assert min(inside) == depth[k] - 1
