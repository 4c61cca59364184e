"""Scaled-down shapes: ``scale(bitmap, n)`` gives n cells in the form of the original.

Method (deterministic, exact where it matters):

1. *Signed distance field* of the original, on the lattice sites of its bounding box padded by
   two: ``+dist`` to the nearest outside site for inside sites, ``−dist`` to the nearest inside
   site for outside sites. Squared lattice distances are integers (``dX² − dX·dY + dY²``), so
   the field is exact up to one correctly rounded square root. Cached per bitmap.
2. *Geometric shrink*: with ``s = √(n/N)`` and ``c`` the centroid of the original's tags, every
   candidate site ``p`` is scored by the field, linearly interpolated on the lattice triangle
   holding its pre-image ``c + (p − c)/s``. Sites are ranked by score; ties by the exact
   (integer) squared distance to the centroid, then by (X, Y).
3. *Constructible growth*: the ``n`` best-ranked sites are the target. From the best-ranked
   site and its best-ranked adjacent pair (a seed triangle), repeatedly add a site that touches
   two adjacent placed sites: a target site if one can be added (best rank first), else a
   "bridge" site next to an unplaced target site (so a one-site-wide arm of the target is
   widened to two and kept), else the best-ranked site. Stop at n sites. The result is
   connected, constructible, has exactly n cells and approximates the original shrunk by
   ``s`` about its centroid.

Everything uses correctly rounded IEEE operations (integer sums, ``+ − × ÷ √``, comparisons),
integer tie-breaks and no set or dict iteration order; no transcendental functions and no
floating-point reductions. Same (bitmap, n) gives the same cells on every machine.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.shapes.gene import bitmap_cells
from etswarm.shapes.lattice import is_connected, is_constructible, tags_to_xy, xy_to_nearest_tag

#: Padding (lattice sites) of the distance field around the original's bounding box.
_PAD = 2
#: Extra candidate sites around the scaled bounding box.
_MARGIN = 3
_OFFSETS = ((0, 1), (1, 1), (1, 0), (0, -1), (-1, -1), (-1, 0))


@dataclass(frozen=True)
class DistanceField:
    """Signed lattice distance field of a shape.

    Attributes:
        x0, y0: tag of ``values[0, 0]``.
        values: (NX, NY) float64, signed distance (units of d) indexed ``[X − x0, Y − y0]``.
        cx, cy: centroid of the shape's tags (float).
        n_cells: number of cells N of the shape.
        cells: (N, 2) int64 tags of the shape, sorted by (X, Y).
        whole_ok: True when the original itself is connected and constructible.
    """

    x0: int
    y0: int
    values: np.ndarray
    cx: float
    cy: float
    n_cells: int
    cells: np.ndarray
    whole_ok: bool


def _bitmap_of(shape_or_bitmap: object) -> tuple[np.ndarray, str]:
    bitmap = getattr(shape_or_bitmap, "bitmap", shape_or_bitmap)
    name = getattr(shape_or_bitmap, "name", "bitmap")
    b = np.ascontiguousarray(np.asarray(bitmap, dtype=bool))
    if b.ndim != 2:
        raise ValueError(f"bitmap must be 2-D, got shape {b.shape}")
    return b, str(name)


def distance_field(bitmap: np.ndarray) -> DistanceField:
    """The (cached) :class:`DistanceField` of an (H, W) bool bitmap."""
    b = np.ascontiguousarray(np.asarray(bitmap, dtype=bool))
    return _field_cached(b.tobytes(), b.shape[0], b.shape[1])


@lru_cache(maxsize=64)
def _field_cached(key: bytes, h: int, w: int) -> DistanceField:
    bitmap = np.frombuffer(key, dtype=bool).reshape(h, w)
    cells = bitmap_cells(bitmap)
    if len(cells) == 0:
        raise EtswarmError("scale: the bitmap has no 1s")
    lo = cells.min(axis=0) - _PAD
    hi = cells.max(axis=0) + _PAD
    nx, ny = int(hi[0] - lo[0]) + 1, int(hi[1] - lo[1]) + 1
    inside = np.zeros((nx, ny), dtype=bool)
    inside[cells[:, 0] - lo[0], cells[:, 1] - lo[1]] = True
    # boundary sites: a site with a neighbour of the other class
    pad = np.zeros((nx + 2, ny + 2), dtype=bool)
    pad[1:-1, 1:-1] = inside
    any_in = np.zeros((nx, ny), dtype=bool)
    any_out = np.zeros((nx, ny), dtype=bool)
    for ox, oy in _OFFSETS:
        nb = pad[1 + ox : nx + 1 + ox, 1 + oy : ny + 1 + oy]
        any_in |= nb
        any_out |= ~nb
    in_edge = np.argwhere(inside & any_out)  # inside sites touching outside
    out_edge = np.argwhere(~inside & any_in)  # outside sites touching inside
    sites = np.argwhere(np.ones((nx, ny), dtype=bool))  # (nx*ny, 2), row-major
    best = np.empty(len(sites), dtype=np.int64)
    flat_inside = inside.ravel()
    for targets, mask in ((out_edge, flat_inside), (in_edge, ~flat_inside)):
        idx = np.flatnonzero(mask)
        chunk = max(1, 2_000_000 // max(len(targets), 1))
        for start in range(0, len(idx), chunk):
            part = idx[start : start + chunk]
            d = sites[part, None, :] - targets[None, :, :]
            dx, dy = d[..., 0], d[..., 1]
            best[part] = (dx * dx - dx * dy + dy * dy).min(axis=1)
    values = np.sqrt(best.astype(np.float64))
    values = np.where(flat_inside, values, -values).reshape(nx, ny)
    values.setflags(write=False)
    n = len(cells)
    cx = int(cells[:, 0].sum()) / n
    cy = int(cells[:, 1].sum()) / n
    cells.setflags(write=False)
    whole_ok = is_connected(cells) and is_constructible(cells)
    return DistanceField(int(lo[0]), int(lo[1]), values, cx, cy, n, cells, whole_ok)


def _scores(field: DistanceField, px: np.ndarray, py: np.ndarray, inv_s: float) -> np.ndarray:
    """Field value at the pre-images of candidate tags (px, py), float64 arrays of equal shape."""
    a = field.cx + (px - field.cx) * inv_s - field.x0
    b = field.cy + (py - field.cy) * inv_s - field.y0
    nx, ny = field.values.shape
    ac = np.clip(a, 0.0, nx - 1.0)
    bc = np.clip(b, 0.0, ny - 1.0)
    ex, ey = a - ac, b - bc
    beyond = np.sqrt(ex * ex - ex * ey + ey * ey)  # distance outside the field box
    i = np.minimum(np.floor(ac), nx - 2.0).astype(np.int64)
    j = np.minimum(np.floor(bc), ny - 2.0).astype(np.int64)
    fa, fb = ac - i, bc - j
    v = field.values
    v00, v11 = v[i, j], v[i + 1, j + 1]
    # the unit cell splits along its (1,1) diagonal, a lattice edge
    lower = fa >= fb  # triangle (i,j) (i+1,j) (i+1,j+1)
    v_mid = np.where(lower, v[i + 1, j], v[i, j + 1])
    w00 = np.where(lower, 1.0 - fa, 1.0 - fb)
    w_mid = np.where(lower, fa - fb, fb - fa)
    w11 = np.where(lower, fb, fa)
    return v00 * w00 + v_mid * w_mid + v11 * w11 - beyond


def scale(shape_or_bitmap: object, n: int) -> np.ndarray:
    """The shape scaled down to exactly ``n`` cells: int64 (n, 2) tags sorted by (X, Y).

    ``shape_or_bitmap`` is a :class:`~etswarm.shapes.Shape` or an (H, W) bool bitmap. The
    result lies in the original's tag frame, shrunk about the original's centroid, and is
    connected and constructible. ``n`` must satisfy ``3 <= n <= N`` (N = cells of the
    original); otherwise EtswarmError. ``n == N`` returns the original cells when they are
    themselves connected and constructible. Pure and deterministic (see module docstring).
    """
    bitmap, name = _bitmap_of(shape_or_bitmap)
    n_total = int(bitmap.sum())
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise EtswarmError(f"scale: N must be an integer, got {n!r}")
    n = int(n)
    if not 3 <= n <= n_total:
        if n_total < 3:
            raise EtswarmError(f"scale: shape {name!r} has {n_total} cells, fewer than 3")
        raise EtswarmError(
            f"scale: N = {n} is out of range for shape {name!r}: choose 3 <= N <= {n_total}"
        )
    out = _scale_cached(bitmap.tobytes(), bitmap.shape[0], bitmap.shape[1], n)
    return out.copy()


@lru_cache(maxsize=256)
def _scale_cached(key: bytes, h: int, w: int, n: int) -> np.ndarray:
    field = _field_cached(key, h, w)
    if n == field.n_cells and field.whole_ok:
        return field.cells.copy()
    return _grow(field, n)


def _grow(field: DistanceField, n: int) -> np.ndarray:
    big_n = field.n_cells
    s = math.sqrt(n / big_n)
    inv_s = math.sqrt(big_n / n)
    nx, ny = field.values.shape
    # candidate tag box: the field box mapped forward, plus a margin
    xs = (field.cx + (field.x0 - field.cx) * s, field.cx + (field.x0 + nx - 1 - field.cx) * s)
    ys = (field.cy + (field.y0 - field.cy) * s, field.cy + (field.y0 + ny - 1 - field.cy) * s)
    X0, X1 = math.floor(xs[0]) - _MARGIN, math.ceil(xs[1]) + _MARGIN
    Y0, Y1 = math.floor(ys[0]) - _MARGIN, math.ceil(ys[1]) + _MARGIN
    kx, ky = X1 - X0 + 1, Y1 - Y0 + 1
    PX, PY = np.meshgrid(
        np.arange(X0, X1 + 1, dtype=np.int64), np.arange(Y0, Y1 + 1, dtype=np.int64), indexing="ij"
    )
    px, py = PX.ravel(), PY.ravel()
    score = _scores(field, px.astype(np.float64), py.astype(np.float64), inv_s)
    # best score first; ties (symmetric sites) by exact squared distance to the centroid, so
    # equally good sites are taken evenly around the shape, then by (X, Y)
    sx, sy = int(field.cells[:, 0].sum()), int(field.cells[:, 1].sum())
    ex, ey = px * big_n - sx, py * big_n - sy
    centre_d2 = ex * ex - ex * ey + ey * ey
    order = np.lexsort((py, px, centre_d2, -score))
    # padded grid (kx+2, ky+2): border sites have rank -1 and are never placed
    stride = ky + 2
    flat = (px - X0 + 1) * stride + (py - Y0 + 1)
    rank = np.full((kx + 2) * stride, -1, dtype=np.int64)
    rank[flat[order]] = np.arange(len(order), dtype=np.int64)
    rank_l = rank.tolist()
    by_rank = flat[order].tolist()
    off = [ox * stride + oy for ox, oy in _OFFSETS]
    placed = bytearray(len(rank_l))
    pushed = bytearray(len(rank_l))
    heap: list[tuple[int, int]] = []  # (tier, rank); see tier()

    def tier(c: int) -> int:
        """0: a target site (rank < n); 1: a bridge, next to an unplaced target site; 2: other.
        A site's tier only ever gets worse as sites are placed."""
        if rank_l[c] < n:
            return 0
        for o in off:
            m = c + o
            if 0 <= rank_l[m] < n and not placed[m]:
                return 1
        return 2

    def place(c: int) -> None:
        placed[c] = 1
        for k in range(6):
            m = c + off[k]
            if rank_l[m] < 0 or placed[m] or pushed[m]:
                continue
            if placed[c + off[k - 1]] or placed[c + off[(k + 1) % 6]]:
                pushed[m] = 1
                heapq.heappush(heap, (tier(m), rank_l[m]))

    c0 = by_rank[0]
    best_pair: tuple[int, int, int, int] | None = None
    for k in range(6):
        a, b = c0 + off[k], c0 + off[(k + 1) % 6]
        ra, rb = rank_l[a], rank_l[b]
        if ra < 0 or rb < 0:
            continue
        key = (max(ra, rb), min(ra, rb), a, b)
        if best_pair is None or key < best_pair:
            best_pair = key
    if best_pair is None:  # pragma: no cover - candidate box always has a margin
        raise RuntimeError("scale: no seed triangle among the candidates")
    for c in (c0, best_pair[2], best_pair[3]):
        place(c)
    count = 3
    while count < n:
        if not heap:  # pragma: no cover - the candidate box is far larger than n
            raise RuntimeError("scale: ran out of candidate sites")
        t, r = heapq.heappop(heap)
        c = by_rank[r]
        if placed[c]:
            continue
        now = tier(c)
        if now != t:  # got worse since pushed: requeue (lazy update)
            heapq.heappush(heap, (now, r))
            continue
        place(c)
        count += 1
    chosen = np.flatnonzero(np.frombuffer(bytes(placed), dtype=np.uint8))  # (X, Y) order
    out = np.empty((len(chosen), 2), dtype=np.int64)
    out[:, 0] = chosen // stride - 1 + X0
    out[:, 1] = chosen % stride - 1 + Y0
    return out


