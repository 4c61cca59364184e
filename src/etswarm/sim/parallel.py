"""The tick phases on several threads (``SimParams.threads > 1``).

The same model as the single-threaded phases (:mod:`etswarm.sim.radio`,
:mod:`etswarm.sim.motion`, :mod:`etswarm.sim.collide`), split so that threads never write
the same memory and the result does not depend on how many threads run or which thread
does what: the same seed gives byte-identical results for every ``threads > 1`` (and for
this code run on one thread).

Randomness. A sequential stream cannot be shared by threads, so the threaded phases draw
from a counter-based hash instead: every draw is a SplitMix64 hash of a 64-bit run key
(drawn once from the seed's "threads" stream), the tick, the robot and, for the radio,
the receiver and a salt naming the draw (loss, distance noise, speed noise, heading
noise). Uniforms take the top 53 bits; normals use Box-Muller on two such uniforms.
The controller still gets the sequential controller stream (it runs on one thread).

Radio. Pass 1 (one part per thread, by place: the senders filed in the part's slots,
taken in index order): each sender of this tick has its message copied and lists its
receivers (slot order) after the loss draw, appending (sender, receiver, measured
distance) to one stream per receiving part (robots by index, as the controller
parts). Pass 2 (one part per thread, by receiver index): each thread merges the
streams to its part from all parts into sender order (each stream is in sender order
and parts' senders are disjoint) and files the copies. So every inbox holds its copies
in sender order, capped at K exactly as the serial radio does; with no loss and no
noise the inboxes are identical to the serial radio's. A tick whose copies would
overflow a stream (only possible when many robots overlap) is sent through a
one-thread version of the same procedure. Working by place keeps the grid rows a
thread reads in the cache of the core that moved those robots; only the copies cross
between cores, in compact streams.

Motion. Robots split by grid slot into one part per thread (so by place: a thread
moves the robots of the strips it resolves first in the collision phase, and their
grid data stays in its core's cache; splitting by index made both cores write every
cache line of the grid each tick, which cost more than the move itself); the arithmetic
is the serial move's. Robots whose collision budget runs out are flagged for the
collision phase.

Collisions. The work list is a flag per grid slot (bit 1 or bit 2, alternating by pass:
the pass examines slots carrying its bit and sets the other bit on robots it moves). The
grid's cell rows are cut into at most ``2 * STRIP_PAIRS`` horizontal strips of at least 2
rows each, with about equal numbers of robots (a function of the grid alone, never of the
thread count). The threaded simulator files robots in cells of 2 r + 3.1 margin (the
single-threaded one in cells of 4 r + 4 margin): a collision query reaches 2 r + 2 margin from a
centre that lies at most a margin outside its cell, so an examined robot touches only
slots in its own row and one row up or down, and strips 0, 2, 4, ... can be resolved at
the same time, then strips 1, 3, 5, ... (threads take the strips of a colour one at a
time until none is left, the first half of the threads from the top, the others from
the bottom; a strip of colour 1 starts as soon as the two strips next to it are done,
without waiting for the whole colour). The smaller cells also make the queries scan fewer robots. A
strip examines its flagged slots in slot order with the serial pass's arithmetic. A robot
pushed out of its slack box earlier in the pass is examined in the next pass (after the
grid rebuild) instead of now. The order in which overlapping pairs are resolved differs
from the single-threaded phase, so positions differ from threads=1 once robots touch; the
physics (overlap shares, still-robot grip, slop, pass limit, walls) is the same.

Where it runs. The threaded tick loop (:mod:`etswarm.sim.kernel`) calls the per-part
functions (``radio_list_part``, ``radio_file_part``, ``move_part``,
``collide_pass_grab``, ...) on every thread and the one-thread ones (``radio_count``,
``move_finish``, ``collide_begin``, ``collide_after_pass``, ``collide_end``) on one.
``radio_phase_mt``, ``move_phase_mt`` and ``collide_phase_mt`` run the same parts one
after another on the calling thread (the slow path, for Python controllers); they give
the same results.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from etswarm.sim.collide import gather_overlaps, place_pushed, push_apart
from etswarm.sim.fpmath import log_as, sin_cos_as
from etswarm.sim.motion import PREFETCH_AHEAD, clamp_to_arena
from etswarm.sim.neighbours import (
    G_CELL,
    G_DRIFT,
    G_INV,
    G_MARGIN,
    G_OX,
    G_OY,
    L_COUNT,
    L_EPOCH,
    L_FIRST,
    P_BUDGET,
    P_X,
    P_Y,
    R_BX,
    R_BY,
    S_DRIFTED,
    S_EPOCH,
    aligned_rows,
    cell_range,
    contact_list_from,
    drifted,
    grid_rebuild,
    list_reach,
    new_epoch,
)
from etswarm.sim.prefetch import prefetch
from etswarm.sim.radio import senders_by_phase
from etswarm.sim.sync import atomic_add, atomic_load, atomic_store, wait_for
from etswarm.sim.world import PAYLOAD_BYTES

#: Strips per colour in the collision phase (strips = 2 * STRIP_PAIRS at most).
STRIP_PAIRS = 8
#: Copies the threaded radio's stream from one part to another holds per robot of the
#: sending part (a tick that would send more is filed by the one-thread radio).
RX_PER_ROBOT = 16

_C1 = np.uint64(0x9E3779B97F4A7C15)
_C2 = np.uint64(0xD1B54A32D192ED03)
_C3 = np.uint64(0x8CB92BA72F3D8DD7)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30 = np.uint64(30)
_S27 = np.uint64(27)
_S31 = np.uint64(31)
_S11 = np.uint64(11)
_TO_UNIT = 1.0 / 9007199254740992.0  # 2^-53

#: columns of ThreadScratch.part_n
PN_SENT, PN_LOST, PN_BAD, PN_DELIVERED, PN_OVERFLOW, PN_STALE, PN_DRIFT = 0, 1, 2, 3, 4, 5, 6
#: entries of ThreadScratch.cstate
CS_CUR, CS_PASSES, CS_PUSHES, CS_EXAMINED, CS_PENDING, CS_CONT, CS_STRIPS, CS_STALE = range(8)
CS_STOP, CS_DONE, CS_GRAB0, CS_GRAB1, CS_CTL, CS_BUILD = 8, 9, 10, 11, 12, 13
CS_FRONT0, CS_FRONT1, CS_BACK0, CS_BACK1, CS_PASSNO = 14, 15, 16, 17, 18
#: Slots a thread takes at a time when it builds contact lists during the control phase.
PREBUILD_CHUNK = 16

#: columns of ThreadScratch.strip_out
SO_EXAMINED, SO_PUSHES, SO_FLAGGED, SO_STALE, SO_DRIFT = 0, 1, 2, 3, 4

#: hash salts naming the draws
SALT_LOSS, SALT_NOISE_A, SALT_NOISE_B = 1, 2, 3
SALT_SPEED_A, SALT_SPEED_B, SALT_HEAD_A, SALT_HEAD_B = 4, 5, 6, 7


class ThreadScratch(NamedTuple):
    """Work arrays of the threaded phases (N robots, T threads, P = STRIP_PAIRS,
    W = 8 * ceil(T / 8) so that a row of W int64 fills whole cache lines, C =
    RX_PER_ROBOT * (N // T + 1)).

    ``key`` (1,) uint64 hash key; ``parts`` (1,) int64 T; ``rec_i``, ``rec_j`` (T, T, C)
    int32 and ``rec_d`` (T, T, C) float32 mm: the radio's streams, [p, q] holding the
    copies that part p's senders send to part q's receivers (sender, receiver,
    measured distance) in sender order; ``rec_n`` (T, W) int64: their lengths
    (row p written by part p); ``rec_at`` (T, W) int64: part q's read positions in
    row q; ``part_n`` (T, 8) int64 per-part counts (columns ``PN_*``); ``sync`` (2,)
    int64 the barrier's state (:mod:`etswarm.sim.sync`); ``cstate`` (24,) int64 the
    collision phase's state between passes and the tick loop's flags (``CS_*``);
    ``strips`` (2 P + 1,) int64 slot bounds of the strips; ``strip_out`` (2 P, 5) int64
    per-strip results; ``strip_done`` (2 P * 8,) int64: entry 8 k the number of the
    pass (``CS_PASSNO``) in which strip k was last resolved (one cache line each);
    ``near`` (T, N) uint32, ``near_d2`` (T, N) float64 and ``work`` (T, N) int32
    per-thread scratch of the collision phase (work, near_d2: also of the
    radio); ``robot_flag`` (N,) uint8 flags by robot while the grid is rebuilt;
    ``tx_type`` (N,) uint8 and ``tx_data`` (N, 9) uint8: this tick's messages by
    sender, copied in pass 1 (so a controller part may rewrite ``out_*`` of its robots
    while other threads still file copies). Rows of T or W int64 that different
    threads write start on cache-line boundaries.
    """

    key: np.ndarray
    parts: np.ndarray
    rec_i: np.ndarray
    rec_j: np.ndarray
    rec_d: np.ndarray
    rec_n: np.ndarray
    rec_at: np.ndarray
    part_n: np.ndarray
    sync: np.ndarray
    cstate: np.ndarray
    strips: np.ndarray
    strip_out: np.ndarray
    strip_done: np.ndarray
    near: np.ndarray
    near_d2: np.ndarray
    work: np.ndarray
    robot_flag: np.ndarray
    tx_type: np.ndarray
    tx_data: np.ndarray


def make_scratch(n: int, threads: int, key: int,
                 rx_per_robot: int = 0) -> ThreadScratch:
    """Work arrays for ``n`` robots on ``threads`` threads with hash key ``key``; the
    radio's streams hold ``rx_per_robot`` (default RX_PER_ROBOT) copies per robot of
    the sending part."""
    t = max(int(threads), 1)
    w = 8 * ((t + 7) // 8)
    room = (rx_per_robot or RX_PER_ROBOT) * (n // t + 1)
    return ThreadScratch(
        key=np.array([key], dtype=np.uint64),
        parts=np.array([t], dtype=np.int64),
        rec_i=np.zeros((t, t, room), dtype=np.int32),
        rec_j=np.zeros((t, t, room), dtype=np.int32),
        rec_d=np.zeros((t, t, room), dtype=np.float32),
        rec_n=aligned_rows(t, w, np.int64),
        rec_at=aligned_rows(t, w, np.int64),
        part_n=aligned_rows(t, 8, np.int64),
        sync=np.zeros(2, dtype=np.int64),
        cstate=np.zeros(24, dtype=np.int64),
        strips=np.zeros(2 * STRIP_PAIRS + 1, dtype=np.int64),
        strip_out=np.zeros((2 * STRIP_PAIRS, 5), dtype=np.int64),
        strip_done=aligned_rows(2 * STRIP_PAIRS, 8, np.int64).reshape(-1),
        near=np.zeros((t, n), dtype=np.uint32),
        near_d2=np.zeros((t, n)),
        work=np.zeros((t, n), dtype=np.int32),
        robot_flag=np.zeros(n, dtype=np.uint8),
        tx_type=np.zeros(n, dtype=np.uint8),
        tx_data=np.zeros((n, 9), dtype=np.uint8),
    )


# ---------------------------------------------------------------- counter-based draws


@njit(cache=True, inline="always")
def _mix(z):
    """SplitMix64 finaliser (uint64 -> uint64)."""
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


@njit(cache=True, inline="always")
def hash_unit(key, tick, a, b):
    """Uniform draw in (0, 1] from (key, tick, a, b) (integers >= 0)."""
    h = _mix(key ^ (np.uint64(tick) * _C1))
    h = _mix(h ^ (np.uint64(a) * _C2))
    h = _mix(h ^ (np.uint64(b) * _C3))
    return (np.float64(h >> _S11) + 1.0) * _TO_UNIT


@njit(cache=True, inline="always")
def hash_normal(key, tick, a, b_first, b_second, portable):
    """Standard normal draw (Box-Muller) from two hashed uniforms (``portable``: with
    ``fpmath``'s functions)."""
    u1 = hash_unit(key, tick, a, b_first)
    u2 = hash_unit(key, tick, a, b_second)
    return np.sqrt(-2.0 * log_as(u1, portable)) * sin_cos_as(2.0 * np.pi * u2, portable)[1]


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def hash_draws(key, tick, a, b, count):
    """``count`` uniforms for (key, tick, a + k, b), k < count (for tests)."""
    out = np.empty(count)
    for k in range(count):
        out[k] = hash_unit(key, tick, a + k, b)
    return out


# ---------------------------------------------------------------- grid upkeep


@njit(cache=True)
def rebuild_keeping_flags(grid, pos, present, flags, robot_flag):
    """Rebuild the grid carrying the per-slot work flags ``flags`` to the new slots."""
    n = pos.shape[0]
    for i in range(n):
        s = grid.slot[i]
        robot_flag[i] = flags[s] if s >= 0 else 0
    grid_rebuild(grid, pos, present)
    flags[:] = 0
    for i in range(n):
        s = grid.slot[i]
        if s >= 0:
            flags[s] = robot_flag[i]


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def grid_sync_flags(grid, pos, present, flags, robot_flag):
    """:func:`etswarm.sim.neighbours.grid_sync` for the flag work list: after outside edits
    the grid is rebuilt and the edited robots are flagged (bit 1) with budget 0."""
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
        rebuild_keeping_flags(grid, pos, present, flags, robot_flag)
        for i in range(n):
            if edited[i]:
                s = grid.slot[i]
                grid.sxb[s, P_BUDGET] = 0.0
                flags[s] |= 1


# ---------------------------------------------------------------- radio


@njit(cache=True)
def _in_range(x, y, start, sxb, ox, oy, inv, nx, ny, reach, r2, cand_s, cand_d2):
    """The filed slots within range of (x, y) (squared range ``r2`` mm^2; ``reach``: range
    plus the grid's margin) in slot order into ``cand_s`` (N,) int32 with their squared
    distances in ``cand_d2`` (N,) float64; returns how many."""
    cx0, cx1 = cell_range(x, reach, ox, inv, nx)
    cy0, cy1 = cell_range(y, reach, oy, inv, ny)
    # kept without branching on distances
    n_in = 0
    for cy in range(cy0, cy1 + 1):
        row = cy * nx
        for s in range(np.uint64(start[row + cx0]), np.uint64(start[row + cx1 + 1])):
            dx = sxb[s, P_X] - x
            dy = sxb[s, P_Y] - y
            d2 = dx * dx + dy * dy
            cand_s[n_in] = s
            cand_d2[n_in] = d2
            n_in += d2 <= r2
    return n_in


@njit(cache=True, inline="always")
def _heard(i, j, d2, tick, key, loss, noise, portable):
    """The distance (mm) receiver j measures to sender i at squared distance d2, or -1.0
    when the copy is lost (hashed draws, see module doc)."""
    if loss > 0.0 and hash_unit(key, tick, i, j * 8 + SALT_LOSS) <= loss:
        return -1.0
    d = np.sqrt(d2)
    if noise > 0.0:
        d += noise * hash_normal(key, tick, i, j * 8 + SALT_NOISE_A, j * 8 + SALT_NOISE_B,
                                 portable)
        if d < 0.0:
            d = 0.0
    return d


@njit(cache=True)
def _is_sender(i, phase, tx_phase, out_on, alive, present):
    # one expression of bitwise ands: an ``and`` chain here compiles to code that costs
    # about 18 ns per call (measured), more than the rest of a radio pass per robot
    return (tx_phase[i] == phase) & out_on[i] & alive[i] & present[i]


@njit(cache=True, inline="always")
def _part_of(j, n, parts):
    """The part q whose robots n q / T .. n (q + 1) / T - 1 include robot j."""
    q = j * parts // n
    while q + 1 < parts and j >= n * (q + 1) // parts:
        q += 1
    while q > 0 and j < n * q // parts:
        q -= 1
    return q


@njit(cache=True)
def _radio_one_thread(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                      out_data, in_count, in_type, in_data, in_dist, counters, scr, order,
                      first):
    """The threaded radio's result computed on one thread without the streams' capacity
    (used when a stream would overflow)."""
    cap = in_type.shape[1]
    key = scr.key[0]
    phase = tick % cfg.tx_period
    start, sxb, sidx, slot = grid.start, grid.sxb, grid.sidx, grid.slot
    ox = grid.geom[G_OX]
    oy = grid.geom[G_OY]
    inv = grid.geom[G_INV]
    nx = grid.dims[0]
    ny = grid.dims[1]
    rng_r = cfg.comm_range
    reach = rng_r + grid.geom[G_MARGIN]
    cand_s = scr.work[0]
    cand_d2 = scr.near_d2[0]
    in_count[:] = 0
    sent = 0
    delivered = 0
    lost = 0
    overflow = 0
    for q_send in range(first[phase], first[phase + 1]):
        i = order[q_send]
        if not _is_sender(i, phase, tx_phase, out_on, alive, present):
            continue
        sent += 1
        s = slot[i]
        n_in = _in_range(sxb[s, P_X], sxb[s, P_Y], start, sxb, ox, oy, inv, nx, ny, reach,
                         rng_r * rng_r, cand_s, cand_d2)
        for q in range(n_in):
            j = sidx[cand_s[q]]
            if j == i or not alive[j]:
                continue
            d = _heard(i, j, cand_d2[q], tick, key, cfg.loss, cfg.dist_noise, cfg.portable)
            if d < 0.0:
                lost += 1
                continue
            c = in_count[j]
            if c >= cap:
                overflow += 1
                continue
            in_type[j, c] = out_type[i]
            in_data[j, c, :] = out_data[i, :]
            in_dist[j, c] = np.float32(d)
            in_count[j] = c + 1
            delivered += 1
    counters[0] += sent
    counters[1] += delivered
    counters[2] += lost
    counters[3] += overflow


@njit(cache=True)
def _radio_list(slo, shi, p, tick, cfg, grid, alive, present, tx_phase, out_on, out_type,
                out_data, scr, order, first):
    """Pass 1 for the senders filed in slots slo..shi-1, in index order: copy each
    message and append every copy that is not lost, as (sender, receiver, distance),
    to the stream of the part the receiver belongs to. ``order``, ``first``: the robots
    grouped by phase (``radio.senders_by_phase``), so only this tick's are looked at."""
    n = alive.shape[0]
    parts = scr.parts[0]
    phase = tick % cfg.tx_period
    key = scr.key[0]
    # the grid's and the scratch's arrays in locals: a tuple field read in the loop
    # would cost numba's reference counting an atomic increment and decrement
    start, sxb, sidx, slot = grid.start, grid.sxb, grid.sidx, grid.slot
    ox = grid.geom[G_OX]
    oy = grid.geom[G_OY]
    inv = grid.geom[G_INV]
    nx = grid.dims[0]
    ny = grid.dims[1]
    rng_r = cfg.comm_range
    reach = rng_r + grid.geom[G_MARGIN]
    r2 = rng_r * rng_r
    loss = cfg.loss
    noise = cfg.dist_noise
    tx_type, tx_data = scr.tx_type, scr.tx_data
    rec_i, rec_j, rec_d, rec_n = scr.rec_i[p], scr.rec_j[p], scr.rec_d[p], scr.rec_n[p]
    room = rec_i.shape[1]
    cand_s = scr.work[p]
    cand_d2 = scr.near_d2[p]
    n_bytes = out_data.shape[1]
    for q in range(parts):
        rec_n[q] = 0
    sent = 0
    lost = 0
    bad = 0
    for q_send in range(first[phase], first[phase + 1]):
        i = order[q_send]
        s = slot[i]
        if s < slo or s >= shi or not _is_sender(i, phase, tx_phase, out_on, alive, present):
            continue
        sent += 1
        tx_type[i] = out_type[i]
        for b in range(n_bytes):
            tx_data[i, b] = out_data[i, b]
        n_in = _in_range(sxb[s, P_X], sxb[s, P_Y], start, sxb, ox, oy, inv, nx, ny, reach,
                         r2, cand_s, cand_d2)
        for c in range(n_in):
            j = sidx[cand_s[c]]
            if j == i or not alive[j]:
                continue
            d = _heard(i, j, cand_d2[c], tick, key, loss, noise, cfg.portable)
            if d < 0.0:
                lost += 1
                continue
            q = _part_of(j, n, parts)
            k = rec_n[q]
            if k >= room:
                bad = 1
                continue
            rec_i[q, k] = i
            rec_j[q, k] = j
            rec_d[q, k] = d
            rec_n[q] = k + 1
    scr.part_n[p, PN_SENT] = sent
    scr.part_n[p, PN_LOST] = lost
    scr.part_n[p, PN_BAD] = bad


@njit(cache=True)
def _radio_file(lo, hi, q, in_count, in_type, in_data, in_dist, scr):
    """Pass 2 for receivers lo..hi-1 (part q): file the copies of every part's stream to
    part q, merged into sender order (each stream is in sender order), with the
    messages as pass 1 copied them."""
    parts = scr.parts[0]
    cap = in_type.shape[1]
    rec_i, rec_j, rec_d, rec_n = scr.rec_i, scr.rec_j, scr.rec_d, scr.rec_n
    tx_type, tx_data, part_n = scr.tx_type, scr.tx_data, scr.part_n
    at = scr.rec_at[q]
    n_bytes = tx_data.shape[1]
    in_count[lo:hi] = 0
    for p in range(parts):
        at[p] = 0
    delivered = 0
    overflow = 0
    while True:
        # the stream whose next copy has the lowest sender
        src = -1
        first = np.int64(0)
        for p in range(parts):
            k = at[p]
            if k < rec_n[p, q] and (src < 0 or rec_i[p, q, k] < first):
                src = p
                first = rec_i[p, q, k]
        if src < 0:
            break
        # that sender's copies (together in its stream)
        k = at[src]
        end = rec_n[src, q]
        mtype = tx_type[first]
        while k < end and rec_i[src, q, k] == first:
            if k + PREFETCH_AHEAD < end:
                # the inbox rows of a copy a few places ahead (scattered)
                ahead = rec_j[src, q, k + PREFETCH_AHEAD]
                prefetch(in_count, ahead)
                prefetch(in_type, ahead)
                prefetch(in_data, ahead)
                prefetch(in_dist, ahead)
            j = rec_j[src, q, k]
            k += 1
            c = in_count[j]
            if c >= cap:
                overflow += 1
                continue
            in_type[j, c] = mtype
            if n_bytes == PAYLOAD_BYTES:  # a constant count: one unrolled copy
                for b in range(PAYLOAD_BYTES):
                    in_data[j, c, b] = tx_data[first, b]
            else:
                for b in range(n_bytes):
                    in_data[j, c, b] = tx_data[first, b]
            in_dist[j, c] = rec_d[src, q, k - 1]
            in_count[j] = c + 1
            delivered += 1
        at[src] = k
    part_n[q, PN_DELIVERED] = delivered
    part_n[q, PN_OVERFLOW] = overflow


@njit(cache=True)
def radio_bad(scr):
    """True when a stream of this tick ran out of room (the one-thread radio files it)."""
    bad = 0
    for p in range(scr.parts[0]):
        bad += scr.part_n[p, PN_BAD]
    return bad > 0


@njit(cache=True)
def radio_file_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, in_count, in_type, in_data, in_dist, counters, scr, order,
                    first):
    """Pass 2 of part ``p`` (receivers n p / T .. n (p + 1) / T - 1) after every part's
    pass 1; if a stream overflowed, part 0 runs the whole tick's radio on its own
    instead (and counts it)."""
    n = pos.shape[0]
    parts = scr.parts[0]
    if radio_bad(scr):
        if p == 0:
            _radio_one_thread(tick, cfg, grid, pos, alive, present, tx_phase, out_on,
                              out_type, out_data, in_count, in_type, in_data, in_dist,
                              counters, scr, order, first)
        return
    _radio_file(n * p // parts, n * (p + 1) // parts, p, in_count, in_type, in_data,
                in_dist, scr)


@njit(cache=True)
def radio_count(counters, scr):
    """Add the tick's radio counts of all parts to ``counters`` (unless the one-thread
    radio ran and counted)."""
    if radio_bad(scr):
        return
    for p in range(scr.parts[0]):
        counters[0] += scr.part_n[p, PN_SENT]
        counters[1] += scr.part_n[p, PN_DELIVERED]
        counters[2] += scr.part_n[p, PN_LOST]
        counters[3] += scr.part_n[p, PN_OVERFLOW]


@njit(cache=True)
def radio_list_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, scr, order, first):
    """Pass 1 of part ``p``: the senders filed in slots n p / T .. n (p + 1) / T - 1 of
    the n filed robots (by place, as :func:`move_part`); ``order``, ``first``:
    ``radio.senders_by_phase`` of ``tx_phase``."""
    n_filed = grid.start[grid.dims[0] * grid.dims[1]]
    parts = scr.parts[0]
    _radio_list(n_filed * p // parts, n_filed * (p + 1) // parts, p, tick, cfg, grid,
                alive, present, tx_phase, out_on, out_type, out_data, scr, order, first)


@njit(cache=True)
def radio_phase_mt(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                   out_data, in_count, in_type, in_data, in_dist, counters, scr):
    """The threaded radio phase run part after part on the calling thread (arrays as in
    World; see module doc): what the threaded loop's threads do, in one call."""
    parts = scr.parts[0]
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    for p in range(parts):
        radio_list_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                        out_data, scr, order, first)
    for q in range(parts):
        radio_file_part(q, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                        out_data, in_count, in_type, in_data, in_dist, counters, scr, order,
                        first)
    radio_count(counters, scr)


