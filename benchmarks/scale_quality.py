"""How close are scaled shapes to the original's form, and how fast is scale()?

For every library shape at n = 75 %, 50 %, 25 % of its cells, prints the Jaccard overlap
between ``scale(shape, n)`` and the original shrunk geometrically to about n sites
(:func:`etswarm.shapes.scale.geometric_shrink`, best placement over integer translations),
next to the paper's method (delete boundary 1s one at a time, skipping deletions that would
leave the shape disconnected or unconstructible). Then times scale() without its cache.

Run: ``.venv/bin/python benchmarks/scale_quality.py``
"""

from __future__ import annotations

import time

import numpy as np

from etswarm.shapes import LIBRARY_NAMES, load_shape, scale
from etswarm.shapes.design import disc, rasterise
from etswarm.shapes.lattice import is_connected, is_constructible, neighbour_counts
from etswarm.shapes.scale import _field_cached, _scale_cached, geometric_shrink
from etswarm.shapes.shape import shape_from_bitmap

FRACTIONS = (0.75, 0.50, 0.25)


def jaccard_best_shift(a: np.ndarray, b: np.ndarray, reach: int = 3) -> float:
    """max over integer translations t (|t| <= reach) of |a ∩ (b+t)| / |a ∪ (b+t)|."""
    sa = {tuple(t) for t in a.tolist()}
    best = 0.0
    for dx in range(-reach, reach + 1):
        for dy in range(-reach, reach + 1):
            sb = {(x + dx, y + dy) for x, y in b.tolist()}
            inter = len(sa & sb)
            best = max(best, inter / (len(sa) + len(sb) - inter))
    return best


def peel(cells: np.ndarray, n: int) -> np.ndarray:
    """The paper's scaling: delete boundary cells one by one (fewest neighbours first, then
    farthest from the centroid), skipping deletions that break connectivity or
    constructibility."""
    cur = cells.copy()
    while len(cur) > n:
        nn = neighbour_counts(cur)
        total = cur.sum(axis=0)
        d = cur * len(cur) - total
        dist2 = d[:, 0] ** 2 - d[:, 0] * d[:, 1] + d[:, 1] ** 2
        boundary = np.flatnonzero(nn < 6)
        order = boundary[np.lexsort((cur[boundary, 1], cur[boundary, 0], -dist2[boundary],
                                     nn[boundary]))]
        for i in order:
            rest = np.delete(cur, i, axis=0)
            if is_connected(rest) and is_constructible(rest):
                cur = rest
                break
        else:
            break  # stuck: no boundary cell can go
    return cur


def quality_table() -> list[tuple[str, int, int, int, float, float]]:
    rows = []
    for name in LIBRARY_NAMES:
        shape = load_shape(name)
        big_n = shape.n_cells
        for frac in FRACTIONS:
            n = max(3, round(frac * big_n))
            ref = geometric_shrink(shape, n)
            ours = scale(shape, n)
            paper = peel(shape.cells, n)
            rows.append((name, big_n, n, len(ref), jaccard_best_shift(ref, ours),
                         jaccard_best_shift(ref, paper) if len(paper) == n else float("nan")))
    return rows


def time_scale(shape, fractions=(0.25, 0.5, 0.75, 0.9)) -> float:
    """Mean ms per scale() call, caches cleared before each (includes the distance field)."""
    times = []
    for frac in fractions:
        n = max(3, round(frac * shape.n_cells))
        _scale_cached.cache_clear()
        _field_cached.cache_clear()
        t0 = time.perf_counter()
        scale(shape, n)
        times.append(time.perf_counter() - t0)
    return 1e3 * float(np.mean(times))


def time_scale_warm(shape, fractions=(0.25, 0.5, 0.75, 0.9)) -> float:
    """Mean ms per scale() call for new n with the distance field already cached."""
    times = []
    for frac in fractions:
        n = max(3, round(frac * shape.n_cells))
        _scale_cached.cache_clear()
        t0 = time.perf_counter()
        scale(shape, n)
        times.append(time.perf_counter() - t0)
    return 1e3 * float(np.mean(times))


def main() -> None:
    print("Jaccard with the geometric shrink (best integer translation)")
    print(f"{'shape':10s} {'N':>5s} {'n':>5s} {'|ref|':>5s} {'scale()':>8s} {'peel':>6s}")
    rows = quality_table()
    for name, big_n, n, k, j_ours, j_peel in rows:
        print(f"{name:10s} {big_n:5d} {n:5d} {k:5d} {j_ours:8.3f} {j_peel:6.3f}")
    ours = np.array([r[4] for r in rows])
    paper = np.array([r[5] for r in rows])
    print(f"{'mean':10s} {'':5s} {'':5s} {'':5s} {ours.mean():8.3f} {np.nanmean(paper):6.3f}")
    print()
    print("scale() time, ms per call (cold: distance field included; warm: field cached)")
    extra = {
        "disc1000": shape_from_bitmap(rasterise(disc(0, 0, 16.6), reach=30), "disc1000"),
        "disc3000": shape_from_bitmap(rasterise(disc(0, 0, 28.8), reach=40), "disc3000"),
    }
    for name, shape in [(n, load_shape(n)) for n in ("T", "starfish", "bigdisc")] + list(
        extra.items()
    ):
        print(f"{name:10s} N={shape.n_cells:5d}  cold {time_scale(shape):7.2f}  "
              f"warm {time_scale_warm(shape):7.2f}")


if __name__ == "__main__":
    main()
