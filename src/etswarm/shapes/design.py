"""How the library shapes are drawn: geometric figures rasterised on the skewed lattice.

Each figure is a predicate on the lattice positions ``x = X − Y/2``, ``y = Y·√3/2`` (units of
the spacing d), so the shapes look right where robots stand; the bitmap rows then slant in the
text file. Run ``python -m etswarm.shapes.design [FOLDER]`` to rewrite the library files
(default: the package's ``library`` folder); the tests check the files match this module.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np

Pred = Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
"""(x, y, Y) arrays -> bool array: inside the figure."""

_S = math.sqrt(3.0) / 2.0
_EPS = 1e-9


def band(y_rows: tuple[int, int], x_from: float, x_to: float) -> Pred:
    """Rows ``Y`` in [y_rows[0], y_rows[1]] with ``x_from <= x < x_to`` (same count each row
    when the width is an integer)."""
    return lambda x, y, Y: (y_rows[0] <= Y) & (y_rows[1] >= Y) & (x >= x_from) & (x < x_to)


def disc(cx: float, cy: float, r: float) -> Pred:
    """Points within distance ``r`` of (cx, cy)."""
    return lambda x, y, Y: (x - cx) ** 2 + (y - cy) ** 2 <= r * r + _EPS


def ring(cx: float, cy: float, r_in: float, r_out: float) -> Pred:
    """Points with r_in < distance <= r_out from (cx, cy)."""
    return lambda x, y, Y: disc(cx, cy, r_out)(x, y, Y) & ~disc(cx, cy, r_in)(x, y, Y)


def polygon(points: list[tuple[float, float]]) -> Pred:
    """Points inside or on the convex polygon with counter-clockwise ``points``."""
    pts = [(float(a), float(b)) for a, b in points]

    def inside(x: np.ndarray, y: np.ndarray, Y: np.ndarray) -> np.ndarray:
        ok = np.ones(np.shape(x), dtype=bool)
        for (x1, y1), (x2, y2) in zip(pts, pts[1:] + pts[:1], strict=True):
            ok &= (x2 - x1) * (y - y1) - (y2 - y1) * (x - x1) >= -_EPS
        return ok

    return inside


def arm(angle_deg: float, r0: float, length: float, w0: float, w1: float) -> Pred:
    """A tapered arm from radius r0 outwards: width w0 at its base, w1 at its tip."""
    a = math.radians(angle_deg)
    u = (math.cos(a), math.sin(a))
    v = (-u[1], u[0])
    r1 = r0 + length

    def at(r: float, w: float) -> tuple[tuple[float, float], tuple[float, float]]:
        return (
            (u[0] * r - v[0] * w / 2, u[1] * r - v[1] * w / 2),
            (u[0] * r + v[0] * w / 2, u[1] * r + v[1] * w / 2),
        )

    b_right, b_left = at(r0, w0)
    t_right, t_left = at(r1, w1)
    return polygon([b_right, t_right, t_left, b_left])


def union(*preds: Pred) -> Pred:
    """Inside any of ``preds``."""
    def inside(x: np.ndarray, y: np.ndarray, Y: np.ndarray) -> np.ndarray:
        out = np.zeros(np.shape(x), dtype=bool)
        for p in preds:
            out |= p(x, y, Y)
        return out

    return inside


def rasterise(pred: Pred, reach: int = 40) -> np.ndarray:
    """(H, W) bool bitmap (row 0 = top) of the lattice sites inside ``pred``, cropped tight."""
    X, Y = np.meshgrid(np.arange(-reach, reach + 1), np.arange(-reach, reach + 1), indexing="ij")
    x = X - Y / 2.0
    y = Y * _S
    inside = pred(x, y, Y)
    xs, ys = X[inside], Y[inside]
    grid = np.zeros((ys.max() - ys.min() + 1, xs.max() - xs.min() + 1), dtype=bool)
    grid[ys.max() - ys, xs - xs.min()] = True
    return grid


def _star() -> Pred:
    arms = [arm(90 + 72 * k, 1.5, 5.4, 3.2, 2.2) for k in range(5)]
    return union(disc(0, 0, 2.6), *arms)


#: name -> (description, figure). The paper's three shapes come first.
DESIGNS: dict[str, tuple[str, Pred]] = {
    "T": (
        "paper's T: 9-wide, 3-row bar on a 3-wide, 6-row stem",
        union(band((6, 8), -4.5, 4.5), band((0, 5), -1.5, 1.5)),
    ),
    "dumbbell": (
        "paper's dumbbell: two round blobs joined by a 2-row bar",
        union(disc(-4.6, 0.43, 2.7), disc(4.6, 0.43, 2.7), band((0, 1), -4.5, 4.5)),
    ),
    "starfish": ("paper's starfish: round body with five tapering arms", _star()),
    "triangle": ("equilateral triangle, side 5", polygon([(-2.01, -0.01), (2.01, -0.01),
                                                          (0, 4 * _S + 0.01)])),
    "hexagon": ("regular hexagon, 4 cells a side", lambda x, y, Y: _hex(x, y, Y, 3)),
    "square": ("square, 6 cells a side", band((0, 6), -3.0, 3.0)),
    "disc": ("disc, radius 3.7 spacings", disc(0, 0, 3.7)),
    "L": ("letter L, strokes 2 wide", union(band((0, 10), -3.0, -1.0), band((0, 1), -3.0, 3.0))),
    "E": (
        "letter E, strokes 2 wide",
        union(
            band((0, 11), -3.0, -1.0),
            band((0, 1), -3.0, 3.0),
            band((5, 6), -3.0, 2.0),
            band((10, 11), -3.0, 3.0),
        ),
    ),
    "H": (
        "letter H, strokes 2 wide",
        union(band((0, 10), -3.5, -1.5), band((0, 10), 1.5, 3.5), band((5, 6), -3.5, 3.5)),
    ),
    "plus": ("plus sign, bars 3 wide", union(band((-1, 1), -4.5, 4.5), band((-5, 5), -1.5, 1.5))),
    "arrow": (
        "arrow pointing right: 3-row shaft and a triangular head",
        union(band((-1, 1), -6.0, 0.0), polygon([(0.0, -3.3), (3.9, 0.0), (0.0, 3.3)])),
    ),
    "heart": (
        "heart: two lobes over a point",
        union(
            disc(-2.2, 1.4, 2.3),
            disc(2.2, 1.4, 2.3),
            polygon([(-4.55, 1.4), (0.0, -4.3), (4.55, 1.4)]),
        ),
    ),
    "O": (
        (
            "hollow ring; the paper reports hollow shapes FAIL; here the hole rules form it in"
            " about 93% of runs (299 of 320, session 73)"
        ),
        ring(0, 0, 2.2, 4.6),
    ),
    "bigdisc": (
        "large disc, radius 10 spacings; does not form yet: its lattice drifts as it grows",
        disc(0, 0, 10.0),
    ),
    "bigplus": (
        "large plus sign, bars 3 wide and 55 long; use --layout cluster",
        union(band((-1, 1), -24.0, 24.0), band((-27, 27), -1.5, 1.5)),
    ),
    "bigH": (
        "large letter H, strokes 3 wide, 41 rows tall; use --layout cluster",
        union(band((-20, 20), -15.5, -12.5), band((-20, 20), 12.5, 15.5),
              band((-1, 1), -12.5, 12.5)),
    ),
}


def _hex(x: np.ndarray, y: np.ndarray, Y: np.ndarray, r: int) -> np.ndarray:
    X = np.rint(x + Y / 2.0)
    return np.maximum(np.maximum(np.abs(X), np.abs(Y)), np.abs(X - Y)) <= r


def library_text(name: str) -> str:
    """The text file content of design ``name``: a ``;`` description line, then ``.``/``#``."""
    description, pred = DESIGNS[name]
    grid = rasterise(pred)
    rows = ["".join("#" if v else "." for v in row) for row in grid]
    return f"; {description}\n" + "\n".join(rows) + "\n"


def write_library(folder: Path) -> list[Path]:
    """Write every design to ``folder/<name>.txt``; return the paths."""
    folder.mkdir(parents=True, exist_ok=True)
    out = []
    for name in DESIGNS:
        path = folder / f"{name}.txt"
        path.write_text(library_text(name), encoding="utf-8")
        out.append(path)
    return out


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent / "library"
    for p in write_library(target):
        print(p)
