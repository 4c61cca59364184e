"""Phase 1 of a tick: the infrared radio.

Inboxes are cleared, then every robot that is present, alive, has ``out_on`` set and whose
broadcast phase comes up this tick (``tick % tx_period == tx_phase``) sends its current
``out_type``/``out_data``. Every other present, alive robot whose centre lies within
``comm_range`` receives a copy unless it is lost (independent probability ``loss`` per
receiver); the copy carries the centre distance plus N(0, dist_noise) noise, clipped at 0.
A full inbox (K messages) drops further copies and counts them. Senders are handled in
index order, so inbox order is sender order.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.neighbours import bucket_of, cell_of


@njit(cache=True)
def radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type, out_data,
                in_count, in_type, in_data, in_dist, counters, rng):
    """Clear the inboxes and deliver this tick's broadcasts (arrays as in World)."""
    n = pos.shape[0]
    cap = in_type.shape[1]
    in_count[:] = 0
    slot = tick % cfg.tx_period
    rng_r = cfg.comm_range
    r2 = rng_r * rng_r
    head, nxt, cell_x, cell_y = grid.head, grid.nxt, grid.cell_x, grid.cell_y
    inv = grid.inv_cell[0]
    mask = head.shape[0] - 1
    loss = cfg.loss
    noise = cfg.dist_noise
    sent = 0
    delivered = 0
    lost = 0
    overflow = 0
    for i in range(n):
        if tx_phase[i] != slot or not out_on[i] or not alive[i] or not present[i]:
            continue
        sent += 1
        x = pos[i, 0]
        y = pos[i, 1]
        mtype = out_type[i]
        for cx in range(cell_of(x - rng_r, inv), cell_of(x + rng_r, inv) + 1):
            for cy in range(cell_of(y - rng_r, inv), cell_of(y + rng_r, inv) + 1):
                j = head[bucket_of(cx, cy, mask)]
                while j >= 0:
                    if j != i and cell_x[j] == cx and cell_y[j] == cy and alive[j]:
                        dx = pos[j, 0] - x
                        dy = pos[j, 1] - y
                        d2 = dx * dx + dy * dy
                        if d2 <= r2:
                            if loss > 0.0 and rng.random() < loss:
                                lost += 1
                            else:
                                k = in_count[j]
                                if k >= cap:
                                    overflow += 1
                                else:
                                    d = np.sqrt(d2)
                                    if noise > 0.0:
                                        d += noise * rng.standard_normal()
                                        if d < 0.0:
                                            d = 0.0
                                    in_type[j, k] = mtype
                                    for b in range(out_data.shape[1]):
                                        in_data[j, k, b] = out_data[i, b]
                                    in_dist[j, k] = d
                                    in_count[j] = k + 1
                                    delivered += 1
                    j = nxt[j]
    counters[0] += sent
    counters[1] += delivered
    counters[2] += lost
    counters[3] += overflow
