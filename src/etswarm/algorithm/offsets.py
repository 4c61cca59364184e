"""Site offsets: where a placed robot really stands, relative to its lattice site.

A searcher stops on a site when two placed neighbours read about d away; it stops a few
mm off the site's centre (median 3-5 mm on `H`, up to 15 mm). With tags alone the next
robot takes that robot to stand exactly on its site, so the errors add up along every
chain of placements: formed shapes stood 20-60 mm (largest residual) from the rigid fit of
their tags, and where two arms grown apart meet again (a regenerated `H`'s crossbar
between the old legs) the free site between them is stretched out of any searcher's
reach (``docs/algorithm.md``).

With offsets on (``ETParams.site_offsets``):

- A robot that takes a site estimates where it stands in the gene's frame from the placed
  robots it read since it stopped (least squares on those readings, from the robots' own
  estimated positions), and keeps the difference from its site's centre, its *offset*.
  Until it is Stable (all its neighbour sites held) it refines the estimate with every
  fresh reading (least mean squares, ``REFINE_GAIN``). The seeds define the frame
  (offset 0); a robot keeps its offset until it leaves its site.
- It sends the offset in its status (bytes 6 and 8, int8 in half-millimetres, see
  ``messages``).
- A searcher expects to read a placed robot from where that robot stands when this is
  farther than the lattice distance (``expected_distance``, ``offset_trust`` of the way):
  the pair window and the consistency test then follow a stretched lattice into its gap
  instead of rejecting the site. Where a robot stands off its site towards the free one,
  the searcher keeps to the lattice distance: it can always stand at d from a body, and
  aiming nearer made captures rarer (formation slower by a fifth).

Positions are in the gene's frame, mm: tag (X, Y) is at ``(d (X - Y/2), d Y sqrt(3)/2)``
(``shapes.lattice.tags_to_xy``).
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.kernel_util import (
    HALF_SQRT3,
    heard_placed_within,
    lattice_distance,
)
from etswarm.algorithm.memory import (
    NB_OX,
    NB_OY,
    NB_TX,
    NB_TY,
    R_OFF_REFINE,
    R_OFF_TICK,
    R_OFF_X,
    R_OFF_Y,
    R_TAG_X,
    R_TAG_Y,
)
from etswarm.algorithm.params import C_OFFSETS, F_OFFSET_TRUST, F_SPACING

#: Offsets are sent in units of this many mm (int8: +-63.5 mm) ...
OFFSET_UNIT_MM = 0.5
#: ... and kept in units of 1 / this many mm, so that small refinements add up.
FINE_PER_MM = 64
#: Fine units per sent unit.
FINE_PER_UNIT = 32
#: Largest offset magnitude a robot sends, in units (int8 range).
OFFSET_MAX_UNITS = 127
#: Placed robots farther than this (mm) do not enter a robot's estimate of its position
#: (the second ring stands at sqrt(3) d = 69 mm for d = 40, at the edge of radio range).
ANCHOR_RANGE_MM = 75.0
#: Gauss-Newton steps of the first estimate (it starts on the site's centre, a few mm
#: from the answer, and converges in two or three).
ESTIMATE_STEPS = 6
#: Each fresh reading of a placed robot moves the estimate this share of the way towards
#: agreeing with it (least mean squares): the estimate averages some ten readings a
#: direction, where the first one rests on one reading (N(0, 2 mm)) of each robot.
REFINE_GAIN = 0.1


@njit(inline="always")
def site_x(x, y, d):  # type: ignore[no-untyped-def]
    """Gene-frame x (mm) of tag (x, y)'s centre for spacing d."""
    return d * (x - 0.5 * y)


@njit(inline="always")
def site_y(y, d):  # type: ignore[no-untyped-def]
    """Gene-frame y (mm) of tag row y's centre for spacing d."""
    return d * HALF_SQRT3 * y


