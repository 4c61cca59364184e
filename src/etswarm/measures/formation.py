"""Measures of a formation (DESIGN §5), computed from the whole world (not by robots).

Inputs are plain arrays so the measures serve the runner, the experiments and the tests:
``tags`` (N, 2) int tags robots believe they hold, ``holds`` (N,) bool (robot holds a tag),
``stable`` (N,) bool, ``pos`` (N, 2) mm, and the target's cells (P, 2).
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS, enclosed_cells, tags_to_xy, xy_to_nearest_tag


def _tag_set(tags: np.ndarray) -> set[tuple[int, int]]:
    return {(int(x), int(y)) for x, y in np.asarray(tags).reshape(-1, 2)}


def duplicate_tags(tags: np.ndarray, holds: np.ndarray) -> list[tuple[int, int]]:
    """Tags held by two or more robots (each listed once, sorted)."""
    held = np.asarray(tags)[np.asarray(holds, dtype=bool)]
    if len(held) == 0:
        return []
    uniq, counts = np.unique(held, axis=0, return_counts=True)
    return [(int(x), int(y)) for x, y in uniq[counts > 1]]


def is_formed(tags: np.ndarray, holds: np.ndarray, stable: np.ndarray, target: np.ndarray) -> bool:
    """Every target cell is held by a Stable robot and no tag is held twice."""
    if duplicate_tags(tags, holds):
        return False
    stable_tags = _tag_set(np.asarray(tags)[np.asarray(stable, dtype=bool)])
    return _tag_set(target) <= stable_tags


def jaccard(tags: np.ndarray, holds: np.ndarray, target: np.ndarray) -> float:
    """|held ∩ target| / |held ∪ target| over tags (1.0 when both are empty)."""
    held = _tag_set(np.asarray(tags)[np.asarray(holds, dtype=bool)])
    want = _tag_set(target)
    union = held | want
    return 1.0 if not union else len(held & want) / len(union)


def free_sites(tags: np.ndarray, holds: np.ndarray, target: np.ndarray) -> list[tuple[int, int]]:
    """Target sites (tags) that no robot with ``holds`` set holds, sorted.

    ``tags`` (N, 2) int, ``holds`` (N,) bool, ``target`` (M, 2) int."""
    held = _tag_set(np.asarray(tags)[np.asarray(holds, dtype=bool)])
    return sorted(_tag_set(target) - held)


def fit_residuals_mm(
    pos: np.ndarray, tags: np.ndarray, holds: np.ndarray, spacing_mm: float
) -> np.ndarray | None:
    """Where each robot that holds a tag stands off its ideal site after the best rigid
    fit of all of them: (K, 2) mm, fitted site minus position, in the order of the
    ``holds`` mask (N,) bool. The fit (rotation + translation, Kabsch) maps ideal site
    positions onto the robots' positions. None when fewer than two robots hold tags."""
    mask = np.asarray(holds, dtype=bool)
    if mask.sum() < 2:
        return None
    p = np.asarray(pos, dtype=np.float64)[mask]
    q = tags_to_xy(np.asarray(tags)[mask], spacing_mm)
    return apply_fit(rigid_fit(q, p), q) - p


def placement_error_mm(
    pos: np.ndarray, tags: np.ndarray, holds: np.ndarray, spacing_mm: float
) -> float | None:
    """RMS distance (mm) of placed robots from their ideal sites after the best rigid fit
    (``fit_residuals_mm``). None when fewer than two robots hold tags."""
    resid = fit_residuals_mm(pos, tags, holds, spacing_mm)
    if resid is None:
        return None
    return float(np.sqrt(np.mean(np.sum(resid**2, axis=1))))


#: Robots of neighbouring sites stand about d = 40 mm apart on a sound lattice. Past this
#: many lattice spacings (60 mm) they are far from touching, though a third 33 mm body
#: still does not fit between them (66 mm): the shape has torn there, whatever the tags say.
STRETCHED_FACTOR = 1.5


def stretched_links(
    pos: np.ndarray, tags: np.ndarray, holds: np.ndarray, spacing_mm: float,
    factor: float = STRETCHED_FACTOR,
) -> int:
    """How many pairs of robots that hold neighbouring lattice tags stand more than
    ``factor`` lattice spacings apart. ``pos`` (N, 2) mm, ``tags`` (N, 2) int, ``holds``
    (N,) bool. A shape can be formed by its tags (DESIGN §5) with its robots in two
    pieces; this counts the links where that happened (0 on a sound lattice). A tag
    held twice counts once, by its lowest-index holder."""
    mask = np.asarray(holds, dtype=bool)
    held = np.asarray(tags, dtype=np.int64)[mask]
    where = np.asarray(pos, dtype=np.float64)[mask]
    if len(held) < 2:
        return 0
    held, first = np.unique(held, axis=0, return_index=True)
    where = where[first]
    # one int64 key per tag; tags stay far inside +-2**20
    keys = (held[:, 0] << 21) + held[:, 1]
    order = np.argsort(keys)
    keys = keys[order]
    count = 0
    for dx, dy in NEIGHBOUR_OFFSETS[:3]:  # each neighbouring pair once
        want = ((held[:, 0] + dx) << 21) + held[:, 1] + dy
        at = np.minimum(np.searchsorted(keys, want), len(keys) - 1)
        found = keys[at] == want
        other = order[at[found]]
        gaps = np.linalg.norm(where[found] - where[other], axis=1)
        count += int(np.count_nonzero(gaps > factor * spacing_mm))
    return count


