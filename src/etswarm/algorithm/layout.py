"""Starting layouts: three seed robots on the lattice and a repository of Queued robots.

This is the experimenter's set-up, as in the paper: the seeds are put on three mutually
adjacent sites and told their tags; every other robot is put in a connected repository
outside the target's footprint and knows nothing but its ID and the gene. IDs are given
so that the lowest ID is the repository robot farthest from the seeds (the paper releases
robots from the end of the queue): a released robot is then always on the repository's
outer edge and can leave.

Layouts:

- ``queue``: a straight line of robots 45 mm apart leading to the seeds.
- ``cluster``: a hexagonally packed blob (45 mm spacing) beside the seeds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from etswarm.errors import EtswarmError
from etswarm.shapes.lattice import seed_triangles, tags_to_xy
from etswarm.sim.fpmath import atan2, atan2_array, sin_cos

LAYOUTS = ("queue", "cluster")

#: Centre spacing of repository robots, mm (connected: below the 70 mm radio range).
REPOSITORY_SPACING_MM = 45.0

#: A queue of more robots than this (6.8 m) gets a note suggesting the cluster: searchers
#: walking a long queue shove it apart, and those lost beside it circle where it used to be
#: (session 31: a plus, an H and an L of 311-347 cells with 3-wide strokes formed 4 of 30
#: runs in 12 h from the queue, 18 from the cluster; the library's bigplus and bigH 3 of
#: 10 each from the queue, 17 and 14 of 20 from the cluster).
LONG_QUEUE_ROBOTS = 150

#: Clearance between the repository and the target's sites, in lattice spacings.
GAP_SPACINGS = 1.3


@dataclass(frozen=True)
class Layout:
    """Initial placement of N robots (robot ID = row index).

    Attributes:
        pos: (N, 2) float64 mm, world frame (origin = site of tag (0, 0)).
        heading: (N,) float64 rad.
        seed_ids: (3,) int64, IDs of the seeds; seed 0 starts Active (TS 1), the others
            Inactive (TS 2).
        seed_tags: (3, 2) int64 tags of the seeds.
    """

    pos: np.ndarray
    heading: np.ndarray
    seed_ids: np.ndarray
    seed_tags: np.ndarray

    @property
    def n(self) -> int:
        return int(self.pos.shape[0])


def _unit(angle: float, portable: bool) -> np.ndarray:
    s, c = sin_cos(angle) if portable else (np.sin(angle), np.cos(angle))
    return np.array([c, s])


def lengths(v: np.ndarray, portable: bool) -> np.ndarray:
    """Length of each row of ``v`` ((K, 2) mm, any K): by IEEE arithmetic alone when
    ``portable`` (the same bits everywhere, as ``fpmath.hypot``), else numpy's ``hypot``."""
    if not portable:
        return np.hypot(v[:, 0], v[:, 1])
    return np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1])


def arctan2(y, x, portable: bool):  # type: ignore[no-untyped-def]
    """``np.arctan2(y, x)`` of floats or 1-D arrays, by :mod:`etswarm.sim.fpmath` when
    ``portable``."""
    if not portable:
        return np.arctan2(y, x)
    if np.ndim(y) == 0:
        return atan2(float(y), float(x))
    return atan2_array(np.ascontiguousarray(y, dtype=np.float64),
                       np.ascontiguousarray(x, dtype=np.float64))


def _queue_points(head: np.ndarray, u: np.ndarray, count: int) -> np.ndarray:
    k = np.arange(count, dtype=np.float64)[:, None]
    return head[None, :] + k * REPOSITORY_SPACING_MM * u[None, :]


def _cluster_points(head: np.ndarray, u: np.ndarray, count: int, keep_out,
                    portable: bool) -> np.ndarray:
    """``count`` hexagonal-lattice points grown outward from ``head`` (nearest first)."""
    radius = int(np.ceil(np.sqrt(count))) + 3
    s = REPOSITORY_SPACING_MM
    ii, jj = np.meshgrid(np.arange(-radius, radius + 1), np.arange(-radius, radius + 1))
    ii = ii.ravel().astype(np.float64)
    jj = jj.ravel().astype(np.float64)
    v = np.array([-u[1], u[0]])
    # Hex lattice aligned with u, shifted so point (0, 0) is the head.
    a = ii + 0.5 * jj
    b = jj * np.sqrt(3) / 2
    pts = head[None, :] + s * (a[:, None] * v[None, :] + b[:, None] * u[None, :])
    ahead = b >= 0
    clear = keep_out(pts)
    pts = pts[ahead & clear]
    dist = lengths(pts - head[None, :], portable)
    order = np.lexsort((pts[:, 1], pts[:, 0], np.round(dist, 6)))
    return pts[order[:count]]


