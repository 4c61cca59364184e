"""Placed robots: Inactive -> Active -> Quasi/Stable, Stable -> Danger (paper Table 1)."""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import (
    ACTIVE,
    DIR_X,
    DIR_Y,
    INACTIVE,
    QUASI,
    STABLE,
    direction_index,
    gene_at,
    is_placed,
    set_state,
)
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_PREV,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_BELOW_SINCE,
    R_COUNT,
    R_CUT_OFF_SINCE,
    R_EPOCH,
    R_EXCUSED,
    R_HELD_EPOCH,
    R_MASK,
    R_MISSING,
    R_NN,
    R_OFF_REFINE,
    R_QUASI_UNTIL,
    R_REMEMBERED_SINCE,
    R_RESUMED_AT,
    R_SEEN_FULL,
    R_SINCE,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
)
from etswarm.algorithm.offsets import refine_offset
from etswarm.algorithm.params import (
    C_REPORT_PATIENCE,
    C_TICKS_DANGER,
    C_TICKS_NB_FRESH,
    C_TICKS_QUASI,
    C_TICKS_REGEN_QUIET,
    C_TICKS_REMEMBERED,
    F_SPACING,
)
from etswarm.algorithm.regeneration import start_election
from etswarm.algorithm.rejoin import leave_if_far, rejoin_if_alone, rejoin_if_cut_off
from etswarm.algorithm.site_memory import is_held

#: Inactive robots with no Active neighbour for this many evaluations become Active.
INACTIVE_PATIENCE_TICKS = 31 * 60
#: A Stable robot whose count falls short only by neighbours it knew of through their
#: neighbours' reports (not heard itself) waits this many times the Danger timeout.
REPORTED_PATIENCE = 4


@njit(inline="always")
def bit_count(bits):  # type: ignore[no-untyped-def]
    """Number of the six direction bits set in ``bits``."""
    count = 0
    for k in range(6):
        count += (bits >> k) & 1
    return count


@njit
def gene_dirs(x, y, gene, ci):  # type: ignore[no-untyped-def]
    """Bits k of the neighbour sites of (x, y) that are sites of the gene ``gene``."""
    bits = 0
    for k in range(6):
        if gene_at(gene, ci, x + DIR_X[k], y + DIR_Y[k]) == 1:
            bits |= 1 << k
    return bits


@njit
def reported_dirs(i, tick, ri, nb, fresh, seen_dirs):  # type: ignore[no-untyped-def]
    """Bits k of robot i's neighbour sites it does not hear the holder of (not in
    ``seen_dirs``) that a fresh placed neighbour of the same target reports held."""
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    epoch = ri[i, R_EPOCH]
    reported = 0
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
            continue
        if nb[i, m, NB_EPOCH] != epoch or tick - nb[i, m, NB_LAST] > fresh:
            continue
        jx = nb[i, m, NB_TX]
        jy = nb[i, m, NB_TY]
        if direction_index(jx - x, jy - y) < 0:
            continue
        for k in range(6):
            if (seen_dirs | reported) & (1 << k):
                continue
            kk = direction_index(x + DIR_X[k] - jx, y + DIR_Y[k] - jy)
            if kk >= 0 and (nb[i, m, NB_MASK] >> kk) & 1:
                reported |= 1 << k
    return reported


