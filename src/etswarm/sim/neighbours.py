"""Neighbour search shared by the radio and the collisions: a cell list with slack.

At each rebuild the bounding box of the present robots is cut into ``nx x ny`` square
cells (side at least the minimum cell size, larger only if more cells than the capacity
max(4096, 8 N) would be needed, so walls are optional and an unbounded swarm still
works). A counting sort by cell (row-major, stable in robot index, so the layout is a
function of the positions only) stores each cell's robots contiguously in "slot" order,
with copies of their positions; a row of neighbouring cells is one contiguous slot range.

- ``start``  (C+1,) int32: cell c = cy*nx + cx holds slots ``start[c] .. start[c+1]-1``
- ``sxb``    (N, 4) float64 mm, by slot: columns ``P_X``, ``P_Y`` the position of the
  robot in the slot (kept current), ``P_BUDGET`` how far the robot may still travel
  before the collision phase must examine it (see :mod:`etswarm.sim.collide`; carried
  over to the new slots by a rebuild), column 3 unused. One row is what a collision
  check of the slot reads and writes: 32 bytes, aligned, so one cache line.
- ``sidx``   (N,) int32: robot in each slot
- ``slot``   (N,) int32: slot of each robot, -1 if not filed (absent)
- ``sref``   (N, 4) float64 mm, by slot: columns ``R_X``, ``R_Y`` the position at the
  start of the contact-list epoch, ``R_BX``, ``R_BY`` the lower corner of the filed cell
  minus the margin (the robot's slack box is this corner plus cell + 2 margin); what a
  moved or pushed robot is checked against, in one aligned 32-byte row
- ``geom``   (7,) float64: minimum cell, margin, cell, 1/cell, origin x, origin y,
  drift (mm)
- ``dims``   (2,) int64: nx, ny
- ``state``  (5,) int64: [stale flag, number of rebuilds, length of the collision work
  list carried over to the next tick, contact-list epoch, drifted flag]
- ``near_slots`` (N, 16) int32, by slot: the robot's contact list (see below) in one
  aligned 64-byte row (one cache line): column ``L_COUNT`` its length (-1: too many
  candidates, use the grid), ``L_EPOCH`` the epoch it was built in (low 32 bits, -1:
  never), then up to LIST_CAP slots from column ``L_FIRST`` on

Contact lists. A collision examination needs the robots within 2 r + margin of the
examined one; scanning its cells each time costs far more than the few robots found. So
the first examination of a robot in an *epoch* lists, in slot order, every robot within
2 r + margin + 4 drift (its contact list), and later examinations in the epoch only
check the listed robots. An epoch lasts while every filed robot stays within ``drift``
mm of where it stood when the epoch began (``sref``): then two robots closer
than 2 r + margin now were closer than 2 r + margin + 4 drift when either list was built,
so a list holds every robot a query of the cells would find, in the same order. A phase
that moves a robot further raises the drifted flag and stops using lists; the next
collision pass starts a new epoch (:func:`new_epoch`), and so does every rebuild (slots
change). Lists are rebuilt lazily, so robots that are never examined cost nothing.

A filed robot may wander up to ``margin`` mm outside its filed cell before the list must
be rebuilt (O(N + cells)); queries widen their box by the margin and clip it to the
grid, so results stay exact. The
phases keep ``sxb``'s positions in step with ``pos`` and raise the stale flag when a robot
leaves its slack box; they rebuild before the next query. Robots that do not move cost
nothing, and a candidate check reads contiguous memory. Outside edits of ``pos`` are
detected by comparing ``pos`` with the slot copies (:func:`grid_sync`).

With ``cell = 4 r + 4 margin`` a collision query (radius 2 r + margin) scans 2 rows of
2 cells.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit


class Grid(NamedTuple):
    """The cell list (see the module docstring for every field's shape and meaning)."""

    start: np.ndarray
    sxb: np.ndarray
    sidx: np.ndarray
    slot: np.ndarray
    sref: np.ndarray
    geom: np.ndarray
    dims: np.ndarray
    state: np.ndarray
    near_slots: np.ndarray


#: indices into Grid.geom
G_CELL_MIN, G_MARGIN, G_CELL, G_INV, G_OX, G_OY, G_DRIFT = 0, 1, 2, 3, 4, 5, 6
#: indices into Grid.state
S_STALE, S_REBUILDS, S_CARRIED, S_EPOCH, S_DRIFTED = 0, 1, 2, 3, 4
#: columns of Grid.sxb: position (mm) and collision budget (mm)
P_X, P_Y, P_BUDGET = 0, 1, 2
#: columns of Grid.sref: position at the start of the epoch, slack-box corner (mm)
R_X, R_Y, R_BX, R_BY = 0, 1, 2, 3
#: columns of Grid.near_slots: list length, epoch built in, first listed slot
L_COUNT, L_EPOCH, L_FIRST = 0, 1, 2
#: Robots a contact list holds; a robot with more candidates is examined through the grid.
LIST_CAP = 14
#: Added to the contact-list radius against rounding (mm).
LIST_EPS = 0.01


def aligned_rows(n_rows: int, width: int, dtype: type = np.float64) -> np.ndarray:
    """A zeroed (n_rows, width) array whose data starts on a 64-byte boundary, so that a
    row of 32 or 64 bytes never straddles two cache lines."""
    count = n_rows * width
    item = np.dtype(dtype).itemsize
    raw = np.zeros(count + 64 // item, dtype=dtype)
    skip = (-raw.ctypes.data % 64) // item
    return raw[skip:skip + count].reshape(n_rows, width)


def make_grid(n_robots: int, cell_mm: float, margin_mm: float,
              drift_mm: float = 1.0) -> Grid:
    """An empty cell list for ``n_robots`` robots: cells of at least ``cell_mm`` mm, slack
    ``margin_mm`` mm, at most max(4096, 8 N) cells; contact-list epochs end when a robot
    drifts ``drift_mm`` mm."""
    if cell_mm <= 0 or margin_mm < 0 or drift_mm <= 0:
        raise ValueError(f"bad grid geometry: cell {cell_mm} mm, margin {margin_mm} mm, "
                         f"drift {drift_mm} mm")
    capacity = max(4096, 8 * n_robots)
    return Grid(
        start=np.zeros(capacity + 1, dtype=np.int32),
        sxb=aligned_rows(n_robots, 4),
        sidx=np.zeros(n_robots, dtype=np.int32),
        slot=np.full(n_robots, -1, dtype=np.int32),
        sref=aligned_rows(n_robots, 4),
        geom=np.array([cell_mm, margin_mm, cell_mm, 1.0 / cell_mm, 0.0, 0.0, drift_mm]),
        dims=np.ones(2, dtype=np.int64),
        state=np.zeros(5, dtype=np.int64),
        near_slots=_empty_lists(n_robots),
    )


def _empty_lists(n_robots: int) -> np.ndarray:
    """Grid.near_slots with no list built: (N, L_FIRST + LIST_CAP) int32, aligned."""
    lists = aligned_rows(n_robots, L_FIRST + LIST_CAP, np.int32)
    lists[:, L_EPOCH] = -1
    return lists


@njit(cache=True, inline="always")
def cell_range(v, reach, origin, inv, n_cells):
    """First and last cell index (clipped to [0, n_cells)) overlapping [v-reach, v+reach]."""
    lo = np.int64(np.floor((v - reach - origin) * inv))
    hi = np.int64(np.floor((v + reach - origin) * inv))
    if lo < 0:
        lo = 0
    if hi > n_cells - 1:
        hi = n_cells - 1
    return lo, hi


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def grid_rebuild(grid, pos, present):
    """File every present robot by its current position (counting sort, O(N + cells)).

    The grid covers the bounding box of the present robots; cells grow beyond the minimum
    size only if the box would need more cells than the capacity.
    """
    n = pos.shape[0]
    start = grid.start
    capacity = start.shape[0] - 1
    margin = grid.geom[G_MARGIN]
    minx = np.inf
    miny = np.inf
    maxx = -np.inf
    maxy = -np.inf
    for i in range(n):
        if present[i]:
            minx = min(minx, pos[i, 0])
            maxx = max(maxx, pos[i, 0])
            miny = min(miny, pos[i, 1])
            maxy = max(maxy, pos[i, 1])
    if minx > maxx:
        minx = maxx = miny = maxy = 0.0
    cell = grid.geom[G_CELL_MIN]
    nx = np.int64((maxx - minx) / cell) + 1
    ny = np.int64((maxy - miny) / cell) + 1
    while nx * ny > capacity:
        cell *= 1.25
        nx = np.int64((maxx - minx) / cell) + 1
        ny = np.int64((maxy - miny) / cell) + 1
    inv = 1.0 / cell
    grid.geom[G_CELL] = cell
    grid.geom[G_INV] = inv
    grid.geom[G_OX] = minx
    grid.geom[G_OY] = miny
    grid.dims[0] = nx
    grid.dims[1] = ny
    n_cells = nx * ny
    cell_idx = np.empty(n, dtype=np.int64)
    kept_budget = np.zeros(n)
    for i in range(n):
        s = grid.slot[i]
        if s >= 0:
            kept_budget[i] = grid.sxb[s, P_BUDGET]
    start[: n_cells + 1] = 0
    for i in range(n):
        if present[i]:
            cx = min(np.int64((pos[i, 0] - minx) * inv), nx - 1)
            cy = min(np.int64((pos[i, 1] - miny) * inv), ny - 1)
            c = cy * nx + cx
            cell_idx[i] = c
            start[c + 1] += 1
        else:
            cell_idx[i] = -1
    for c in range(n_cells):
        start[c + 1] += start[c]
    fill = start[:n_cells].copy()
    for i in range(n):
        c = cell_idx[i]
        if c < 0:
            grid.slot[i] = -1
            continue
        k = fill[c]
        fill[c] = k + 1
        grid.slot[i] = k
        grid.sidx[k] = i
        grid.sxb[k, P_X] = pos[i, 0]
        grid.sxb[k, P_Y] = pos[i, 1]
        grid.sxb[k, P_BUDGET] = kept_budget[i]
        grid.sref[k, R_X] = pos[i, 0]
        grid.sref[k, R_Y] = pos[i, 1]
        grid.sref[k, R_BX] = minx + (c % nx) * cell - margin
        grid.sref[k, R_BY] = miny + (c // nx) * cell - margin
    grid.state[S_STALE] = 0
    grid.state[S_REBUILDS] += 1
    grid.state[S_EPOCH] += 1  # slots changed: every contact list is void
    grid.state[S_DRIFTED] = 0


@njit(cache=True)
def new_epoch(grid):
    """Start a contact-list epoch: every list is void, robots drift from where they are."""
    n_filed = grid.start[grid.dims[0] * grid.dims[1]]
    sxb = grid.sxb
    sref = grid.sref
    for s in range(n_filed):
        sref[s, R_X] = sxb[s, P_X]
        sref[s, R_Y] = sxb[s, P_Y]
    grid.state[S_EPOCH] += 1
    grid.state[S_DRIFTED] = 0


@njit(cache=True)
def drifted(sref, s, x, y, drift2):
    """True when slot ``s`` at (x, y) is more than the drift (``drift2`` its square) away
    from where it stood when the epoch began (``sref``: the grid's array; hot loops pass
    arrays, not the grid, since every field read from the grid tuple costs the numba
    runtime an atomic reference count up and down)."""
    ex = x - sref[s, R_X]
    ey = y - sref[s, R_Y]
    return ex * ex + ey * ey > drift2


@njit(cache=True, inline="always")
def list_reach(grid, near_r):
    """(squared radius, cell-query reach) in mm of the contact lists for examinations
    that need the robots within ``near_r`` mm: radius near_r + 4 drift + LIST_EPS, reach
    that plus the margin (see :func:`build_contact_list`)."""
    list_r = near_r + 4.0 * grid.geom[G_DRIFT] + LIST_EPS
    return list_r * list_r, list_r + grid.geom[G_MARGIN]


@njit(cache=True)
def build_contact_list(grid, a, xi, yi, near_r, row_lo, row_hi, buf):
    """Write the contact list of slot ``a`` at (xi, yi): every other filed slot within
    ``near_r`` + 4 drift (+ LIST_EPS) mm, in slot order, scanning cell rows clipped to
    ``row_lo`` .. ``row_hi``, stamped with the grid's epoch. Returns its length, or -1 if
    it holds more than LIST_CAP.
    ``buf`` (N,) uint32 scratch (the scan keeps slots without branching on distances).
    Hot loops call :func:`contact_list_from` with the grid's arrays instead."""
    list_r2, reach = list_reach(grid, near_r)
    return contact_list_from(grid.start, grid.sxb, grid.near_slots, a, xi, yi,
                             list_r2, reach, grid.geom[G_OX], grid.geom[G_OY],
                             grid.geom[G_INV], grid.dims[0], grid.dims[1], row_lo, row_hi,
                             grid.state[S_EPOCH], buf)


@njit(cache=True)
def contact_list_from(start, sxb, near_slots, a, xi, yi, list_r2, reach, ox, oy, inv,
                      nx, ny, row_lo, row_hi, epoch, buf):
    """:func:`build_contact_list` from the grid's arrays (``start``, ``sxb``,
    ``near_slots``) and geometry (origin ``ox``, ``oy``, 1/cell ``inv``, ``nx`` x ``ny``
    cells; ``list_r2`` and ``reach`` from :func:`list_reach`), stamped ``epoch``."""
    cx0, cx1 = cell_range(xi, reach, ox, inv, nx)
    cy0, cy1 = cell_range(yi, reach, oy, inv, ny)
    cy0 = max(cy0, row_lo)
    cy1 = min(cy1, row_hi)
    ua = np.uint64(a)
    count = 0
    for cy in range(cy0, cy1 + 1):
        row = cy * nx
        for s in range(np.uint64(start[row + cx0]), np.uint64(start[row + cx1 + 1])):
            dx = sxb[s, P_X] - xi
            dy = sxb[s, P_Y] - yi
            buf[count] = s
            count += (dx * dx + dy * dy < list_r2) & (s != ua)
    near_slots[a, L_EPOCH] = np.int32(epoch)
    if count > LIST_CAP:
        near_slots[a, L_COUNT] = -1
        return -1
    for q in range(count):
        near_slots[a, L_FIRST + q] = buf[q]
    near_slots[a, L_COUNT] = count
    return count


@njit(cache=True)
def rebuild_keeping_list(grid, pos, present, lst, n_list, flag):
    """Rebuild the grid while a work list of slots ``lst[:n_list]`` (flags by slot in
    ``flag``) is live: the list and its flags are carried over to the new slots (robots
    no longer present are dropped). Returns the new list length."""
    for k in range(n_list):
        s = lst[k]
        flag[s] = 0
        lst[k] = grid.sidx[s]
    grid_rebuild(grid, pos, present)
    kept = 0
    for k in range(n_list):
        s = grid.slot[lst[k]]
        if s >= 0:  # robots removed from the world leave the list
            lst[kept] = s
            flag[s] = 1
            kept += 1
    return kept


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def grid_sync(grid, pos, present, dirty, dirty_flag, n_dirty):
    """Bring the grid in line with ``pos``/``present`` after edits made outside the kernel.

    If any present robot is unfiled or not where its slot copy says, or an absent robot
    is still filed (or the grid is stale), the grid is rebuilt and those robots are put
    on the collision work list ``dirty`` (slots; flags by slot in ``dirty_flag``), so the
    next collision phase examines them. Returns the new work-list length. Costs O(N)
    comparisons and nothing else when nothing changed. ``dirty[:n_dirty]`` may hold a
    work list carried over from the last tick; it is kept.
    """
    changed = grid.state[0] != 0
    n = pos.shape[0]
    edited = np.zeros(n, dtype=np.bool_)
    for i in range(n):
        s = grid.slot[i]
        if present[i]:
            if s >= 0 and pos[i, 0] == grid.sxb[s, P_X] and pos[i, 1] == grid.sxb[s, P_Y]:
                continue
            changed = True
            edited[i] = True
        elif s >= 0:
            changed = True
    if changed:
        n_dirty = rebuild_keeping_list(grid, pos, present, dirty, n_dirty, dirty_flag)
        for i in range(n):
            if edited[i]:
                s = grid.slot[i]
                grid.sxb[s, P_BUDGET] = 0.0
                if dirty_flag[s] == 0:
                    dirty_flag[s] = 1
                    dirty[n_dirty] = s
                    n_dirty += 1
    return n_dirty


@njit(cache=True)
def neighbours_within(grid, pos, i, radius, out):
    """Robots j != i filed in the grid with centre distance <= ``radius`` mm of robot i.

    Writes their indices to ``out`` (int32, large enough) in slot order and returns how
    many. The phases inline the same loop.
    """
    start = grid.start
    inv = grid.geom[G_INV]
    nx = grid.dims[0]
    x = pos[i, 0]
    y = pos[i, 1]
    r2 = radius * radius
    reach = radius + grid.geom[G_MARGIN]
    cx0, cx1 = cell_range(x, reach, grid.geom[G_OX], inv, nx)
    cy0, cy1 = cell_range(y, reach, grid.geom[G_OY], inv, grid.dims[1])
    count = 0
    for cy in range(cy0, cy1 + 1):
        row = cy * nx
        for k in range(start[row + cx0], start[row + cx1 + 1]):
            j = grid.sidx[k]
            if j == i:
                continue
            dx = grid.sxb[k, P_X] - x
            dy = grid.sxb[k, P_Y] - y
            if dx * dx + dy * dy <= r2:
                out[count] = j
                count += 1
    return count
