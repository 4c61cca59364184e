"""The skewed triangular lattice: tags, embedding, adjacency, connectivity, constructibility.

Conventions (DESIGN §1): a tag ``(X, Y)`` is an integer pair; its six lattice neighbours are
at the offsets :data:`NEIGHBOUR_OFFSETS`, listed in cyclic order, so consecutive offsets
(including the last and the first) are themselves adjacent. Tag ``(X, Y)`` sits at
``x = d·(X − Y/2)``, ``y = d·Y·√3/2`` (mm) for lattice spacing ``d``.

A *cell set* is an int64 array of shape (P, 2) of distinct tags. Functions here never depend
on set or dict iteration order: results are functions of the sorted tags only.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np
from scipy.ndimage import label
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import shortest_path

#: (6, 2) int64 tag offsets of the six neighbours, in cyclic order: (0,1) (1,1) (1,0) (0,-1)
#: (-1,-1) (-1,0); offsets k and k+1 (mod 6) are adjacent to each other.
NEIGHBOUR_OFFSETS: np.ndarray = np.array(
    [(0, 1), (1, 1), (1, 0), (0, -1), (-1, -1), (-1, 0)], dtype=np.int64
)
NEIGHBOUR_OFFSETS.setflags(write=False)

_OFFSETS = [tuple(int(v) for v in row) for row in NEIGHBOUR_OFFSETS]
_SQRT3_2 = math.sqrt(3.0) / 2.0


def as_cells(cells: np.ndarray | list | tuple) -> np.ndarray:
    """Return ``cells`` as a C-contiguous int64 array of shape (P, 2)."""
    arr = np.asarray(cells, dtype=np.int64)
    if arr.size == 0:
        return np.zeros((0, 2), dtype=np.int64)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"cells must have shape (P, 2), got {arr.shape}")
    return np.ascontiguousarray(arr)


def sort_cells(cells: np.ndarray) -> np.ndarray:
    """Return the (P, 2) tags sorted by (X, Y)."""
    cells = as_cells(cells)
    order = np.lexsort((cells[:, 1], cells[:, 0]))
    return cells[order]


def tags_to_xy(tags: np.ndarray, spacing_mm: float = 40.0) -> np.ndarray:
    """Embed tags (K, 2) in the plane: (K, 2) float64 mm, ``x = d(X − Y/2)``, ``y = d·Y·√3/2``."""
    t = np.asarray(tags, dtype=np.float64).reshape(-1, 2)
    out = np.empty_like(t)
    out[:, 0] = spacing_mm * (t[:, 0] - 0.5 * t[:, 1])
    out[:, 1] = spacing_mm * _SQRT3_2 * t[:, 1]
    return out


def xy_to_nearest_tag(xy: np.ndarray, spacing_mm: float = 40.0) -> np.ndarray:
    """Nearest lattice tag (K, 2) int64 of points ``xy`` (K, 2) mm (inverse of :func:`tags_to_xy`).

    Uses cube-coordinate rounding, so every point goes to the lattice site whose hexagonal
    Voronoi cell contains it (ties on cell borders resolved by round-half-to-even).
    """
    p = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    fy = p[:, 1] / (spacing_mm * _SQRT3_2)
    fx = p[:, 0] / spacing_mm + 0.5 * fy
    # cube coordinates (a, b, c) = (X, -Y, Y - X), a + b + c = 0
    a, b, c = fx, -fy, fy - fx
    ra, rb, rc = np.rint(a), np.rint(b), np.rint(c)
    da, db, dc = np.abs(ra - a), np.abs(rb - b), np.abs(rc - c)
    fix_a = (da > db) & (da > dc)
    fix_b = ~fix_a & (db > dc)
    ra = np.where(fix_a, -rb - rc, ra)
    rb = np.where(fix_b, -ra - rc, rb)
    return np.stack([ra, -rb], axis=1).astype(np.int64)


def turn_cells(cells: np.ndarray, turns: int) -> np.ndarray:
    """``cells`` ((P, 2) int64 tags) turned ``turns`` times by 60° about tag (0, 0), each
    turn taking every neighbour offset to the next one in :data:`NEIGHBOUR_OFFSETS`
    ((X, Y) -> (Y, Y - X)); (P, 2) int64. A turned shape is the same shape: the lattice
    looks the same from every 60° step."""
    out = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    for _ in range(turns % 6):
        out = np.stack([out[:, 1], out[:, 1] - out[:, 0]], axis=1)
    return out


def lattice_distance(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Number of lattice steps between tags ``a`` and ``b`` (broadcasting (..., 2) arrays)."""
    d = np.asarray(a, dtype=np.int64) - np.asarray(b, dtype=np.int64)
    dx, dy = d[..., 0], d[..., 1]
    return np.maximum(np.maximum(np.abs(dx), np.abs(dy)), np.abs(dx - dy))