@njit
def remembered_dirs(i, missing, ri, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """``missing`` (bits k of robot i's neighbour sites) when every one of those sites is
    in its memory of held sites ``held_i`` ((WX, WY) at tag (ox, oy), see ``site_memory``)
    kept for its current epoch; else 0."""
    if missing == 0 or ri[i, R_HELD_EPOCH] != ri[i, R_EPOCH] + 1:
        return 0
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    for k in range(6):
        if (missing >> k) & 1 and not is_held(held_i, x + DIR_X[k], y + DIR_Y[k], ox, oy):
            return 0
    return missing


@njit
def excuse_remembered(i, tick, ri, missing, held_i, ox, oy, ci):  # type: ignore[no-untyped-def]
    """An Active or Quasi robot i that misses neighbour sites ``missing`` (bits): when its
    memory has known all of them held for ``C_TICKS_REMEMBERED`` ticks without a break and
    it is Active, it excuses them (``R_EXCUSED``, as after a false alarm): their holders
    stand out of its range. Keeps ``R_REMEMBERED_SINCE``; returns the bits excused now."""
    if remembered_dirs(i, missing, ri, held_i, ox, oy) == 0:
        ri[i, R_REMEMBERED_SINCE] = 0
        return 0
    if ri[i, R_REMEMBERED_SINCE] == 0:
        ri[i, R_REMEMBERED_SINCE] = tick + 1
        return 0
    if ri[i, R_STATE] != ACTIVE or tick - (ri[i, R_REMEMBERED_SINCE] - 1) < ci[C_TICKS_REMEMBERED]:
        return 0
    ri[i, R_EXCUSED] |= missing
    ri[i, R_REMEMBERED_SINCE] = 0
    return missing


@njit
def placed_rule(i, tick, ri, nb, nb_dist, gene, ci, cf, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Inactive -> Active -> Quasi/Stable, and Stable -> Danger (paper Table 1); ``gene``
    holds the gene flags of the robot's target (GX, GY), ``held_i`` the robot's memory of
    held sites ((WX, WY) at tag (ox, oy), see ``site_memory``)."""
    fresh = ci[C_TICKS_NB_FRESH]
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    ts = ri[i, R_TS]
    state = ri[i, R_STATE]
    epoch = ri[i, R_EPOCH]
    slots = nb.shape[1]
    seen_dirs = 0
    witnessed_stable = False
    lower_active = False
    any_active = False
    heard_placed = False  # any placed robot of its target, lately
    for m in range(slots):
        if nb[i, m, NB_ID] < 0:
            continue
        st = nb[i, m, NB_STATE]
        if not is_placed(st):
            continue
        if nb[i, m, NB_EPOCH] == epoch and tick - nb[i, m, NB_LAST] <= fresh:
            heard_placed = True
        k = direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y)
        if k < 0 or nb[i, m, NB_EPOCH] != epoch:
            continue  # not a neighbour, or one still holding a tag of an older target
        if st == STABLE and nb[i, m, NB_PREV] == ACTIVE:
            witnessed_stable = True
        if tick - nb[i, m, NB_LAST] > fresh:
            continue
        seen_dirs |= 1 << k
        if st == ACTIVE:
            any_active = True
            if nb[i, m, NB_TS] < ts:
                lower_active = True
    # A neighbour site counts when its holder is heard, or when a neighbour that hears the
    # holder reports it (a holder placed a little too far to be heard is still there).
    # Only direct observations are passed on (R_MASK), so no report outlives its source.
    # (Held sites are gene sites, so with all NN heard there is nothing left to report.)
    # Sites excused after a false alarm count too (``regeneration.resume``).
    nn = ri[i, R_NN]
    excused = ri[i, R_EXCUSED]
    count = bit_count(seen_dirs | excused)
    known_dirs = seen_dirs
    if count < nn:
        known_dirs = seen_dirs | reported_dirs(i, tick, ri, nb, fresh, seen_dirs)
        count = bit_count(known_dirs | excused)
        if ACTIVE <= state <= QUASI and count < nn and ci[C_TICKS_REMEMBERED] > 0:
            # Holders its memory knows of but it cannot hear, for minutes: a torn lattice.
            missing = gene_dirs(x, y, gene, ci) & ~(known_dirs | excused) & 63
            excused |= excuse_remembered(i, tick, ri, missing, held_i, ox, oy, ci)
            count = bit_count(known_dirs | excused)
    ri[i, R_COUNT] = count
    ri[i, R_MASK] = seen_dirs
    if state == STABLE:
        ri[i, R_OFF_REFINE] = 0  # its neighbours are all placed: it stands where it is
    else:
        refine_offset(i, tick, nb, nb_dist, ri, cf[F_SPACING])

    if state == INACTIVE:
        if witnessed_stable:
            set_state(i, ri, ACTIVE, tick)
        elif any_active:
            ri[i, R_SINCE] = tick
        elif tick - ri[i, R_SINCE] > INACTIVE_PATIENCE_TICKS:
            set_state(i, ri, ACTIVE, tick)
    elif state == ACTIVE:
        if count >= nn:
            set_state(i, ri, STABLE, tick)
            ri[i, R_BELOW_SINCE] = -1
            ri[i, R_CUT_OFF_SINCE] = 0
        elif lower_active:
            set_state(i, ri, QUASI, tick)
            ri[i, R_QUASI_UNTIL] = tick + ci[C_TICKS_QUASI]
        elif rejoin_if_alone(i, tick, ri, nb, ci, held_i, ox, oy):
            return  # kept where no robot hears it: it searches for its site again
        elif leave_if_far(i, tick, ri, ci, held_i, ox, oy):
            return  # it stands, or believes it stands, most of the way to another site
    elif state == QUASI:
        if tick >= ri[i, R_QUASI_UNTIL]:
            set_state(i, ri, ACTIVE, tick)
    elif state == STABLE:
        excused_only = nn > 0 and known_dirs == 0 and count >= nn
        if rejoin_if_cut_off(i, tick, heard_placed, excused_only, ri, ci, held_i, ox, oy):
            return  # pushed out of its neighbours' range: it searches for its site again
        resumed = ri[i, R_RESUMED_AT]
        if count >= nn or (resumed > 0 and tick - (resumed - 1) < ci[C_TICKS_REGEN_QUIET]):
            # (just back from a false alarm, its neighbours may not all have caught up)
            if count >= nn:
                ri[i, R_SEEN_FULL] = seen_dirs
            ri[i, R_BELOW_SINCE] = -1
        elif ri[i, R_BELOW_SINCE] < 0:
            ri[i, R_BELOW_SINCE] = tick
        else:
            # A neighbour it knew of only through reports (its holder stands out of its
            # range where the lattice has stretched) may drop out of the reports for a
            # while without any damage: when only such neighbours are missing, wait longer
            # (``REPORTED_PATIENCE``). One it heard itself that falls silent is damage.
            patience = ci[C_TICKS_DANGER]
            if ci[C_REPORT_PATIENCE] == 1 and (ri[i, R_SEEN_FULL] & ~known_dirs & 63) == 0:
                patience *= REPORTED_PATIENCE
            if tick - ri[i, R_BELOW_SINCE] >= patience:
                start_election(i, tick, ri, ci)
                ri[i, R_MISSING] = gene_dirs(x, y, gene, ci) & ~(known_dirs | excused)