# ---------------------------------------------------------------- motion


@njit(cache=True)
def _move_part(lo, hi, tick, cfg, grid, pos, heading, motor, alive, present, speed,
               turn_rate, flags, trig, key, out, at, at_drift):
    """Move the robots in grid slots lo..hi-1 (the serial move's arithmetic; robots that
    are not present have no slot); ``out[at]`` = 1 if one left its slack box, else 0;
    ``out[at_drift]`` = 1 if one drifted (contact lists void)."""
    dt = cfg.dt
    r = cfg.radius
    leg = cfg.leg_angle
    sin_leg, cos_leg = sin_cos_as(leg, cfg.portable)
    walls = cfg.arena > 0.0
    two_pi = 2.0 * np.pi
    sxb, sref = grid.sxb, grid.sref
    span = grid.geom[G_CELL] + 2.0 * grid.geom[G_MARGIN]
    drift2 = grid.geom[G_DRIFT] * grid.geom[G_DRIFT]
    sidx = grid.sidx
    trig_end = trig[:, 5]  # a row of trig may straddle two cache lines
    stale = False
    drift = False
    for s in range(lo, hi):
        i = sidx[s]
        if s + PREFETCH_AHEAD < hi:
            # the robot a few slots ahead: its rows by index lie scattered
            ahead = sidx[s + PREFETCH_AHEAD]
            prefetch(pos, ahead)
            prefetch(trig, ahead)
            prefetch(trig_end, ahead)
            prefetch(heading, ahead)
            prefetch(speed, ahead)
            prefetch(turn_rate, ahead)
            prefetch(motor, ahead)
        m = motor[i]
        if m == 0 or not alive[i]:
            continue
        h = heading[i]
        if trig[i, 0] != h:
            trig[i, 0] = h
            trig[i, 2], trig[i, 1] = sin_cos_as(h, cfg.portable)
        ch = trig[i, 1]
        sh = trig[i, 2]
        # forward and turning are both computed and one is selected (which one is
        # random per robot: a branch on it is mispredicted often); the values are the
        # same as if only the chosen one were computed
        fwd = m == 1
        step = speed[i] * dt
        if fwd and cfg.speed_noise > 0.0:
            step *= 1.0 + cfg.speed_noise * hash_normal(key, tick, i, SALT_SPEED_A,
                                                        SALT_SPEED_B, cfg.portable)
        rate = turn_rate[i]
        if trig[i, 3] != rate:
            trig[i, 3] = rate
            trig[i, 5], trig[i, 4] = sin_cos_as(rate * dt, cfg.portable)
        cw = m == 3  # clockwise about the right leg, else counter-clockwise about the left
        cd = trig[i, 4]
        sd = -trig[i, 5] if cw else trig[i, 5]
        dth = -(rate * dt) if cw else rate * dt
        sl = -sin_leg if cw else sin_leg
        # leg direction a = heading +- leg_angle; the centre rotates by dth about
        # the leg at pos + r*(cos a, sin a): new centre = leg - r*(cos(a+dth), ...)
        ca = ch * cos_leg - sh * sl
        sa = sh * cos_leg + ch * sl
        ca2 = ca * cd - sa * sd
        sa2 = sa * cd + ca * sd
        px = pos[i, 0]
        py = pos[i, 1]
        x = px + step * ch if fwd else px + r * (ca - ca2)
        y = py + step * sh if fwd else py + r * (sa - sa2)
        h_new = h if fwd else h + dth
        travel = abs(step) if fwd else r * abs(dth)  # turning: arc length >= chord
        ch_t = ch * cd - sh * sd
        sh_t = sh * cd + ch * sd
        ch = ch if fwd else ch_t
        sh = sh if fwd else sh_t
        if cfg.heading_noise > 0.0:
            h_new += cfg.heading_noise * hash_normal(key, tick, i, SALT_HEAD_A, SALT_HEAD_B,
                                                      cfg.portable)
            sh, ch = sin_cos_as(h_new, cfg.portable)
        if h_new > np.pi:
            h_new -= two_pi
        elif h_new <= -np.pi:
            h_new += two_pi
        if walls:
            x = clamp_to_arena(x, r, cfg.arena)
            y = clamp_to_arena(y, r, cfg.arena)
        pos[i, 0] = x
        pos[i, 1] = y
        heading[i] = h_new
        trig[i, 0] = h_new
        trig[i, 1] = ch
        trig[i, 2] = sh
        sxb[s, P_X] = x
        sxb[s, P_Y] = y
        bx = sref[s, R_BX]
        by = sref[s, R_BY]
        if x < bx or x >= bx + span or y < by or y >= by + span:
            stale = True
        drift |= drifted(sref, s, x, y, drift2)
        b = sxb[s, P_BUDGET] - travel
        sxb[s, P_BUDGET] = b
        if b <= 0.0:
            flags[s] |= 1
    out[at] = 1 if stale else 0
    out[at_drift] = 1 if drift else 0


