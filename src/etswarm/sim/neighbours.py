"""Neighbour search shared by the radio and the collisions: an incremental spatial hash.

The plane is cut into square cells of side ``cell_mm``; cell ``(cx, cy)`` holds the robots
whose centre lies in ``[cx*cell, (cx+1)*cell) x [cy*cell, (cy+1)*cell)``. Cells are hashed
into a power-of-two table of buckets, so the world needs no bounds (walls are optional).
Each bucket is a doubly linked list of robot indices, which makes inserting, removing and
moving one robot O(1): a robot that did not move costs nothing, and a robot that moved
within its cell costs one comparison.

The hot loops (move, collide) inline the "did the cell change?" test and call
:func:`relink` only when it did: passing arrays to a compiled function costs reference
counting on every call, which would dominate a per-robot loop.

Queries scan every cell overlapping the box ``[x-q, x+q] x [y-q, y+q]`` and keep only the
robots whose stored cell is the scanned cell (two cells may share a bucket), so each robot
is seen at most once per query. With ``cell_mm = 4 * body radius`` a contact query
(q = 2 r) touches 2 x 2 cells and a radio query (q = 70 mm) 3 x 3 or 4 x 4.

All functions are numba-compiled and work on a :class:`Grid` of plain arrays:

- ``head``   (B,) int32: first robot of each bucket, -1 if empty (B a power of two >= 2 N)
- ``nxt``    (N,) int32: next robot in the same bucket, -1 at the end
- ``prv``    (N,) int32: previous robot in the same bucket, -1 at the front
- ``cell_x``, ``cell_y`` (N,) int64: the cell each robot is filed under
- ``in_grid`` (N,) bool: robot is filed (present robots only)
- ``known_pos`` (N, 2) float64 mm: the position the grid last saw, to detect outside edits
- ``inv_cell`` (1,) float64: 1 / cell_mm
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit


class Grid(NamedTuple):
    """The spatial hash (see the module docstring for every field's shape and meaning)."""

    head: np.ndarray
    nxt: np.ndarray
    prv: np.ndarray
    cell_x: np.ndarray
    cell_y: np.ndarray
    in_grid: np.ndarray
    known_pos: np.ndarray
    inv_cell: np.ndarray


def make_grid(n_robots: int, cell_mm: float) -> Grid:
    """An empty grid for ``n_robots`` robots and cells of side ``cell_mm`` mm."""
    if cell_mm <= 0:
        raise ValueError(f"cell size must be > 0 mm, got {cell_mm}")
    buckets = 1024
    while buckets < 2 * n_robots:
        buckets *= 2
    return Grid(
        head=np.full(buckets, -1, dtype=np.int32),
        nxt=np.full(n_robots, -1, dtype=np.int32),
        prv=np.full(n_robots, -1, dtype=np.int32),
        cell_x=np.zeros(n_robots, dtype=np.int64),
        cell_y=np.zeros(n_robots, dtype=np.int64),
        in_grid=np.zeros(n_robots, dtype=np.bool_),
        known_pos=np.full((n_robots, 2), np.nan),
        inv_cell=np.array([1.0 / cell_mm]),
    )


@njit(cache=True, inline="always")
def cell_of(v: float, inv_cell: float) -> int:
    """Cell coordinate of a position coordinate ``v`` (mm)."""
    return np.int64(np.floor(v * inv_cell))


@njit(cache=True, inline="always")
def bucket_of(cx: int, cy: int, mask: int) -> int:
    """Bucket of cell (cx, cy): a multiplicative hash masked to the table size."""
    h = (cx * np.int64(0x9E3779B1)) ^ (cy * np.int64(0x85EBCA77))
    h ^= h >> np.int64(15)
    return h & mask


@njit(cache=True, inline="always")
def unlink(head, nxt, prv, cell_x, cell_y, i):
    """Remove robot ``i`` from its bucket list (arrays of a Grid)."""
    p = prv[i]
    q = nxt[i]
    if p >= 0:
        nxt[p] = q
    else:
        head[bucket_of(cell_x[i], cell_y[i], head.shape[0] - 1)] = q
    if q >= 0:
        prv[q] = p
    nxt[i] = -1
    prv[i] = -1


@njit(cache=True, inline="always")
def link(head, nxt, prv, cell_x, cell_y, i, cx, cy):
    """File robot ``i`` under cell (cx, cy) at the front of its bucket list."""
    b = bucket_of(cx, cy, head.shape[0] - 1)
    first = head[b]
    nxt[i] = first
    prv[i] = -1
    if first >= 0:
        prv[first] = i
    head[b] = i
    cell_x[i] = cx
    cell_y[i] = cy


@njit(cache=True)
def relink(head, nxt, prv, cell_x, cell_y, i, cx, cy):
    """Move robot ``i`` (filed) to cell (cx, cy). Called only when a robot changes cell."""
    unlink(head, nxt, prv, cell_x, cell_y, i)
    link(head, nxt, prv, cell_x, cell_y, i, cx, cy)


@njit(cache=True)
def grid_insert(grid: Grid, i: int, x: float, y: float) -> None:
    """File robot ``i`` at position (x, y) mm."""
    inv = grid.inv_cell[0]
    link(grid.head, grid.nxt, grid.prv, grid.cell_x, grid.cell_y, i, cell_of(x, inv),
         cell_of(y, inv))
    grid.in_grid[i] = True
    grid.known_pos[i, 0] = x
    grid.known_pos[i, 1] = y


@njit(cache=True)
def grid_remove(grid: Grid, i: int) -> None:
    """Take robot ``i`` out of the grid (no-op if it is not filed)."""
    if not grid.in_grid[i]:
        return
    unlink(grid.head, grid.nxt, grid.prv, grid.cell_x, grid.cell_y, i)
    grid.in_grid[i] = False
    grid.known_pos[i, 0] = np.nan
    grid.known_pos[i, 1] = np.nan


@njit(cache=True)
def grid_move(grid: Grid, i: int, x: float, y: float) -> None:
    """Robot ``i`` (filed) is now at (x, y) mm: refile it only if its cell changed."""
    inv = grid.inv_cell[0]
    grid.known_pos[i, 0] = x
    grid.known_pos[i, 1] = y
    cx = cell_of(x, inv)
    cy = cell_of(y, inv)
    if cx != grid.cell_x[i] or cy != grid.cell_y[i]:
        relink(grid.head, grid.nxt, grid.prv, grid.cell_x, grid.cell_y, i, cx, cy)


@njit(cache=True)
def grid_sync(grid: Grid, pos: np.ndarray, present: np.ndarray, dirty: np.ndarray,
              dirty_flag: np.ndarray, n_dirty: int) -> int:
    """Bring the grid in line with ``pos``/``present`` after edits made outside the kernel.

    Robots that appeared or whose position differs from what the grid last saw are
    (re)filed and appended to the work list ``dirty`` (flags in ``dirty_flag``), so the
    next collision phase examines them. Robots no longer present are removed. Returns the
    new work-list length. Cost O(N) comparisons, nothing refiled when nothing changed.
    """
    for i in range(pos.shape[0]):
        if present[i]:
            x = pos[i, 0]
            y = pos[i, 1]
            if grid.in_grid[i]:
                if x == grid.known_pos[i, 0] and y == grid.known_pos[i, 1]:
                    continue
                grid_move(grid, i, x, y)
            else:
                grid_insert(grid, i, x, y)
            if dirty_flag[i] == 0:
                dirty_flag[i] = 1
                dirty[n_dirty] = i
                n_dirty += 1
        elif grid.in_grid[i]:
            grid_remove(grid, i)
    return n_dirty


@njit(cache=True)
def neighbours_within(grid: Grid, pos: np.ndarray, i: int, radius: float,
                      out: np.ndarray) -> int:
    """Indices of filed robots j != i with centre distance <= ``radius`` mm of robot i.

    Writes them to ``out`` (int32, large enough) and returns how many. Used by tests and
    by slow-path helpers; the kernels inline the same loop.
    """
    inv = grid.inv_cell[0]
    mask = grid.head.shape[0] - 1
    x = pos[i, 0]
    y = pos[i, 1]
    r2 = radius * radius
    count = 0
    for cx in range(cell_of(x - radius, inv), cell_of(x + radius, inv) + 1):
        for cy in range(cell_of(y - radius, inv), cell_of(y + radius, inv) + 1):
            j = grid.head[bucket_of(cx, cy, mask)]
            while j >= 0:
                if j != i and grid.cell_x[j] == cx and grid.cell_y[j] == cy:
                    dx = pos[j, 0] - x
                    dy = pos[j, 1] - y
                    if dx * dx + dy * dy <= r2:
                        out[count] = j
                        count += 1
                j = grid.nxt[j]
    return count