def plan_layout(
    cells: np.ndarray,
    n_robots: int,
    *,
    layout: str = "queue",
    spacing_mm: float = 40.0,
    rng: np.random.Generator,
    portable: bool = False,
) -> Layout:
    """Place ``n_robots`` robots (>= 3) to build ``cells`` ((P, 2) tags).

    The seed triangle is drawn with ``rng`` among triangles from which the whole shape can
    be built and whose repository fits: every repository robot at least ``GAP_SPACINGS`` d
    from every target site and the
    repository's first robot within 1.8 d of a seed (so searching robots walk from the
    repository straight onto the growing shape). ``portable``: angles by
    :mod:`etswarm.sim.fpmath` (``SimParams.portable_math``).
    """
    if layout not in LAYOUTS:
        raise EtswarmError(f"--layout must be one of {', '.join(LAYOUTS)}, got {layout!r}")
    if n_robots < 3:
        raise EtswarmError(f"--robots must be at least 3 (the seeds), got {n_robots}")
    d = spacing_mm
    tris = seed_triangles(cells)
    if len(tris) == 0:
        raise EtswarmError("the shape has no seed triangle from which it can be built")
    sites = tags_to_xy(np.asarray(cells), d)
    tree = cKDTree(sites)
    centre = sites.mean(axis=0)
    n_rep = n_robots - 3

    def keep_out(points: np.ndarray) -> np.ndarray:
        dist, _ = tree.query(points)
        return dist >= GAP_SPACINGS * d

    order = rng.permutation(len(tris))
    for t in order[: min(len(order), 400)]:
        seed_tags = tris[t]
        seed_xy = tags_to_xy(seed_tags, d)
        s_centre = seed_xy.mean(axis=0)
        out = s_centre - centre
        base = arctan2(out[1], out[0], portable) if np.hypot(*out) > 1e-9 else 0.0
        for k in range(24):
            # Directions in order of closeness to "away from the shape's centre".
            step = (k + 1) // 2 * (1 if k % 2 else -1)
            u = _unit(base + step * np.pi / 12, portable)
            head = None
            for r in np.arange(1.0, 4.0, 0.05) * d:
                p = s_centre + r * u
                if keep_out(p[None, :])[0]:
                    head = p
                    break
            if head is None:
                continue
            if np.min(np.hypot(*(seed_xy - head[None, :]).T)) > 1.8 * d:
                continue
            if n_rep == 0:
                rep = np.zeros((0, 2))
            elif layout == "queue":
                rep = _queue_points(head, u, n_rep)
                if not np.all(keep_out(rep)):
                    continue
            else:
                rep = _cluster_points(head, u, n_rep, keep_out, portable)
                if len(rep) < n_rep:
                    continue
            return _assemble(rep, seed_xy, seed_tags, portable)
    raise EtswarmError(
        f"could not fit a {layout} of {n_rep} robots beside the shape; try --layout cluster"
    )


def _assemble(
    rep: np.ndarray, seed_xy: np.ndarray, seed_tags: np.ndarray, portable: bool
) -> Layout:
    """Number the robots: repository farthest-first, then the three seeds."""
    s_centre = seed_xy.mean(axis=0)
    far = lengths(rep - s_centre[None, :], portable) if len(rep) else np.zeros(0)
    rep = rep[np.argsort(-far, kind="stable")]
    pos = np.vstack([rep, seed_xy]) if len(rep) else seed_xy.copy()
    rel = pos - s_centre[None, :]
    heading = arctan2(rel[:, 1], rel[:, 0], portable)
    n_rep = len(rep)
    seed_ids = np.arange(n_rep, n_rep + 3, dtype=np.int64)
    heading[seed_ids] = 0.0
    return Layout(
        pos=pos.astype(np.float64),
        heading=heading.astype(np.float64),
        seed_ids=seed_ids,
        seed_tags=np.asarray(seed_tags, dtype=np.int64),
    )