@njit(cache=True)
def move_part(p, tick, cfg, grid, pos, heading, motor, alive, present, speed, turn_rate,
              flags, trig, scr):
    """Move the robots in slots n p / T .. n (p + 1) / T - 1 of the n filed ones (by
    slot, so that a thread moves the robots of the strips it resolves first in the
    collision phase: see :func:`collide_pass_grab`); part_n[p, PN_STALE] = left a box."""
    n = grid.start[grid.dims[0] * grid.dims[1]]
    parts = scr.parts[0]
    _move_part(n * p // parts, n * (p + 1) // parts, tick, cfg, grid, pos, heading, motor,
               alive, present, speed, turn_rate, flags, trig, scr.key[0], scr.part_n[p],
               PN_STALE, PN_DRIFT)


@njit(cache=True)
def move_finish(grid, pos, present, flags, scr):
    """After every part moved: rebuild the grid if a robot left its slack box (or mark
    the contact lists void if one drifted)."""
    stale = False
    for p in range(scr.parts[0]):
        stale |= scr.part_n[p, PN_STALE] != 0
        if scr.part_n[p, PN_DRIFT] != 0:
            grid.state[S_DRIFTED] = 1
    if stale:
        rebuild_keeping_flags(grid, pos, present, flags, scr.robot_flag)


