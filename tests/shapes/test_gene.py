"""The gene: conventions, NN, dense grids."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings

from etswarm.shapes import compute_gene, gene_grid, load_shape, scaled_gene
from etswarm.shapes.gene import bitmap_cells, cells_to_bitmap
from etswarm.shapes.lattice import edge_count

from .helpers import any_bitmaps


def test_full_3x3_block_centre_is_paper_example() -> None:
    g = compute_gene(np.ones((3, 3), dtype=bool))
    rows = {(x, y): (f, nn) for x, y, f, nn in g.as_array().tolist()}
    assert rows[(0, 0)] == (1, 6)
    # corners: top-left (i=0,j=0) -> tag (-1, 1); its neighbours in the block: (i,j+1),(i+1,j)
    assert rows[(-1, 1)] == (1, 2)
    # bottom-left (i=2,j=0) -> (-1,-1): neighbours (i-1,j),(i-1,j+1),(i,j+1)
    assert rows[(-1, -1)] == (1, 3)


def test_tags_follow_the_origin_and_axis_conventions() -> None:
    b = np.zeros((4, 5), dtype=bool)  # row0 = 1, col0 = 2
    b[0, 4] = True  # top right: X = 4 - 2 = 2, Y = 1 - 0 = 1
    b[3, 0] = True  # bottom left: X = -2, Y = 1 - 3 = -2
    assert bitmap_cells(b).tolist() == [[-2, -2], [2, 1]]
    g = compute_gene(b)
    assert len(g) == 20
    keys = list(zip(g.x.tolist(), g.y.tolist(), strict=True))
    assert keys == sorted(keys)
    assert set(keys) == {(x, y) for x in range(-2, 3) for y in range(-2, 2)}


@settings(max_examples=150, deadline=None)
@given(any_bitmaps())
def test_nn_sum_is_twice_the_edges_between_ones(bitmap: np.ndarray) -> None:
    g = compute_gene(bitmap)
    ones = g.flag == 1
    cells = np.stack([g.x[ones], g.y[ones]], axis=1)
    assert int(g.nn[ones].sum()) == 2 * edge_count(cells)
    assert g.flag.sum() == bitmap.sum()
    assert ((g.nn >= 0) & (g.nn <= 6)).all()


@settings(max_examples=80, deadline=None)
@given(any_bitmaps())
def test_gene_grid_matches_the_table(bitmap: np.ndarray) -> None:
    g = compute_gene(bitmap)
    grid = gene_grid(g)
    for x, y, f, nn in g.as_array().tolist():
        assert grid.flag_at(x, y) == f and grid.nn_at(x, y) == nn
    assert grid.flag_at(grid.x0 - 1, grid.y0) == 0
    assert grid.flag.shape == (bitmap.shape[1], bitmap.shape[0])


def test_scaled_gene_of_a_shape_matches_its_gene_on_the_cells() -> None:
    shape = load_shape("starfish")
    full = shape.gene()
    part = scaled_gene(shape.cells)
    on_full = {(x, y): nn for x, y, f, nn in full.as_array().tolist() if f}
    on_part = {(x, y): nn for x, y, f, nn in part.as_array().tolist() if f}
    assert on_full == on_part


def test_cells_to_bitmap_round_trips_up_to_translation() -> None:
    cells = load_shape("heart").cells
    back = bitmap_cells(cells_to_bitmap(cells))
    shift = back[0] - cells[0]
    assert np.array_equal(back - shift, cells)


def test_gene_records_are_plain_ints() -> None:
    rec = compute_gene(np.ones((1, 3), dtype=bool)).records()
    assert rec[0] == {"x": -1, "y": 0, "flag": 1, "nn": 1}
    assert all(type(v) is int for r in rec for v in r.values())
