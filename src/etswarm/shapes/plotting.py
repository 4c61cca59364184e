"""Pictures of shapes: the bitmap beside its skewed lattice (paper Fig. 3), scaled shapes.

Uses matplotlib's object API with the Agg canvas directly, so importing this module never
changes the global matplotlib backend.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PatchCollection
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Rectangle, RegularPolygon

from etswarm.shapes.gene import scaled_gene
from etswarm.shapes.lattice import as_cells, tags_to_xy
from etswarm.shapes.scale import scale
from etswarm.shapes.shape import Shape

_INSIDE = "#3b7dd8"
_OUTSIDE = "#eeeeee"
_ORIGIN = "#d62728"


def _font_size(n_pixels: int) -> float:
    return float(np.clip(150.0 / np.sqrt(max(n_pixels, 1)), 3.0, 11.0))


def _draw_bitmap(ax: Axes, shape: Shape) -> None:
    b = shape.bitmap
    h, w = b.shape
    nn = shape.gene().nn.reshape(w, h)[:, ::-1].T  # back to (H, W) pixel layout
    patches = [Rectangle((j, h - 1 - i), 1, 1) for i in range(h) for j in range(w)]
    colours = [_INSIDE if b[i, j] else _OUTSIDE for i in range(h) for j in range(w)]
    ax.add_collection(
        PatchCollection(patches, facecolors=colours, edgecolors="#999999", linewidths=0.3)
    )
    fs = _font_size(h * w)
    for i in range(h):
        for j in range(w):
            ax.text(j + 0.5, h - 0.5 - i, str(nn[i, j]), ha="center", va="center",
                    fontsize=fs, color="white" if b[i, j] else "#888888")
    row0, col0 = shape.origin
    ax.add_patch(Rectangle((col0, h - 1 - row0), 1, 1, fill=False, edgecolor=_ORIGIN,
                           linewidth=2.0))
    ax.set_xlim(0, w)
    ax.set_ylim(0, h)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(f"bitmap {w}x{h} (Cartesian)")


def _draw_lattice(ax: Axes, x: np.ndarray, y: np.ndarray, flag: np.ndarray, nn: np.ndarray | None,
                  title: str, origin: bool = True) -> None:
    xy = tags_to_xy(np.stack([x, y], axis=1), 1.0)
    cells = [RegularPolygon((px, py), 6, radius=1 / np.sqrt(3)) for px, py in xy]
    colours = [_INSIDE if f else _OUTSIDE for f in flag]
    ax.add_collection(PatchCollection(cells, facecolors=colours, edgecolors="white",
                                      linewidths=0.6))
    if nn is not None:
        fs = _font_size(len(xy))
        for (px, py), f, k in zip(xy, flag, nn, strict=True):
            ax.text(px, py, str(int(k)), ha="center", va="center", fontsize=fs,
                    color="white" if f else "#888888")
    if origin:
        ax.add_patch(Circle((0, 0), 0.45, fill=False, edgecolor=_ORIGIN, linewidth=2.0))
    pad = 1.0
    ax.set_xlim(xy[:, 0].min() - pad, xy[:, 0].max() + pad)
    ax.set_ylim(xy[:, 1].min() - pad, xy[:, 1].max() + pad)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(title)


def _save(fig: Figure, path: str | Path) -> Path:
    path = Path(path)
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    return path


def _figsize(aspect: float) -> tuple[float, float]:
    """(width, height) inches for panels whose widths over height sum to ``aspect``."""
    width = float(np.clip(4.5 * aspect, 6.0, 16.0))
    height = float(np.clip(width / aspect, 2.5, 8.0)) + 0.8
    return width, height


def plot_gene(shape: Shape, path: str | Path) -> Path:
    """Draw the bitmap and its skewed lattice side by side, NN in each cell, origin in red."""
    g = shape.gene()
    h, w = shape.size
    xy = tags_to_xy(np.stack([g.x, g.y], axis=1), 1.0)
    lat_w, lat_h = np.ptp(xy[:, 0]) + 2.0, np.ptp(xy[:, 1]) + 2.0
    fig = Figure(figsize=_figsize(w / h + lat_w / lat_h))
    ax_b, ax_l = fig.subplots(1, 2, width_ratios=[w / h, lat_w / lat_h])
    _draw_bitmap(ax_b, shape)
    _draw_lattice(ax_l, g.x, g.y, g.flag, g.nn, "skewed triangular lattice (robots)")
    fig.suptitle(f"{shape.name}: {shape.n_cells} cells; NN in each cell, origin (0,0) in red")
    return _save(fig, path)


def plot_cells(cells: np.ndarray, path: str | Path, title: str = "") -> Path:
    """Draw a cell set (P, 2) on the lattice with each cell's NN within the set."""
    g = scaled_gene(as_cells(cells))
    fig = Figure(figsize=(6, 6))
    ax = fig.subplots(1, 1)
    keep = g.flag == 1
    _draw_lattice(ax, g.x[keep], g.y[keep], g.flag[keep], g.nn[keep], title, origin=False)
    return _save(fig, path)


def plot_scaled(shape: Shape, n: int, path: str | Path) -> Path:
    """Draw the original shape and ``scale(shape, n)`` side by side on the same lattice frame."""
    small = scale(shape, n)
    g = scaled_gene(small)
    fig = Figure(figsize=(12, 6))
    ax_o, ax_s = fig.subplots(1, 2)
    cells = shape.cells
    ones = np.ones(len(cells), dtype=np.int64)
    _draw_lattice(ax_o, cells[:, 0], cells[:, 1], ones, None, f"original: {shape.n_cells} cells")
    keep = g.flag == 1
    _draw_lattice(ax_s, g.x[keep], g.y[keep], g.flag[keep], g.nn[keep], f"scaled: {n} cells (NN)")
    ax_s.set_xlim(ax_o.get_xlim())
    ax_s.set_ylim(ax_o.get_ylim())
    fig.suptitle(f"{shape.name} scaled from {shape.n_cells} to {n} cells")
    return _save(fig, path)
