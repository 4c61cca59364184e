"""Where a Leader puts the scaled shape: the translation of ``scale(bitmap, n)``.

The Leader computes this on board from what it learnt while electing; the host answers
its request with the same computation (``run.ETRun``). Growth needs a seed triangle: three
mutually adjacent held sites of the new shape, from which searchers localise. The paper
seeds the Leader and two of its neighbours; a Leader with no two adjacent neighbours
left (dead robots round it, ``T`` ``kill random=0.1`` seed 7, where the Leader had one
live neighbour) seeds from any triangle of sites it heard or remembers held instead, and
leaves the new shape itself if it must.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from etswarm.algorithm.extent import cells_in
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS, turn_cells

Tag = tuple[int, int]

#: With ``seeds`` "any", another seed triangle wins over the Leader's own only when it
#: covers at least this share of the shape's cells more of the remnant: a placement off
#: the Leader starts growth from every kept robot at once (none is the Active seed).
LEAVE_LEADER_SHARE = 0.2

#: The six neighbour offsets in turn round a site (consecutive ones are adjacent).
RING: list[Tag] = [(int(a), int(b)) for a, b in NEIGHBOUR_OFFSETS]


def triangles_at(tag: Tag, held: set[Tag]) -> list[tuple[Tag, Tag, Tag]]:
    """Seed triangles with a corner on ``tag``: it and two adjacent neighbour sites, all in
    ``held``."""
    if tag not in held:
        return []
    x, y = tag
    out = []
    for a, b in zip(RING, RING[1:] + RING[:1], strict=True):
        p, q = (x + a[0], y + a[1]), (x + b[0], y + b[1])
        if p in held and q in held:
            out.append((tag, p, q))
    return out


def holds_a_pair(kept: set[Tag]) -> bool:
    """Whether two of the sites ``kept`` are lattice neighbours."""
    return any((x + a, y + b) in kept for x, y in kept for a, b in RING)


@dataclass(frozen=True)
class RemnantView:
    """What the Leader knows of its remnant when it places the scaled shape.

    ``known``: tags it heard held since the election began; ``remnant``: the held tags it
    remembers inside the remnant's ``extent`` (hexagon of least and greatest tags along
    the three axes, (3, 2) int, or None); ``silent``: sites that fell silent (a dead robot
    may stand there); ``enclosed``: silent sites with live robots round them; ``fits``:
    whether a placed shape ((P, 2) tags) lies inside the gene grids.
    """

    known: set[Tag]
    remnant: set[Tag]
    silent: set[Tag]
    enclosed: set[Tag]
    extent: np.ndarray | None
    fits: Callable[[np.ndarray], bool]
    #: with ``placement_off_shape = "fewest"``: the target the remnant was building (tags);
    #: empty, cells off it count like any other
    old_shape: frozenset[Tag] = frozenset()
    #: with ``placement_off_shape = "weigh"``: a cell off ``old_shape`` counts against a
    #: placement as much as a remnant site it leaves out
    weigh_off_shape: bool = False


def choose_translation(
    cells: np.ndarray, leader: Tag, view: RemnantView, seeds: str = "leader"
) -> tuple[int, int] | None:
    """The translation (tx, ty) for the scaled shape ``cells`` ((P, 2) tags), or None when
    no translation fits the gene grids.

    ``seeds = "leader"`` (the paper's seeds): first the translations that put a cell on
    the Leader's site, ranked by: seeded (the Leader and two adjacent known neighbours
    inside), fewest enclosed silent sites, most remembered held sites of the remnant
    inside (less the cells off ``view.old_shape`` with ``view.weigh_off_shape``), fewest
    cells off ``view.old_shape`` (when it is given), most cells inside the extent, most
    known sites, fewest silent sites, then smallest shift. If none of them is seeded, the
    translations that put a cell on any site known or remembered held, seeded by any
    triangle of such sites, ranked the same way.

    ``seeds = "any"``: the best translation seeded by any triangle (ranked the same way,
    the Leader's own site inside as the last tie-break before the shift) replaces the
    Leader's own when it covers fewer enclosed silent sites, or as many and far more of
    the remnant (``LEAVE_LEADER_SHARE``): a Leader hemmed in by dead robots (``kill``)
    no longer has to keep the shape on itself when another seed triangle keeps far more
    of the remnant.

    ``seeds = "silent"``: as "any" when the Leader knows of silent sites inside its
    remnant (``view.enclosed``: robots died among the living), else as "leader".
    """
    if seeds == "silent":
        seeds = "any" if view.enclosed else "leader"
    own = [(leader[0] - int(sx), leader[1] - int(sy)) for sx, sy in cells.tolist()]
    held = view.known | {leader}
    best = _best(cells, own, triangles_at(leader, held), view, held=held)
    seeded_here = best is not None and best[0] == 0
    if seeds == "leader" and seeded_here:
        return best[-2], best[-1]
    # sites it remembers held in the remnant count too: it heard few robots itself
    held |= view.remnant
    triangles = [t for tag in sorted(held) for t in triangles_at(tag, held)]
    if triangles:
        shifts = sorted({(kx - int(sx), ky - int(sy)) for kx, ky in held for sx, sy in cells})
        anywhere = _best(
            cells, shifts, triangles, view, leader if seeds == "any" else None, held=held
        )
        if anywhere is not None and anywhere[0] == 0:
            if seeded_here and not _far_better(anywhere, best, len(cells)):
                return best[-2], best[-1]
            return anywhere[-2], anywhere[-1]
    return None if best is None else (best[-2], best[-1])


def choose_placement(
    cells: np.ndarray, leader: Tag, view: RemnantView, seeds: str = "leader", turns: bool = False
) -> tuple[int, int, int] | None:
    """The turn and translation (turn, tx, ty) for the scaled shape ``cells`` ((P, 2)
    tags): ``choose_translation`` of ``lattice.turn_cells(cells, turn)``; None when no
    translation fits the gene grids.

    Without ``turns`` the turn is 0 (the original's orientation). With ``turns`` each of
    the six turns gets its translation, and each is ranked by ``_best``'s key with seed
    triangles anywhere among the sites known or remembered held. A turn replaces the one
    before it in the order 0-5 only when it ranks better on seeding and enclosed silent
    sites, or equal there and covers at least one more remnant site (less the cells off
    the old shape when those are weighed): an equal one leaves the shape as it was."""
    if not turns:
        shift = choose_translation(cells, leader, view, seeds)
        return None if shift is None else (0, shift[0], shift[1])
    pool = view.known | view.remnant | {leader}
    triangles = [t for tag in sorted(pool) for t in triangles_at(tag, pool)]
    best: tuple[int, int, int] | None = None
    best_key: tuple[int, ...] | None = None
    for turn in range(6):
        turned = turn_cells(cells, turn)
        shift = choose_translation(turned, leader, view, seeds)
        if shift is None:
            continue
        key = _best(turned, [shift], triangles, view, held=pool)
        if key is None:
            continue
        if best_key is None or key[:2] < best_key[:2] or (
            key[:2] == best_key[:2] and key[2] < best_key[2]
        ):
            best_key = key
            best = (turn, shift[0], shift[1])
    return best


def _far_better(other: tuple[int, ...], own: tuple[int, ...], n_cells: int) -> bool:
    """Whether placement key ``other`` is worth leaving the Leader's own seeds for: it
    covers fewer enclosed silent sites, or as many and at least ``LEAVE_LEADER_SHARE`` of
    the shape's cells more of the remembered remnant (``_best``'s keys: [1] enclosed,
    [2] minus the remnant covered)."""
    if other[1] != own[1]:
        return other[1] < own[1]
    return own[2] - other[2] >= max(1.0, LEAVE_LEADER_SHARE * n_cells)


def _best(
    cells: np.ndarray,
    shifts: list[Tag],
    triangles: list[tuple[Tag, Tag, Tag]],
    view: RemnantView,
    leader: Tag | None = None,
    held: set[Tag] | frozenset[Tag] = frozenset(),
) -> tuple[int, ...] | None:
    """The least ranking key (see ``choose_translation``) over ``shifts``, ending with the
    shift (tx, ty); None when no shift fits. With ``leader``, a shift that keeps the
    Leader's site wins a tie before the shortest shift does. A shift on no seed triangle
    ranks better when it keeps two adjacent sites of ``held``: searchers can locate a site
    from such a pair, and from one robot alone they cannot."""
    best: tuple[int, ...] | None = None
    for tx, ty in shifts:
        moved = cells + np.array([tx, ty])
        if not view.fits(moved):
            continue
        sites = {(int(x), int(y)) for x, y in moved.tolist()}
        if any(all(c in sites for c in tri) for tri in triangles):
            seeded = 0
        else:
            seeded = 1 if holds_a_pair(sites & held) else 2
        within = 0 if view.extent is None else int(cells_in(moved, view.extent).sum())
        off = len(sites - view.old_shape) if view.old_shape else 0
        covered = len(sites & view.remnant) - (off if view.weigh_off_shape else 0)
        key = (
            seeded, len(sites & view.enclosed), -covered, off,
            -within, -len(sites & view.known), len(sites & view.silent),
            0 if leader is None or leader in sites else 1, abs(tx) + abs(ty), tx, ty,
        )
        if best is None or key < best:
            best = key
    return best
