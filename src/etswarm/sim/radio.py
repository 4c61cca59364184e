"""Phase 1 of a tick: the infrared radio.

Inboxes are cleared, then every robot that is present, alive, has ``out_on`` set and whose
broadcast phase comes up this tick (``tick % tx_period == tx_phase``) sends its current
``out_type``/``out_data``. Every other present, alive robot whose centre lies within
``comm_range`` receives a copy unless it is lost (independent probability ``loss`` per
receiver); the copy carries the centre distance plus N(0, dist_noise) noise, clipped at 0
(with ``portable_math`` drawn by ``fpmath.normal``, the same bits on every machine). A
full inbox
(K messages) drops further copies and counts them. Senders are handled in index order, so
inbox order is sender order; receivers of one sender come in cell-list order (their inbox
rows, scattered in memory, are prefetched first).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.fpmath import normal_as
from etswarm.sim.neighbours import G_INV, G_MARGIN, G_OX, G_OY, P_X, P_Y, cell_range
from etswarm.sim.prefetch import prefetch
from etswarm.sim.world import PAYLOAD_BYTES


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def senders_by_phase(tx_phase, tx_period):
    """The robots grouped by broadcast phase: robots ``order[first[s]:first[s + 1]]``, in
    index order, have ``tx_phase`` s (``order`` (N,) int64, ``first`` (tx_period + 1,)
    int64; a robot whose phase is outside [0, tx_period) is in no group)."""
    n = tx_phase.shape[0]
    first = np.zeros(tx_period + 1, dtype=np.int64)
    for i in range(n):
        if 0 <= tx_phase[i] < tx_period:
            first[tx_phase[i] + 1] += 1
    for s in range(tx_period):
        first[s + 1] += first[s]
    order = np.empty(n, dtype=np.int64)
    at = first[:tx_period].copy()
    for i in range(n):
        if 0 <= tx_phase[i] < tx_period:
            order[at[tx_phase[i]]] = i
            at[tx_phase[i]] += 1
    return order, first


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type, out_data,
                in_count, in_type, in_data, in_dist, counters, rng, order, first):
    """Clear the inboxes and deliver this tick's broadcasts (arrays as in World; ``order``
    and ``first``: :func:`senders_by_phase` of ``tx_phase``, so that only this tick's
    senders are visited)."""
    n = pos.shape[0]
    # slots in range of the sender being handled and their squared distances (mm^2)
    cand_s = np.empty(n, dtype=np.uint32)
    cand_d2 = np.empty(n)
    deliver(tick, cfg, grid, pos, alive, present, out_on, out_type, out_data, in_count,
            in_type, in_data, in_dist, counters, rng, order, first, cand_s, cand_d2)


@njit(cache=True, _nrt=False)
def deliver(tick, cfg, grid, pos, alive, present, out_on, out_type, out_data, in_count,
            in_type, in_data, in_dist, counters, rng, order, first, cand_s, cand_d2):
    """:func:`radio_phase`'s work, in the scratch rows ``cand_s`` (N,) uint32 and
    ``cand_d2`` (N,) float64. Compiled without numba's reference counting: it allocates
    nothing and its arrays are held by its caller, so counting them would only cost calls
    (see etswarm.sim.borrow)."""
    cap = in_type.shape[1]
    in_count[:] = 0
    slot = tick % cfg.tx_period
    rng_r = cfg.comm_range
    r2 = rng_r * rng_r
    start, sxb, sidx = grid.start, grid.sxb, grid.sidx
    inv = grid.geom[G_INV]
    ox = grid.geom[G_OX]
    oy = grid.geom[G_OY]
    nx = grid.dims[0]
    ny = grid.dims[1]
    reach = rng_r + grid.geom[G_MARGIN]
    loss = cfg.loss
    noise = cfg.dist_noise
    n_bytes = out_data.shape[1]
    portable = cfg.portable
    sent = 0
    delivered = 0
    lost = 0
    overflow = 0
    for q_send in range(first[slot], first[slot + 1]):
        i = order[q_send]
        if not out_on[i] or not alive[i] or not present[i]:
            continue
        sent += 1
        x = pos[i, 0]
        y = pos[i, 1]
        mtype = out_type[i]
        cx0, cx1 = cell_range(x, reach, ox, inv, nx)
        cy0, cy1 = cell_range(y, reach, oy, inv, ny)
        # the slots in range, in slot order, kept without branching on distances (an
        # unsigned count: numba then indexes without a test for negative indices)
        n_in = np.uint64(0)
        for cy in range(cy0, cy1 + 1):
            row = cy * nx
            for s in range(np.uint64(start[row + cx0]), np.uint64(start[row + cx1 + 1])):
                dx = sxb[s, P_X] - x
                dy = sxb[s, P_Y] - y
                d2 = dx * dx + dy * dy
                cand_s[n_in] = s
                cand_d2[n_in] = d2
                n_in += np.uint64(d2 <= r2)
        # ask for the receivers' inbox rows before filing into them (scattered rows)
        for q in range(n_in):
            j = sidx[cand_s[q]]
            prefetch(in_count, j)
            prefetch(in_type, j)
            prefetch(in_data, j)
            prefetch(in_dist, j)
        for q in range(n_in):
            d2 = cand_d2[q]
            j = sidx[cand_s[q]]
            if j == i or not alive[j]:
                continue
            if loss > 0.0 and rng.random() < loss:
                lost += 1
                continue
            k = in_count[j]
            if k >= cap:
                overflow += 1
                continue
            d = np.sqrt(d2)
            if noise > 0.0:
                d += noise * normal_as(rng, portable)
                if d < 0.0:
                    d = 0.0
            in_type[j, k] = mtype
            if n_bytes == PAYLOAD_BYTES:  # a constant count: one unrolled copy
                for c in range(PAYLOAD_BYTES):
                    in_data[j, k, c] = out_data[i, c]
            else:
                for c in range(n_bytes):
                    in_data[j, k, c] = out_data[i, c]
            in_dist[j, k] = d
            in_count[j] = k + 1
            delivered += 1
    counters[0] += sent
    counters[1] += delivered
    counters[2] += lost
    counters[3] += overflow


@njit(cache=True)
def snapshot_senders(tick, cfg, out_on, out_type, out_data, snap_on, snap_type, snap_data,
                     order, first):
    """Copy the outgoing messages of tick ``tick``'s senders (``out_on`` (N,), ``out_type``
    (N,), ``out_data`` (N, B)) into the same rows of ``snap_*``, so that
    :func:`radio_phase` can deliver them from the copy while the controller writes the
    next ones (``order``, ``first``: :func:`senders_by_phase`)."""
    slot = tick % cfg.tx_period
    n_bytes = out_data.shape[1]
    for q in range(first[slot], first[slot + 1]):
        i = order[q]
        snap_on[i] = out_on[i]
        snap_type[i] = out_type[i]
        for c in range(n_bytes):
            snap_data[i, c] = out_data[i, c]