def squared_distance(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Exact squared Euclidean distance in units of d², an integer: ``dX² − dX·dY + dY²``."""
    d = np.asarray(a, dtype=np.int64) - np.asarray(b, dtype=np.int64)
    dx, dy = d[..., 0], d[..., 1]
    return dx * dx - dx * dy + dy * dy


def are_adjacent(a: tuple[int, int], b: tuple[int, int]) -> bool:
    """True when tags ``a`` and ``b`` are lattice neighbours."""
    return (int(b[0]) - int(a[0]), int(b[1]) - int(a[1])) in _OFFSETS


def neighbour_index(cells: np.ndarray) -> np.ndarray:
    """(P, 6) int64: index into ``cells`` of each cell's neighbour k (offset k), or -1 if absent."""
    cells = as_cells(cells)
    p = len(cells)
    if p == 0:
        return np.zeros((0, 6), dtype=np.int64)
    lo = cells.min(axis=0) - 1
    hi = cells.max(axis=0) + 1
    grid = np.full((int(hi[0] - lo[0]) + 1, int(hi[1] - lo[1]) + 1), -1, dtype=np.int64)
    rel = cells - lo
    grid[rel[:, 0], rel[:, 1]] = np.arange(p)
    out = np.empty((p, 6), dtype=np.int64)
    for k, (ox, oy) in enumerate(_OFFSETS):
        out[:, k] = grid[rel[:, 0] + ox, rel[:, 1] + oy]
    return out


def neighbour_counts(cells: np.ndarray) -> np.ndarray:
    """(P,) int64: how many of each cell's six neighbours are in ``cells`` (the NN)."""
    return (neighbour_index(cells) >= 0).sum(axis=1).astype(np.int64)


def _steps_from_extra_node(nbr: np.ndarray, joined: np.ndarray) -> np.ndarray:
    """(P,) float steps from one extra node, joined to cells ``joined`` (indices), to every
    cell of the lattice graph ``nbr`` ((P, 6) neighbour indices, -1 none); inf where it
    cannot be reached."""
    p = len(nbr)
    inner = nbr >= 0
    rows = np.concatenate([np.repeat(np.arange(p), 6)[inner.ravel()], joined,
                           np.full(len(joined), p)])
    cols = np.concatenate([nbr[inner], np.full(len(joined), p), joined])
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(p + 1, p + 1)).tocsr()
    return shortest_path(graph, unweighted=True, indices=p)[:p]


def depths(cells: np.ndarray) -> np.ndarray:
    """(P,) int64: each cell's depth, the fewest lattice steps from it to a site outside
    ``cells`` (1 for a cell on the rim, one with a neighbour outside). A shape whose
    depths are all at most 2 is drawn in strokes at most three cells wide."""
    nbr = neighbour_index(cells)
    if len(nbr) == 0:
        return np.zeros(0, dtype=np.int64)
    # The extra node stands for the outside, joined to every rim cell.
    rim = np.flatnonzero(~(nbr >= 0).all(axis=1))
    return _steps_from_extra_node(nbr, rim).astype(np.int64)


