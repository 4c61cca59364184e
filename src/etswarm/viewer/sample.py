"""A hand-made scene: a lattice triangle with robots in every ET state.

Used by the tests, the docs' pictures and ``etswarm view --sample`` style checks; it
depends on nothing but the lattice embedding of the design brief (section 1).
"""

from __future__ import annotations

import math

import numpy as np

from etswarm.algorithm.states import State
from etswarm.seeding import stream
from etswarm.viewer.scene import Scene


def lattice_xy(tags: np.ndarray, spacing_mm: float = 40.0) -> np.ndarray:
    """(K, 2) tags (X, Y) -> (K, 2) mm: ``x = d(X - Y/2)``, ``y = d Y sqrt(3)/2``."""
    tags = np.asarray(tags, dtype=np.float64).reshape(-1, 2)
    x = spacing_mm * (tags[:, 0] - tags[:, 1] / 2)
    y = spacing_mm * tags[:, 1] * math.sqrt(3) / 2
    return np.stack([x, y], axis=1)


def triangle_tags(side: int) -> np.ndarray:
    """(K, 2) tags of a filled lattice triangle with ``side`` cells on each edge."""
    return np.array([(x, y) for y in range(side) for x in range(y, side)], dtype=np.int64)


def sample_scene(side: int = 6, queue: int = 8, seed: int = 0, spacing_mm: float = 40.0) -> Scene:
    """A triangle of ``side`` being formed: placed robots in the placed states, two
    searching robots on its edge, a Danger/Leader pair, a dead robot, and a queue."""
    rng = stream(seed, "viewer-sample")
    tags = triangle_tags(side)
    sites = lattice_xy(tags, spacing_mm)
    n_placed = len(tags) - 3  # the last three sites still empty
    placed_states = [State.STABLE] * n_placed
    cycle = [State.INACTIVE, State.ACTIVE, State.QUASI, State.DANGER, State.LEADER]
    for k, s in enumerate(cycle):
        placed_states[n_placed - 1 - k] = s
    pos = [sites[:n_placed] + rng.normal(0, 1.5, (n_placed, 2))]
    states = list(placed_states)
    has_tag = [True] * n_placed
    tag_rows = list(tags[:n_placed])
    ts = list(range(1, n_placed + 1))
    # two robots searching along the right edge
    edge = sites[n_placed - 1] + np.array(
        [[spacing_mm * 1.1, -spacing_mm * 0.3], [spacing_mm * 1.4, -spacing_mm * 1.3]]
    )
    pos.append(edge)
    states += [State.SEARCH, State.SEARCH]
    # a queue of robots leading to the seeds, below-left of the shape
    qx = sites[0, 0] - spacing_mm * (1.2 + np.arange(queue) * 0.95)
    qy = np.full(queue, sites[0, 1] - spacing_mm * 0.9)
    pos.append(np.stack([qx, qy], axis=1))
    states += [State.QUEUED] * queue
    n = n_placed + 2 + queue
    has_tag += [False] * (n - n_placed)
    tag_rows += [np.zeros(2, np.int64)] * (n - n_placed)
    ts += [0] * (n - n_placed)
    alive = np.ones(n, bool)
    alive[n_placed // 2] = False  # one battery death inside the shape
    heading = rng.uniform(0, 2 * math.pi, n)
    heading[n_placed : n_placed + 2] = [math.pi / 2, math.pi * 0.6]
    return Scene(
        pos=np.concatenate(pos),
        heading=heading,
        present=np.ones(n, bool),
        alive=alive,
        state=np.array(states, np.uint8),
        tag=np.array(tag_rows),
        has_tag=np.array(has_tag),
        ts=np.array(ts),
        target_sites=sites,
        sim_time_s=3 * 3600 + 25 * 60 + 7.4,
        speedup=118.0,
        events=["t=1:02:11 formed", "t=1:40:00 split x=60 mm", "t=2:10:05 Leader #14 census 12"],
        title="sample: triangle, side 6",
    )


def sample_record(side: int = 6, frames: int = 240, dt_s: float = 30.0, seed: int = 0):  # type: ignore[no-untyped-def]
    """A made-up recording: robots leave a queue, settle on a triangle one by one
    (Search -> Inactive -> Active -> Stable), one side is cut away half-way, and the
    rest regenerate (Danger -> Leader -> Active -> Stable). For tests and docs only.
    """
    from etswarm.viewer.record import RunRecord

    rng = stream(seed, "viewer-sample-record")
    tags = triangle_tags(side)
    sites = lattice_xy(tags)
    n = len(tags)
    queue = np.stack([sites[0, 0] - 40.0 * (1.2 + np.arange(n)), np.full(n, sites[0, 1] - 36.0)], 1)
    t = np.arange(frames) * dt_s
    placed_at = np.linspace(0.05, 0.45, n) * t[-1]  # when robot i reaches its site
    cut_t = 0.55 * t[-1]
    cut = sites[:, 0] > np.median(sites[:, 0])  # robots removed by the cut
    pos = np.zeros((frames, n, 2))
    state = np.zeros((frames, n), np.uint8)
    present = np.ones((frames, n), bool)
    has_tag = np.zeros((frames, n), bool)
    nn = np.zeros((frames, n), np.int64)
    site_set = {tuple(x) for x in tags.tolist()}
    full_nn = np.array(
        [
            sum(
                (x + dx, y + dy) in site_set
                for dx, dy in ((0, 1), (1, 1), (1, 0), (0, -1), (-1, -1), (-1, 0))
            )
            for x, y in tags.tolist()
        ]
    )
    for k, tk in enumerate(t):
        travel = np.clip((tk - (placed_at - 600)) / 600, 0, 1)[:, None]
        pos[k] = queue + (sites - queue) * travel + rng.normal(0, 0.8, (n, 2))
        placed = tk >= placed_at
        st = np.where(placed, State.STABLE, np.where(travel[:, 0] > 0, State.SEARCH, State.QUEUED))
        recent = placed & (tk < placed_at + 240)
        st[recent] = State.ACTIVE
        st[placed & (tk < placed_at + 90)] = State.INACTIVE
        has_tag[k] = placed
        nn[k] = full_nn
        if tk >= cut_t:
            present[k] = ~cut
            since = tk - cut_t
            st[~cut] = State.DANGER if since < 300 else State.STABLE
            if 300 <= since < 600:
                st[~cut] = State.ACTIVE
                st[np.flatnonzero(~cut)[0]] = State.LEADER
            if since >= 600:
                kept = ~cut
                sub = {tuple(x) for x in tags[kept].tolist()}
                nn[k, kept] = [
                    sum(
                        (x + dx, y + dy) in sub
                        for dx, dy in ((0, 1), (1, 1), (1, 0), (0, -1), (-1, -1), (-1, 0))
                    )
                    for x, y in tags[kept].tolist()
                ]
        state[k] = st
    formed_t = float(placed_at[-1] + 240)
    events = [
        {"t_s": formed_t, "kind": "formed"},
        {"t_s": cut_t, "kind": "damage", "how": "split"},
        {"t_s": cut_t + 600, "kind": "formed"},
    ]
    return RunRecord(
        t_s=t,
        pos=pos,
        heading=rng.uniform(0, 2 * math.pi, (frames, n)),
        state=state,
        present=present,
        alive=np.ones((frames, n), bool),
        tag=np.broadcast_to(tags, (frames, n, 2)).copy(),
        has_tag=has_tag,
        ts=np.broadcast_to(np.arange(1, n + 1), (frames, n)).copy(),
        nn=nn,
        events=events,
        target_sites=sites,
        title=f"sample triangle, side {side}",
    )