@njit(inline="always")
def sent_offset(fine):  # type: ignore[no-untyped-def]
    """The int8 offset (units of ``OFFSET_UNIT_MM``) a robot sends for its kept one
    ``fine`` (units of 1 / ``FINE_PER_MM`` mm), rounded and clamped."""
    units = (fine + FINE_PER_UNIT // 2) // FINE_PER_UNIT
    return max(-OFFSET_MAX_UNITS, min(OFFSET_MAX_UNITS, units))


@njit(inline="always")
def anchor_x(i, j, nb, d):  # type: ignore[no-untyped-def]
    """Gene-frame x (mm) where placed robot j of robot i's table stands (tag + offset)."""
    return site_x(nb[i, j, NB_TX], nb[i, j, NB_TY], d) + nb[i, j, NB_OX] * OFFSET_UNIT_MM


@njit(inline="always")
def anchor_y(i, j, nb, d):  # type: ignore[no-untyped-def]
    """Gene-frame y (mm) where placed robot j of robot i's table stands (tag + offset)."""
    return site_y(nb[i, j, NB_TY], d) + nb[i, j, NB_OY] * OFFSET_UNIT_MM


@njit(inline="always")
def expected_distance(i, j, cx, cy, nb, ci, cf):  # type: ignore[no-untyped-def]
    """Distance (mm) robot i expects to read from placed robot j of its table when standing
    on the centre of site (cx, cy): from where j really stands (its tag's centre plus the
    offset it sent) with offsets on, else the lattice distance between the two tags.
    With offsets on, the answer is ``ETParams.offset_trust`` of the way from the lattice
    distance to the true one when that is farther, else the lattice distance."""
    d = cf[F_SPACING]
    rel = lattice_distance(cx, cy, nb[i, j, NB_TX], nb[i, j, NB_TY]) * d
    if ci[C_OFFSETS] == 0:
        return rel
    ex = site_x(cx, cy, d) - anchor_x(i, j, nb, d)
    ey = site_y(cy, d) - anchor_y(i, j, nb, d)
    # Only ever farther than the lattice distance: a robot standing off its site towards
    # it narrows the site, and a searcher can always stand at d from a body (it orbits
    # there); one standing away has left room, and the searcher goes in after the centre.
    true = max(math.sqrt(ex * ex + ey * ey), rel)
    return rel + cf[F_OFFSET_TRUST] * (true - rel)


@njit(inline="always")
def is_anchor(i, j, since, nb, nb_dist):  # type: ignore[no-untyped-def]
    """Row j of robot i's table is a placed robot read since ``since`` within range."""
    return heard_placed_within(i, j, since, ANCHOR_RANGE_MM, nb, nb_dist)


@njit(inline="always")
def from_anchor(i, j, px, py, nb, d):  # type: ignore[no-untyped-def]
    """Unit vector (x, y) from where placed robot j of robot i's table stands to the point
    (px, py) (mm, gene frame), and the distance (mm); (0, 0, distance) nearer than 1 mm."""
    ux = px - anchor_x(i, j, nb, d)
    uy = py - anchor_y(i, j, nb, d)
    norm = math.sqrt(ux * ux + uy * uy)
    if norm < 1.0:
        return 0.0, 0.0, norm
    return ux / norm, uy / norm, norm


@njit
def locate(i, since, px, py, nb, nb_dist, d):  # type: ignore[no-untyped-def]
    """Where robot i stands (gene frame, mm) by least squares on its latest readings of the
    placed robots it read since ``since`` (``is_anchor``), by Gauss-Newton steps from the
    guess (px, py). Returns ``(ok, x, y)``; ``ok`` is False with fewer than two such
    robots or with all of them in one line from it."""
    for _ in range(ESTIMATE_STEPS):
        # normal equations of the linearised residuals reading_j - |p - q_j|
        a11 = 0.0
        a12 = 0.0
        a22 = 0.0
        b1 = 0.0
        b2 = 0.0
        n = 0
        for j in range(nb.shape[1]):
            if not is_anchor(i, j, since, nb, nb_dist):
                continue
            ux, uy, norm = from_anchor(i, j, px, py, nb, d)
            if norm < 1.0:
                continue
            res = nb_dist[i, j] - norm
            a11 += ux * ux
            a12 += ux * uy
            a22 += uy * uy
            b1 += ux * res
            b2 += uy * res
            n += 1
        det = a11 * a22 - a12 * a12
        if n < 2 or det < 1e-3:
            return False, px, py
        px += (a22 * b1 - a12 * b2) / det
        py += (a11 * b2 - a12 * b1) / det
    return True, px, py


@njit
def estimate_offset(i, tick, cx, cy, since, nb, nb_dist, ri, ci, d):  # type: ignore[no-untyped-def]
    """Robot i has just taken site (cx, cy): estimate where it stands from the placed robots
    it read since ``since`` (``locate`` from the site's centre) and keep its offset from
    the centre (R_OFF_X, R_OFF_Y; 0 with fewer than two such robots or with offsets off).
    It goes on refining it (``refine_offset``) while not Stable."""
    ri[i, R_OFF_X] = 0
    ri[i, R_OFF_Y] = 0
    ri[i, R_OFF_REFINE] = 0
    if ci[C_OFFSETS] == 0:
        return
    ri[i, R_OFF_REFINE] = 1
    ri[i, R_OFF_TICK] = tick
    px0 = site_x(cx, cy, d)
    py0 = site_y(cy, d)
    ok, px, py = locate(i, since, px0, py0, nb, nb_dist, d)
    if not ok:
        return  # too few robots, or all in one line from it: refine from the centre
    ri[i, R_OFF_X] = round((px - px0) * FINE_PER_MM)
    ri[i, R_OFF_Y] = round((py - py0) * FINE_PER_MM)


@njit
def refine_offset(i, tick, nb, nb_dist, ri, d):  # type: ignore[no-untyped-def]
    """Placed robot i, still refining (R_OFF_REFINE), moves its estimate a little towards
    agreeing with every reading of a placed robot taken since its last refinement."""
    if ri[i, R_OFF_REFINE] == 0:
        return
    since = ri[i, R_OFF_TICK] + 1
    ri[i, R_OFF_TICK] = tick
    px = site_x(ri[i, R_TAG_X], ri[i, R_TAG_Y], d) + ri[i, R_OFF_X] / FINE_PER_MM
    py = site_y(ri[i, R_TAG_Y], d) + ri[i, R_OFF_Y] / FINE_PER_MM
    dx = 0.0
    dy = 0.0
    for j in range(nb.shape[1]):
        if not is_anchor(i, j, since, nb, nb_dist):
            continue
        ux, uy, norm = from_anchor(i, j, px, py, nb, d)
        if norm < 1.0:
            continue
        step = REFINE_GAIN * (nb_dist[i, j] - norm)
        dx += step * ux
        dy += step * uy
    ri[i, R_OFF_X] += round(dx * FINE_PER_MM)
    ri[i, R_OFF_Y] += round(dy * FINE_PER_MM)