@njit(cache=True)
def move_phase_mt(tick, cfg, grid, pos, heading, motor, alive, present, speed, turn_rate,
                  flags, trig, scr):
    """The threaded move phase run part after part on the calling thread; robots whose
    budget ran out get flag bit 1 (``flags`` by slot)."""
    for p in range(scr.parts[0]):
        move_part(p, tick, cfg, grid, pos, heading, motor, alive, present, speed, turn_rate,
                  flags, trig, scr)
    move_finish(grid, pos, present, flags, scr)


# ---------------------------------------------------------------- collisions


@njit(cache=True)
def strip_bounds(grid, strips):
    """Cut the grid's rows into strips of >= 2 rows with about equal robot counts; write
    their slot bounds to ``strips`` and return how many (<= 2 * STRIP_PAIRS)."""
    nx = grid.dims[0]
    ny = grid.dims[1]
    start = grid.start
    total = start[nx * ny]
    n_strips = min(2 * STRIP_PAIRS, ny // 2)
    if n_strips < 1:
        n_strips = 1
    strips[0] = 0
    prev = 0
    for k in range(1, n_strips):
        target = total * k / n_strips
        row = prev + 2
        last = ny - 2 * (n_strips - k)
        while row < last and start[row * nx] < target:
            row += 1
        strips[k] = start[row * nx]
        prev = row
    strips[n_strips] = total
    return n_strips


@njit(cache=True, inline="always")
def _collide_strip(lo, hi, cur_bit, nxt_bit, lists_ok, cfg, grid, pos, motor, flags, near,
                   near_d2, work, out):
    """One pass over the slots lo..hi-1 of a strip (see module doc); writes examined,
    pushes, newly flagged slots, a stale flag and a drift flag to ``out`` (5,).

    Contact lists (see :mod:`etswarm.sim.neighbours`) are used while ``lists_ok`` and no
    robot this strip moved has drifted; a list is built from the robot's own cell row
    and the rows next to it only (no other strip writes there during the pass, and a
    robot two rows away cannot come within contact + margin without leaving its slack
    box, which sends the pass's robots through a rebuild)."""
    r = cfg.radius
    still_share = cfg.still_share
    contact = 2.0 * r
    resolve2 = (contact - cfg.slop) * (contact - cfg.slop)
    walls = cfg.arena > 0.0
    arena = cfg.arena
    start, sxb, sidx, sref = grid.start, grid.sxb, grid.sidx, grid.sref
    margin = grid.geom[G_MARGIN]
    reach = contact + 2.0 * margin
    near2 = (contact + margin) * (contact + margin)
    half_margin = 0.5 * margin
    contact2 = contact * contact
    share_k = 0.5 / (2.0 * contact + margin)
    span = grid.geom[G_CELL] + 2.0 * grid.geom[G_MARGIN]
    inv = grid.geom[G_INV]
    ox = grid.geom[G_OX]
    oy = grid.geom[G_OY]
    nx = grid.dims[0]
    ny = grid.dims[1]
    near_r = contact + margin
    drift2 = grid.geom[G_DRIFT] * grid.geom[G_DRIFT]
    epoch = grid.state[S_EPOCH]
    near_slots = grid.near_slots
    epoch32 = np.int32(epoch)
    list_r2, list_reach_mm = list_reach(grid, near_r)
    drift = False
    examined = 0
    pushes = 0
    n_next = 0
    stale = False
    # the strip's flagged slots in slot order, gathered without branching on the flags
    # (only this strip examines or flags them while it runs)
    n_work = 0
    for a in range(lo, hi):
        work[n_work] = a
        n_work += (flags[a] & cur_bit) != 0
    for w in range(n_work):
        a = work[w]
        f = flags[a] & ~cur_bit
        xi = sxb[a, P_X]
        yi = sxb[a, P_Y]
        abx = sref[a, R_BX]
        aby = sref[a, R_BY]
        if xi < abx or xi >= abx + span or yi < aby or yi >= aby + span:
            # pushed out of its slack box earlier in this pass: its query could reach
            # beyond the rows next to its own; examine it after the rebuild
            stale = True
            if f & nxt_bit == 0:
                n_next += 1
            flags[a] = f | nxt_bit
            continue
        flags[a] = f
        examined += 1
        moved_i = False
        own = half_margin
        n_list = -1
        if lists_ok and not drift:
            if near_slots[a, L_EPOCH] != epoch32:
                row_a = np.int64((sref[a, R_BY] + margin - oy) * inv + 0.5)
                contact_list_from(start, sxb, near_slots, a, xi, yi, list_r2, list_reach_mm,
                                  ox, oy, inv, nx, ny, row_a - 1, row_a + 1, epoch, near)
            n_list = near_slots[a, L_COUNT]
        still_a = motor[sidx[a]] == 0
        if n_list >= 0:
            # the listed slots in one loop, as in etswarm.sim.collide.collide_phase:
            # budgets and the pairs to push from the position at the examination's start
            x0 = xi
            y0 = yi
            for q in range(L_FIRST, L_FIRST + n_list):
                s = np.uint32(near_slots[a, q])
                xs = sxb[s, P_X]
                ys = sxb[s, P_Y]
                dx = xs - x0
                dy = ys - y0
                d2 = dx * dx + dy * dy
                within = np.float64(d2 < near2)
                share = (within * max((d2 - contact2) * share_k, 0.0)
                         + (1.0 - within) * half_margin)
                own = min(own, share)
                sxb[s, P_BUDGET] = min(sxb[s, P_BUDGET], share)
                if d2 >= resolve2:
                    continue
                dx = xs - xi
                dy = ys - yi
                d2 = dx * dx + dy * dy
                if d2 >= resolve2:
                    continue
                j = sidx[s]
                xi, yi, xj, yj = push_apart(a, s, dx, dy, d2, xi, yi, xs, ys, still_a,
                                            motor[j] == 0, contact, still_share, r, walls,
                                            arena)
                far, left_box = place_pushed(s, j, xj, yj, sxb, sref, pos, drift2, span)
                drift |= far
                stale = stale or left_box
                fs = flags[s]
                n_next += (fs & nxt_bit) == 0
                flags[s] = fs | nxt_bit
                moved_i = True
                pushes += 1
        else:
            n_over, own = gather_overlaps(a, xi, yi, own, reach, near2, contact2, share_k,
                                          resolve2, ox, oy, inv, nx, ny, start, sxb,
                                          near, near_d2)
            for q in range(n_over):
                s = near[q]
                xs = sxb[s, P_X]
                ys = sxb[s, P_Y]
                dx = xs - xi
                dy = ys - yi
                d2 = dx * dx + dy * dy
                if d2 >= resolve2:
                    continue
                j = sidx[s]
                xi, yi, xj, yj = push_apart(a, s, dx, dy, d2, xi, yi, xs, ys, still_a,
                                            motor[j] == 0, contact, still_share, r, walls,
                                            arena)
                far, left_box = place_pushed(s, j, xj, yj, sxb, sref, pos, drift2, span)
                drift |= far
                stale = stale or left_box
                fs = flags[s]
                n_next += (fs & nxt_bit) == 0
                flags[s] = fs | nxt_bit
                moved_i = True
                pushes += 1
        if not moved_i:
            sxb[a, P_BUDGET] = own
        else:
            i = sidx[a]
            sxb[a, P_BUDGET] = 0.0
            sxb[a, P_X] = xi
            sxb[a, P_Y] = yi
            pos[i, 0] = xi
            pos[i, 1] = yi
            drift |= drifted(sref, a, xi, yi, drift2)
            if xi < abx or xi >= abx + span or yi < aby or yi >= aby + span:
                stale = True
            fa = flags[a]
            n_next += (fa & nxt_bit) == 0
            flags[a] = fa | nxt_bit
    out[SO_EXAMINED] = examined
    out[SO_PUSHES] = pushes
    out[SO_FLAGGED] = n_next
    out[SO_STALE] = stale
    out[SO_DRIFT] = drift


@njit(cache=True)
def collide_begin(grid, scr):
    """Start a tick's collision phase (one thread, after the move)."""
    cs = scr.cstate
    cs[CS_CUR] = 1
    cs[CS_PASSES] = 0
    cs[CS_PUSHES] = 0
    cs[CS_EXAMINED] = 0
    cs[CS_PENDING] = 0
    cs[CS_CONT] = 1
    cs[CS_STALE] = 0
    cs[CS_STRIPS] = strip_bounds(grid, scr.strips)
    cs[CS_GRAB0] = 0
    cs[CS_GRAB1] = 0
    cs[CS_FRONT0:CS_BACK1 + 1] = 0
    cs[CS_PASSNO] += 1
    if grid.state[S_DRIFTED] != 0:
        new_epoch(grid)


@njit(cache=True, inline="always")
def _lists_ok(k, n_strips, strip_out):
    """Contact lists are good for strip ``k`` in this pass: the epoch began before the
    pass (so nobody had drifted before it), and for a colour-1 strip neither colour-0
    strip next to it drifted a robot in this pass (only those two can move robots that
    the strip's lists hold: see :func:`_collide_strip`). Lists are a cache: results do
    not depend on whether they are used."""
    if k % 2 == 0:
        return True
    drifts = strip_out[k - 1, SO_DRIFT]
    if k + 1 < n_strips:
        drifts += strip_out[k + 1, SO_DRIFT]
    return drifts == 0


@njit(cache=True)
def collide_strips(p, parts, colour, cfg, grid, pos, motor, flags, scr):
    """Thread ``p`` of ``parts`` resolves strips ``p``, ``p + parts``, ... of ``colour``."""
    cs = scr.cstate
    n_strips = cs[CS_STRIPS]
    cur_bit = cs[CS_CUR]
    n_col = (n_strips + 1 - colour) // 2
    for q in range(p, n_col, parts):
        k = 2 * q + colour
        ok = _lists_ok(k, n_strips, scr.strip_out)
        _collide_strip(scr.strips[k], scr.strips[k + 1], cur_bit, 3 - cur_bit, ok, cfg, grid,
                       pos, motor, flags, scr.near[p], scr.near_d2[p], scr.work[p],
                       scr.strip_out[k])


@njit(cache=True, inline="always")
def _claim_strip(cs, colour, n_col, from_back, alone, mine):
    """The next unclaimed strip of ``colour`` (0 .. n_col - 1) counted from the front or
    the back, or -1 when all are claimed: every strip is claimed exactly once, the
    front claims 0, 1, ... and the back claims n_col - 1, n_col - 2, ... ``alone``:
    this thread is the only one claiming from its end (two threads), so ``mine`` (how
    many it claimed before) counts that end and no shared counter of the end is needed
    (one atomic step a claim instead of two)."""
    if atomic_add(cs, CS_GRAB0 + colour, 1) >= n_col:
        return -1
    if alone:
        at = mine
    elif from_back:
        at = atomic_add(cs, CS_BACK0 + colour, 1)
    else:
        at = atomic_add(cs, CS_FRONT0 + colour, 1)
    return n_col - 1 - at if from_back else at


@njit(cache=True)
def collide_pass_grab(p, cfg, grid, pos, motor, flags, scr):
    """Thread ``p``'s share of a collision pass: strips of colour 0, then of colour 1,
    taken one at a time until none is left (the threads that finish first take more).
    The first half of the threads take strips from the front, the others from the
    back, so a thread mostly resolves the strips whose robots it moved
    (:func:`move_part`) and their data stays in its core's cache. A colour-1 strip
    starts as soon as the two colour-0 strips next to it are done (the only ones whose
    rows it touches), not when all are: no barrier between the colours."""
    cs = scr.cstate
    n_strips = cs[CS_STRIPS]
    cur_bit = cs[CS_CUR]
    passno = cs[CS_PASSNO]
    from_back = 2 * p >= scr.parts[0]
    near, near_d2, work, strips, strip_out = scr.near[p], scr.near_d2[p], scr.work[p], \
        scr.strips, scr.strip_out
    done = scr.strip_done
    alone = scr.parts[0] == 2
    for colour in range(2):
        n_col = (n_strips + 1 - colour) // 2
        mine = 0
        q = _claim_strip(cs, colour, n_col, from_back, alone, mine)
        while q >= 0:
            mine += 1
            k = 2 * q + colour
            if colour == 1:
                wait_for(done, 8 * (k - 1), passno)
                if k + 1 < n_strips:
                    wait_for(done, 8 * (k + 1), passno)
            _collide_strip(strips[k], strips[k + 1], cur_bit, 3 - cur_bit,
                           _lists_ok(k, n_strips, strip_out), cfg, grid, pos, motor,
                           flags, near, near_d2, work, strip_out[k])
            atomic_store(done, 8 * k, passno)
            q = _claim_strip(cs, colour, n_col, from_back, alone, mine)


@njit(cache=True)
def collide_after_pass(cfg, grid, pos, present, flags, scr):
    """Sum a pass's strips and decide whether another pass runs (one thread); before
    it, rebuild the grid if a robot left its slack box and cut new strips."""
    cs = scr.cstate
    out = scr.strip_out
    ex = 0
    pu = 0
    nn = 0
    for k in range(cs[CS_STRIPS]):
        ex += out[k, SO_EXAMINED]
        pu += out[k, SO_PUSHES]
        nn += out[k, SO_FLAGGED]
        if out[k, SO_STALE] != 0:
            cs[CS_STALE] = 1
        if out[k, SO_DRIFT] != 0:
            grid.state[S_DRIFTED] = 1
    if ex == 0 and nn == 0:
        cs[CS_PENDING] = 0
        cs[CS_CONT] = 0
        return
    cs[CS_EXAMINED] += ex
    cs[CS_PUSHES] += pu
    cs[CS_PASSES] += 1
    cs[CS_CUR] = 3 - cs[CS_CUR]
    cs[CS_PENDING] = 1 if nn > 0 else 0
    cs[CS_CONT] = 1 if nn > 0 and cs[CS_PASSES] < cfg.max_passes else 0
    if cs[CS_CONT] != 0:
        if cs[CS_STALE] != 0:
            rebuild_keeping_flags(grid, pos, present, flags, scr.robot_flag)
            cs[CS_STALE] = 0
        elif grid.state[S_DRIFTED] != 0:
            new_epoch(grid)
        cs[CS_STRIPS] = strip_bounds(grid, scr.strips)
        cs[CS_GRAB0] = 0
        cs[CS_GRAB1] = 0
        cs[CS_FRONT0:CS_BACK1 + 1] = 0
        cs[CS_PASSNO] += 1


@njit(cache=True)
def collide_end(grid, pos, present, flags, counters, scr):
    """Finish a tick's collision phase (one thread): robots left over by the pass limit
    keep flag bit 1, the grid is valid, counters are updated."""
    cs = scr.cstate
    if cs[CS_PENDING] != 0:
        counters[5] += 1
        if cs[CS_CUR] == 2:
            for s in range(flags.shape[0]):
                flags[s] = flags[s] >> 1
    if cs[CS_STALE] != 0:
        rebuild_keeping_flags(grid, pos, present, flags, scr.robot_flag)
        cs[CS_STALE] = 0
    elif grid.state[S_DRIFTED] != 0:
        new_epoch(grid)  # now, so that lists can be built during the control phase
    counters[4] += cs[CS_PUSHES]
    counters[6] += cs[CS_EXAMINED]


# ---------------------------------------------------------------- control phase


@njit(cache=True)
def no_part_step(lo, hi, tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                 out_on, out_type, out_data, mem):
    """The ``part_step`` of a controller that has none: all its work is in ``step``."""
    return


@njit(cache=True, inline="always")
def part_bounds(p, n, scr):
    """Robots ``lo .. hi - 1`` of part ``p`` (by index: the radio's receivers and the
    controller part's robots)."""
    parts = scr.parts[0]
    return n * p // parts, n * (p + 1) // parts


@njit(cache=True)
def control_begin(scr):
    """Before the controller runs on one thread (called by that thread before it lets
    the others go on to :func:`prebuild_lists`)."""
    scr.cstate[CS_CTL] = 0
    scr.cstate[CS_BUILD] = 0


@njit(cache=True)
def control_done(scr):
    """The controller has returned: threads in :func:`prebuild_lists` stop."""
    atomic_add(scr.cstate, CS_CTL, 1)


@njit(cache=True)
def prebuild_lists(p, cfg, grid, scr):
    """While one thread runs the controller (which moves nobody), the others build the
    contact lists the collision phase would build when it first examines each robot
    (see :mod:`etswarm.sim.neighbours`), taking PREBUILD_CHUNK slots at a time until
    the controller returns. Lists are a cache: results do not depend on how many get
    built here."""
    cs = scr.cstate
    if grid.state[S_DRIFTED] != 0:
        return
    epoch = grid.state[S_EPOCH]
    epoch32 = np.int32(epoch)
    n_filed = grid.start[grid.dims[0] * grid.dims[1]]
    margin = grid.geom[G_MARGIN]
    near_r = 2.0 * cfg.radius + margin
    oy = grid.geom[G_OY]
    inv = grid.geom[G_INV]
    sxb, sref, start, near_slots = grid.sxb, grid.sref, grid.start, grid.near_slots
    list_r2, list_reach_mm = list_reach(grid, near_r)
    ox = grid.geom[G_OX]
    nx = grid.dims[0]
    ny = grid.dims[1]
    buf = scr.near[p]
    while atomic_load(cs, CS_CTL) == 0:
        first = atomic_add(cs, CS_BUILD, PREBUILD_CHUNK)
        if first >= n_filed:
            return
        for a in range(first, min(first + PREBUILD_CHUNK, n_filed)):
            if near_slots[a, L_EPOCH] != epoch32:
                # the rows next to its own only, as in the collision strips
                row_a = np.int64((sref[a, R_BY] + margin - oy) * inv + 0.5)
                contact_list_from(start, sxb, near_slots, a, sxb[a, P_X], sxb[a, P_Y],
                                  list_r2, list_reach_mm, ox, oy, inv, nx, ny, row_a - 1,
                                  row_a + 1, epoch, buf)


@njit(cache=True)
def collide_phase_mt(cfg, grid, pos, present, motor, flags, counters, scr):
    """The threaded collision phase run part after part on the calling thread (see module
    doc).

    ``flags`` (N,) uint8 by slot: bit 1 marks the robots to examine; on return only
    robots left over by the pass limit are flagged (bit 1) and the grid is valid.
    """
    parts = scr.parts[0]
    collide_begin(grid, scr)
    while scr.cstate[CS_CONT] != 0:
        for p in range(parts):
            collide_strips(p, parts, 0, cfg, grid, pos, motor, flags, scr)
        for q in range(parts):
            collide_strips(q, parts, 1, cfg, grid, pos, motor, flags, scr)
        collide_after_pass(cfg, grid, pos, present, flags, scr)
    collide_end(grid, pos, present, flags, counters, scr)
