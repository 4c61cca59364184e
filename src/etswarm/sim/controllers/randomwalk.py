"""Example fast-path controller: a random walk that keeps a neighbour table.

Every robot picks a move (forward 50 %, turn left 25 %, turn right 25 %) and keeps it for
16..79 ticks (uniform), then picks again. It broadcasts message type 1 with payload
``[id low byte, id high byte, neighbour count, 0, ...]`` and keeps a table of the robots
it heard: each entry holds an ID and the tick it was last heard, and expires 64 ticks
after that. The neighbour count is the number of unexpired entries; it is refreshed
every 8 ticks (staggered by ID) and shown on the LED.

``mem`` layout (tuple of arrays, N robots, T table slots):
    0 stop      (1,) int64     reserved stop flag (never set by this controller)
    1 next_move (N,) int64     tick at which the robot picks its next move
    2 nb_id     (N, T) int32   neighbour IDs, -1 = empty slot
    3 nb_seen   (N, T) int32   tick each neighbour was last heard (fits 2 years of ticks)
    4 nb_count  (N,) int64     unexpired entries at the last refresh
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.prefetch import prefetch

#: Message type of random-walk broadcasts.
MSG_HELLO = 1
#: Ticks after which a neighbour-table entry expires.
EXPIRE_TICKS = 64
#: Neighbour-table slots per robot.
TABLE_SLOTS = 16
#: Robots ahead whose table and inbox rows a control step asks the cache for.
PREFETCH_AHEAD = 4


@njit(cache=True)
def randomwalk_part(lo, hi, tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                    out_on, out_type, out_data, mem):
    """The per-robot work of a control tick for robots ``lo .. hi - 1`` (no random draws):
    hear (refresh or add neighbour-table entries) and, every 8 ticks, refresh the
    neighbour count and the outgoing message. Touches only those robots' rows, so parts
    may run on different threads at once (the ``part_step`` of the controller protocol)."""
    nb_id = mem[2]
    nb_seen = mem[3]
    nb_count = mem[4]
    slots = nb_id.shape[1]
    for i in range(lo, hi):
        if i + PREFETCH_AHEAD < hi:
            # rows of a robot a few places ahead (read only if it heard or refreshes)
            ahead = i + PREFETCH_AHEAD
            prefetch(nb_id, ahead)
            prefetch(nb_seen, ahead)
            prefetch(in_type, ahead)
            prefetch(in_data, ahead)
        if not alive[i]:
            continue
        # hear: refresh or add table entries
        for k in range(in_count[i]):
            if in_type[i, k] != MSG_HELLO:
                continue
            sender = np.int32(in_data[i, k, 0]) | (np.int32(in_data[i, k, 1]) << 8)
            # the entry holding the sender: a scan without early exit (no branch to
            # mispredict; IDs are unique in a table, so the match is the first one)
            hit = np.int32(slots)
            for s in range(slots):
                hit = min(hit, np.int32(s) if nb_id[i, s] == sender else np.int32(slots))
            if hit < slots:
                nb_seen[i, hit] = tick
                continue
            # not in the table: the first free or expired entry, else the oldest
            free = -1
            oldest = 0
            for s in range(slots):
                if nb_id[i, s] < 0 or tick - nb_seen[i, s] > EXPIRE_TICKS:
                    if free < 0:
                        free = s
                elif nb_seen[i, s] < nb_seen[i, oldest]:
                    oldest = s
            s = free if free >= 0 else oldest
            nb_id[i, s] = sender
            nb_seen[i, s] = tick
        # refresh the neighbour count and the outgoing message every 8 ticks
        if (tick + i) & 7 == 0 or not out_on[i]:
            count = 0
            for s in range(slots):
                if nb_id[i, s] >= 0 and tick - nb_seen[i, s] <= EXPIRE_TICKS:
                    count += 1
            nb_count[i] = count
            out_type[i] = MSG_HELLO
            out_data[i, 0] = i & 0xFF
            out_data[i, 1] = (i >> 8) & 0xFF
            out_data[i, 2] = min(count, 255)
            out_on[i] = True
            led[i] = min(count, 255)


@njit(cache=True)
def randomwalk_rest(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on,
                    out_type, out_data, mem, rng):
    """The rest of a control tick after :func:`randomwalk_part` ran for every robot: a new
    random move every 16..79 ticks, drawn in robot order (one thread)."""
    next_move = mem[1]
    for i in range(alive.shape[0]):
        if tick >= next_move[i] and alive[i]:
            u = rng.random()
            if u < 0.5:
                motor[i] = 1
            elif u < 0.75:
                motor[i] = 2
            else:
                motor[i] = 3
            next_move[i] = tick + 16 + np.int64(rng.random() * 64.0)


@njit(cache=True)
def randomwalk_step(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on,
                    out_type, out_data, mem, rng):
    """One control tick for all robots (signature: the fast-path controller contract):
    :func:`randomwalk_part` over all robots, then :func:`randomwalk_rest` (the moves draw
    from ``rng`` in robot order either way, so splitting changes no result)."""
    randomwalk_part(0, alive.shape[0], tick, alive, in_count, in_type, in_data, in_dist,
                    motor, led, out_on, out_type, out_data, mem)
    randomwalk_rest(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on,
                    out_type, out_data, mem, rng)


class RandomWalk:
    """The random-walk controller for ``n`` robots (fast path: ``step`` + ``mem``)."""

    name = "randomwalk"

    def __init__(self, n: int) -> None:
        self.step = randomwalk_step
        self.part_step = randomwalk_part
        self.rest_step = randomwalk_rest
        if n > 65536:
            raise ValueError("the random walk encodes IDs in 2 bytes: at most 65536 robots")
        self.mem = (
            np.zeros(1, dtype=np.int64),
            np.zeros(n, dtype=np.int64),
            np.full((n, TABLE_SLOTS), -1, dtype=np.int32),
            np.zeros((n, TABLE_SLOTS), dtype=np.int32),
            np.zeros(n, dtype=np.int64),
        )

    def neighbour_count(self) -> np.ndarray:
        """(N,) int64 unexpired neighbour-table entries at each robot's last refresh."""
        return self.mem[4]