def steps_from(cells: np.ndarray, sources: np.ndarray) -> np.ndarray:
    """(P,) float: the fewest lattice steps within ``cells`` from any of ``sources``
    ((S, 2) tags; those not in ``cells`` are ignored) to each cell; 0 on a source, inf
    where no source is reached."""
    nbr = neighbour_index(cells)
    if len(nbr) == 0:
        return np.zeros(0)
    index = {tuple(c): k for k, c in enumerate(np.asarray(cells).tolist())}
    joined = np.array([index[t] for t in map(tuple, np.asarray(sources).tolist()) if t in index],
                      dtype=np.int64)
    return _steps_from_extra_node(nbr, joined) - 1.0


def edge_count(cells: np.ndarray) -> int:
    """Number of lattice edges with both ends in ``cells``."""
    return int(neighbour_counts(cells).sum()) // 2


def component_labels(cells: np.ndarray) -> np.ndarray:
    """(P,) int64 connected-component label of each cell; components numbered 0.. in order of
    their first cell in ``cells``."""
    nbr = neighbour_index(cells).tolist()
    labels = [-1] * len(nbr)
    current = 0
    for start in range(len(nbr)):
        if labels[start] >= 0:
            continue
        labels[start] = current
        stack = [start]
        while stack:
            c = stack.pop()
            for m in nbr[c]:
                if m >= 0 and labels[m] < 0:
                    labels[m] = current
                    stack.append(m)
        current += 1
    return np.asarray(labels, dtype=np.int64)


#: The six-neighbour connectivity of tags as a 3x3 structuring element over (X, Y) index
#: grids: entry [1 + dX, 1 + dY] is 1 for the offsets (0, ±1), (±1, 0), (1, 1), (-1, -1).
_HEX_STRUCTURE = np.array([[1, 1, 0], [1, 1, 1], [0, 1, 1]], dtype=np.int64)


def enclosed_cells(cells: np.ndarray) -> np.ndarray:
    """(H, 2) int64 sorted tags of the holes of ``cells``: the sites outside the shape that
    no path of outside sites (six-neighbour steps) joins to the far outside, such as the
    middle of an ``O``. Empty for a shape without holes. A robot that orbits the shape
    from outside reaches them only through free sites of the shape itself."""
    cells = as_cells(cells)
    if len(cells) == 0:
        return np.zeros((0, 2), dtype=np.int64)
    lo = cells.min(axis=0) - 1
    hi = cells.max(axis=0) + 1
    free = np.ones((int(hi[0] - lo[0]) + 1, int(hi[1] - lo[1]) + 1), dtype=bool)
    rel = cells - lo
    free[rel[:, 0], rel[:, 1]] = False
    labels, _ = label(free, structure=_HEX_STRUCTURE)
    # The one-site margin round the shape is free and joined all round: its label is the
    # far outside.
    holes = free & (labels != labels[0, 0])
    return sort_cells(np.argwhere(holes).astype(np.int64) + lo)


def hole_edge_cells(cells: np.ndarray) -> np.ndarray:
    """(E, 2) int64 sorted tags of the cells of ``cells`` with a neighbour site in one of
    its holes (``enclosed_cells``): the inner edge of a ring. Empty for a shape without
    holes."""
    cells = as_cells(cells)
    holes = {tuple(t) for t in enclosed_cells(cells).tolist()}
    edge = [
        c for c in cells.tolist()
        if any((c[0] + int(dx), c[1] + int(dy)) in holes for dx, dy in NEIGHBOUR_OFFSETS)
    ]
    return sort_cells(np.array(edge, dtype=np.int64).reshape(-1, 2))


def is_connected(cells: np.ndarray) -> bool:
    """True when ``cells`` is non-empty and forms one connected piece on the lattice."""
    cells = as_cells(cells)
    if len(cells) == 0:
        return False
    return int(component_labels(cells).max()) == 0