def rigid_fit(
    ideal: np.ndarray, actual: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Best rotation + translation (Kabsch) taking ``ideal`` (K, 2) mm onto ``actual``
    (K, 2) mm, K >= 2: returns ``(rot (2, 2), ideal_centre (2,), actual_centre (2,))``."""
    qc0 = ideal.mean(axis=0)
    pc0 = actual.mean(axis=0)
    u, _, vt = np.linalg.svd((ideal - qc0).T @ (actual - pc0))
    sign = np.sign(np.linalg.det(u @ vt)) or 1.0
    return u @ np.diag([1.0, sign]) @ vt, qc0, pc0


def apply_fit(fit: tuple[np.ndarray, np.ndarray, np.ndarray], points: np.ndarray) -> np.ndarray:
    """Map ideal positions ``points`` (M, 2) mm through a :func:`rigid_fit` result."""
    rot, qc0, pc0 = fit
    return (np.asarray(points, dtype=np.float64) - qc0) @ rot + pc0


def in_holes(
    points: np.ndarray, pos: np.ndarray, tags: np.ndarray, holds: np.ndarray,
    target: np.ndarray, spacing_mm: float,
) -> np.ndarray:
    """Which ``points`` (M, 2) mm stand in a hole of the ``target`` cells (P, 2), such as
    the middle of an ``O``: (M,) bool, by the nearest site of the lattice that the robots
    holding tags (``pos`` (N, 2) mm, ``tags`` (N, 2), ``holds`` (N,) bool, two at least)
    fit best (``rigid_fit``). Used to tell searchers shut in a hole from those outside."""
    mask = np.asarray(holds, dtype=bool)
    rot, ideal_centre, actual_centre = rigid_fit(
        tags_to_xy(np.asarray(tags)[mask], spacing_mm), np.asarray(pos, dtype=np.float64)[mask]
    )
    ideal = (np.asarray(points, dtype=np.float64).reshape(-1, 2) - actual_centre) @ rot.T
    sites = xy_to_nearest_tag(ideal + ideal_centre, spacing_mm)
    holes = {tuple(t) for t in enclosed_cells(target).tolist()}
    return np.array([tuple(t) in holes for t in sites.tolist()], dtype=bool)


def shut_in_holes(
    pos: np.ndarray, tags: np.ndarray, holds: np.ndarray, searching: np.ndarray,
    target: np.ndarray, spacing_mm: float,
) -> int:
    """How many ``searching`` robots (N,) bool stand in a hole of the ``target`` cells
    (P, 2), by :func:`in_holes` on the lattice the holders (``holds`` (N,) bool; ``pos``
    (N, 2) mm, ``tags`` (N, 2)) fit. A hole whose edge is held all round shuts them in:
    the sites they would take stay free. 0 for a target without holes, or with fewer than
    two holders to fit."""
    searching = np.asarray(searching, dtype=bool)
    if not searching.any() or np.count_nonzero(holds) < 2 or not len(enclosed_cells(target)):
        return 0
    pos = np.asarray(pos, dtype=np.float64)
    return int(np.count_nonzero(in_holes(pos[searching], pos, tags, holds, target, spacing_mm)))


def way_across(free: list[tuple[int, int]], target: np.ndarray) -> bool:
    """Some of the ``free`` tags of ``target`` ((P, 2) tags) join a site on the edge of one
    of its holes to a site beside the outside (a neighbour site neither in the shape nor
    in a hole), through free tags alone (six-neighbour steps): a way across a ring, the end
    every capture rule refuses (docs/algorithm.md, "Session 64"). False for a target
    without holes."""
    if len(free) == 0:
        return False
    cells = _tag_set(target)
    holes = _tag_set(enclosed_cells(target))
    free_set = {(int(x), int(y)) for x, y in free}

    def around(site: tuple[int, int]) -> list[tuple[int, int]]:
        return [(site[0] + int(dx), site[1] + int(dy)) for dx, dy in NEIGHBOUR_OFFSETS]

    frontier = [t for t in free_set if any(n in holes for n in around(t))]
    reached = set(frontier)
    while frontier:
        site = frontier.pop()
        if any(n not in cells and n not in holes for n in around(site)):
            return True
        for n in around(site):
            if n in free_set and n not in reached:
                reached.add(n)
                frontier.append(n)
    return False


def components(pos: np.ndarray, members: np.ndarray, radius_mm: float) -> list[np.ndarray]:
    """Connected groups of ``members`` robots (links between centres <= radius_mm).

    Returns a list of int64 ID arrays, largest group first (ties: lowest ID first).
    """
    ids = np.flatnonzero(np.asarray(members, dtype=bool))
    if len(ids) == 0:
        return []
    tree = cKDTree(np.asarray(pos)[ids])
    pairs = tree.query_pairs(radius_mm, output_type="ndarray")
    m = len(ids)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(m, m))
    _, labels = connected_components(graph, directed=False)
    groups = [ids[labels == lab] for lab in np.unique(labels)]
    groups.sort(key=lambda g: (-len(g), int(g[0])))
    return groups


def min_pair_distance(pos: np.ndarray, members: np.ndarray) -> float:
    """Smallest centre distance between two ``members`` robots (inf for fewer than two)."""
    p = np.asarray(pos)[np.asarray(members, dtype=bool)]
    if len(p) < 2:
        return float("inf")
    dist, _ = cKDTree(p).query(p, k=2)
    return float(dist[:, 1].min())