def _nearest_site_shrink(field: DistanceField, s: float) -> np.ndarray:
    """Sites whose pre-image under the shrink by ``s`` about the centroid has its nearest
    lattice site inside the original (the original's Voronoi region, shrunk)."""
    nx, ny = field.values.shape
    X0 = math.floor(field.cx + (field.x0 - field.cx) * s) - 1
    X1 = math.ceil(field.cx + (field.x0 + nx - 1 - field.cx) * s) + 1
    Y0 = math.floor(field.cy + (field.y0 - field.cy) * s) - 1
    Y1 = math.ceil(field.cy + (field.y0 + ny - 1 - field.cy) * s) + 1
    PX, PY = np.meshgrid(np.arange(X0, X1 + 1), np.arange(Y0, Y1 + 1), indexing="ij")
    p = np.stack([PX.ravel(), PY.ravel()], axis=1).astype(np.int64)
    q = np.empty((len(p), 2), dtype=np.float64)
    q[:, 0] = field.cx + (p[:, 0] - field.cx) / s
    q[:, 1] = field.cy + (p[:, 1] - field.cy) / s
    site = xy_to_nearest_tag(tags_to_xy(q, 1.0), 1.0) - (field.x0, field.y0)
    ok = (site[:, 0] >= 0) & (site[:, 0] < nx) & (site[:, 1] >= 0) & (site[:, 1] < ny)
    keep = np.zeros(len(p), dtype=bool)
    keep[ok] = field.values[site[ok, 0], site[ok, 1]] > 0
    return p[keep]


def geometric_shrink(shape_or_bitmap: object, n: int) -> np.ndarray:
    """Reference for quality measures: the original's region (union of its cells' hexagons)
    shrunk about its centroid, sampled at lattice sites, with the factor chosen (bisection)
    so the site count is as close to ``n`` as possible. (K, 2) int64 tags sorted by (X, Y);
    K is close to ``n`` and the set need be neither connected nor constructible."""
    bitmap, _ = _bitmap_of(shape_or_bitmap)
    field = distance_field(bitmap)
    lo, hi = 0.0, 1.0
    best = _nearest_site_shrink(field, 1.0)
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        cand = _nearest_site_shrink(field, mid)
        if abs(len(cand) - n) < abs(len(best) - n):
            best = cand
        if len(cand) == n:
            break
        if len(cand) < n:
            lo = mid
        else:
            hi = mid
    return best