def triangles(cells: np.ndarray) -> np.ndarray:
    """(T, 3) int64 index triples of the mutually adjacent cell triples in ``cells``.

    Each lattice triangle appears once, anchored at its vertex with the least tag: the "right"
    triangle ``(c, c+(1,0), c+(1,1))`` then the "up" triangle ``(c, c+(1,1), c+(0,1))``, in cell
    order.
    """
    nbr = neighbour_index(cells)
    c = np.arange(len(nbr))
    right = (nbr[:, 2] >= 0) & (nbr[:, 1] >= 0)
    up = (nbr[:, 1] >= 0) & (nbr[:, 0] >= 0)
    tri = np.zeros((2 * len(nbr), 3), dtype=np.int64)
    keep = np.zeros(2 * len(nbr), dtype=bool)
    tri[0::2] = np.stack([c, nbr[:, 2], nbr[:, 1]], axis=1)
    tri[1::2] = np.stack([c, nbr[:, 1], nbr[:, 0]], axis=1)
    keep[0::2] = right
    keep[1::2] = up
    return tri[keep]


def _closure(nbr: list[list[int]], seeds: list[int]) -> list[int]:
    """Indices in the order they can be added from ``seeds`` (seeds first), breadth first.

    A cell is added when two adjacent placed cells are among its neighbours; when cell c is
    placed, its neighbour m in direction k becomes addable if the cell in direction k-1 or k+1
    of c (the two common neighbours of c and m) is placed.
    """
    placed = bytearray(len(nbr))
    order: list[int] = []
    for s in seeds:
        if not placed[s]:
            placed[s] = 1
            order.append(s)
    queue = deque(order)
    while queue:
        c = queue.popleft()
        row = nbr[c]
        for k in range(6):
            m = row[k]
            if m < 0 or placed[m]:
                continue
            a = row[k - 1]
            b = row[(k + 1) % 6]
            if (a >= 0 and placed[a]) or (b >= 0 and placed[b]):
                placed[m] = 1
                order.append(m)
                queue.append(m)
    return order


def _tag_indices(cells: np.ndarray, tags: np.ndarray) -> list[int]:
    index = {(int(x), int(y)): i for i, (x, y) in enumerate(cells.tolist())}
    out = []
    for x, y in np.asarray(tags, dtype=np.int64).reshape(-1, 2).tolist():
        if (x, y) not in index:
            raise ValueError(f"seed tag ({x}, {y}) is not one of the cells")
        out.append(index[(x, y)])
    return out


def construction_order(cells: np.ndarray, seeds: np.ndarray) -> np.ndarray:
    """Tags (K, 2) in an order a swarm can place them, starting from ``seeds`` (3, 2).

    The three seeds come first (they must be mutually adjacent cells of ``cells``); each later
    tag is adjacent to two already-placed tags that are adjacent to each other. The order is
    breadth first from the seeds. ``K < len(cells)`` when some cells can never be added from
    these seeds (see :func:`unconstructible_cells`).
    """
    cells = as_cells(cells)
    seeds = as_cells(seeds)
    if len(seeds) != 3:
        raise ValueError(f"need exactly three seed tags, got {len(seeds)}")
    idx = _tag_indices(cells, seeds)
    s = cells[idx]
    for i in range(3):
        if not are_adjacent(tuple(s[i]), tuple(s[(i + 1) % 3])):
            raise ValueError(f"seed tags {s.tolist()} are not mutually adjacent")
    nbr = neighbour_index(cells).tolist()
    return cells[np.asarray(_closure(nbr, idx), dtype=np.int64)]


