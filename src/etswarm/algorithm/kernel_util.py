"""Constants and small compiled helpers shared by the ET controller's rules."""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    R_GROWTH,
    R_SINCE,
    R_STATE,
)
from etswarm.algorithm.params import (
    C_GENE_X0,
    C_GENE_Y0,
)
from etswarm.algorithm.states import State

# State codes as plain ints (numba folds module-level ints into the compiled code).
QUEUED = int(State.QUEUED)
SEARCH = int(State.SEARCH)
INACTIVE = int(State.INACTIVE)
ACTIVE = int(State.ACTIVE)
QUASI = int(State.QUASI)
STABLE = int(State.STABLE)
DANGER = int(State.DANGER)
LEADER = int(State.LEADER)

# Motor commands (simulator contract).
STOP = 0
FORWARD = 1
LEFT = 2
RIGHT = 3

HALF_SQRT3 = 0.8660254037844386
FAR = 1.0e9

# The six lattice directions in cyclic order (DESIGN §1).
DIR_X = (0, 1, 1, 0, -1, -1)
DIR_Y = (1, 1, 0, -1, -1, 0)


@njit(inline="always")
def is_placed(state):  # type: ignore[no-untyped-def]
    """True for the states that hold a lattice tag."""
    return state >= INACTIVE


@njit(inline="always")
def heard_placed_within(i, m, since, reach, nb, nb_dist):  # type: ignore[no-untyped-def]
    """Row m of robot i's table is a placed robot heard since tick ``since`` and read
    within ``reach`` mm."""
    return (
        nb[i, m, NB_ID] >= 0
        and is_placed(nb[i, m, NB_STATE])
        and nb[i, m, NB_LAST] >= since
        and nb_dist[i, m] <= reach
    )


@njit(inline="always")
def direction_index(dx, dy):  # type: ignore[no-untyped-def]
    """Index 0..5 of the lattice direction (dx, dy), or -1 if not a neighbour offset."""
    if dx == 0 and dy == 1:
        return 0
    if dx == 1 and dy == 1:
        return 1
    if dx == 1 and dy == 0:
        return 2
    if dx == 0 and dy == -1:
        return 3
    if dx == -1 and dy == -1:
        return 4
    if dx == -1 and dy == 0:
        return 5
    return -1


@njit(inline="always")
def two_step_direction(dx, dy):  # type: ignore[no-untyped-def]
    """Index 0..5 of the lattice direction k when (dx, dy) is two steps along it (the tags
    across a site from each other), or -1."""
    if dx % 2 != 0 or dy % 2 != 0:
        return -1
    return direction_index(dx // 2, dy // 2)


@njit(inline="always")
def lattice_distance(ax, ay, bx, by):  # type: ignore[no-untyped-def]
    """Distance between tags (ax, ay) and (bx, by) in lattice spacings."""
    dy = ay - by
    dx = (ax - bx) - 0.5 * dy
    return math.sqrt(dx * dx + (dy * HALF_SQRT3) ** 2)


@njit(inline="always")
def gene_at(grid, ci, x, y):  # type: ignore[no-untyped-def]
    """Value of a gene grid (flag or NN, (GX, GY)) at tag (x, y); 0 outside the grid."""
    gx = x - ci[C_GENE_X0]
    gy = y - ci[C_GENE_Y0]
    if gx < 0 or gy < 0 or gx >= grid.shape[0] or gy >= grid.shape[1]:
        return 0
    return grid[gx, gy]


@njit(inline="always")
def first_growth(i, ri):  # type: ignore[no-untyped-def]
    """Robot i still works on the first formation: no election since the start gave it a
    new target (a false alarm's kept target does not count, see ``R_GROWTH``). The rules
    tuned apart for the first formation and for regrowth ask this, not the epoch."""
    return ri[i, R_GROWTH] == 0


@njit
def set_state(i, ri, state, tick):  # type: ignore[no-untyped-def]
    ri[i, R_STATE] = state
    ri[i, R_SINCE] = tick


@njit(inline="always")
def hex_distance(dx, dy):  # type: ignore[no-untyped-def]
    """Lattice steps between two tags that differ by (dx, dy)."""
    if (dx >= 0) == (dy >= 0):
        return max(abs(dx), abs(dy))
    return abs(dx) + abs(dy)