class Constructibility:
    """What can be built of a cell set, from which seeds.

    Attributes:
        cells: (P, 2) the analysed tags (as given).
        buildable: (P,) bool, cells in the largest set that some seed triangle can build.
        seed_triangles: (S, 3) int64 indices of the seed triangles that build ``buildable``
            (every mutually adjacent triple whose construction reaches all buildable cells).
        isolated: (P,) bool, cells in no triangle at all (no two adjacent neighbours in the set).
    """

    def __init__(self, cells: np.ndarray) -> None:
        self.cells = as_cells(cells)
        p = len(self.cells)
        nbr = neighbour_index(self.cells).tolist()
        tri = triangles(self.cells)
        in_tri = np.zeros(p, dtype=bool)
        in_tri[tri.ravel()] = True
        self.isolated = ~in_tri
        self.buildable = np.zeros(p, dtype=bool)
        self.seed_triangles = np.zeros((0, 3), dtype=np.int64)
        if len(tri) == 0:
            return
        comp = _triangle_components(self.cells, tri)
        n_comp = int(comp.max()) + 1
        first = np.full(n_comp, -1, dtype=np.int64)
        for t in range(len(tri) - 1, -1, -1):
            first[comp[t]] = t
        # Closure of each component (all its triangles share it). A component whose first
        # triangle lies inside an already computed closure has a closure inside that one; it is
        # only computed later if that closure turns out to be the largest.
        closures: dict[int, np.ndarray] = {}
        dominated: dict[int, int] = {}
        for cid in range(n_comp):
            t0 = tri[first[cid]]
            owner = next((j for j, m in closures.items() if m[t0].all()), None)
            if owner is not None:
                dominated[cid] = owner
                continue
            members = np.zeros(p, dtype=bool)
            members[_closure(nbr, [int(v) for v in t0])] = True
            closures[cid] = members
        best_id = min(closures, key=lambda j: (-int(closures[j].sum()), j))
        best = closures[best_id]
        best_comps = [best_id]
        for cid in range(n_comp):
            if cid == best_id:
                continue
            if cid in closures:
                if np.array_equal(closures[cid], best):
                    best_comps.append(cid)
            elif dominated[cid] == best_id or np.array_equal(closures[dominated[cid]], best):
                members = np.zeros(p, dtype=bool)
                members[_closure(nbr, [int(v) for v in tri[first[cid]]])] = True
                if np.array_equal(members, best):
                    best_comps.append(cid)
        self.buildable = best
        good = np.isin(comp, np.asarray(best_comps, dtype=np.int64))
        self.seed_triangles = tri[good]

    @property
    def constructible(self) -> bool:
        """True when every cell is buildable (and there is at least one triangle)."""
        return bool(len(self.cells) > 0 and self.buildable.all())

    def unbuildable_cells(self) -> np.ndarray:
        """(K, 2) tags no seed choice can reach, in the order of ``cells``."""
        return self.cells[~self.buildable]

    def reason(self, index: int) -> str:
        """Short human reason why cell ``index`` cannot be built."""
        if self.isolated[index]:
            return "no two adjacent neighbours"
        return "not reachable through adjacent neighbour pairs"


def _triangle_components(cells: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """(T,) component id of each triangle; triangles sharing an edge are in one component.

    Triangles sharing an edge build each other, so every triangle of a component has the same
    construction closure.
    """
    parent = list(range(len(tri)))

    def find(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    edge_owner: dict[tuple[int, int], int] = {}
    for t, (a, b, c) in enumerate(tri.tolist()):
        for u, v in ((a, b), (b, c), (a, c)):
            key = (u, v) if u < v else (v, u)
            other = edge_owner.get(key)
            if other is None:
                edge_owner[key] = t
            else:
                ra, rb = find(t), find(other)
                if ra != rb:
                    if ra < rb:
                        parent[rb] = ra
                    else:
                        parent[ra] = rb
    roots = [find(t) for t in range(len(tri))]
    relabel: dict[int, int] = {}
    out = np.empty(len(tri), dtype=np.int64)
    for t, r in enumerate(roots):
        if r not in relabel:
            relabel[r] = len(relabel)
        out[t] = relabel[r]
    return out


def constructibility(cells: np.ndarray) -> Constructibility:
    """Analyse which cells of ``cells`` (P, 2) a swarm can build, and from which seeds."""
    return Constructibility(cells)


def is_constructible(cells: np.ndarray) -> bool:
    """True when some three mutually adjacent cells can seed the construction of all ``cells``."""
    return Constructibility(cells).constructible


def unconstructible_cells(cells: np.ndarray) -> np.ndarray:
    """Tags (K, 2) that can never be added, whichever seed triangle is chosen.

    The seed triangle that builds the most cells is assumed; the cells it cannot reach are
    returned (in the order of ``cells``). Empty when the set is constructible. A set with no
    triangle at all returns every cell.
    """
    return Constructibility(cells).unbuildable_cells()


def seed_triangles(cells: np.ndarray) -> np.ndarray:
    """(S, 3, 2) tags of every mutually adjacent triple from which all buildable cells follow."""
    an = Constructibility(cells)
    return an.cells[an.seed_triangles]
