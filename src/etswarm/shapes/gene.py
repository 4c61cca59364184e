"""The gene: one row (X, Y, F, NN) per pixel, and dense lookup grids for controllers.

DESIGN §1: origin at the central pixel ``row0 = (H-1)//2``, ``col0 = (W-1)//2``; tag
``X = j - col0``, ``Y = row0 - i``; NN counts the 1s among the six lattice neighbours
``(i-1,j) (i-1,j+1) (i,j+1) (i+1,j) (i+1,j-1) (i,j-1)``; rows sorted by (X, Y).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from etswarm.shapes.lattice import as_cells


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class Gene:
    """A gene table; every field is an (M,) int64 array, rows sorted by (X, Y).

    Attributes:
        x, y: the tag of each pixel.
        flag: 1 inside the shape, 0 outside.
        nn: number of 1s among the six lattice neighbours (0..6).
    """

    x: np.ndarray
    y: np.ndarray
    flag: np.ndarray
    nn: np.ndarray

    def __post_init__(self) -> None:
        for name in ("x", "y", "flag", "nn"):
            object.__setattr__(self, name, _frozen(np.asarray(getattr(self, name), np.int64)))

    def __len__(self) -> int:
        return len(self.x)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Gene):
            return NotImplemented
        return all(
            np.array_equal(getattr(self, k), getattr(other, k)) for k in ("x", "y", "flag", "nn")
        )

    __hash__ = None  # type: ignore[assignment]

    def as_array(self) -> np.ndarray:
        """(M, 4) int64 columns X, Y, F, NN."""
        return np.stack([self.x, self.y, self.flag, self.nn], axis=1)

    def records(self) -> list[dict[str, int]]:
        """The rows as ``{"x", "y", "flag", "nn"}`` dicts of Python ints (JSON-ready)."""
        return [
            {"x": x, "y": y, "flag": f, "nn": n}
            for x, y, f, n in self.as_array().tolist()
        ]

    def cells(self) -> np.ndarray:
        """(P, 2) tags of the rows with flag 1, sorted by (X, Y)."""
        keep = self.flag == 1
        return np.stack([self.x[keep], self.y[keep]], axis=1)


@dataclass(frozen=True, eq=False)
class GeneGrid:
    """Dense gene lookup for array code (numba): index ``[X - x0, Y - y0]``.

    Attributes:
        x0, y0: tag of index ``[0, 0]`` (the least X and least Y of the gene).
        flag: (NX, NY) int8, 1 inside the shape; tags outside the grid count as 0.
        nn: (NX, NY) int8, the NN of each tag.
    """

    x0: int
    y0: int
    flag: np.ndarray
    nn: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.flag.shape[0]), int(self.flag.shape[1]))

    def contains(self, x: int, y: int) -> bool:
        """True when tag (x, y) lies on the grid."""
        i, j = x - self.x0, y - self.y0
        return 0 <= i < self.flag.shape[0] and 0 <= j < self.flag.shape[1]

    def flag_at(self, x: int, y: int) -> int:
        """Flag of tag (x, y); 0 off the grid."""
        return int(self.flag[x - self.x0, y - self.y0]) if self.contains(x, y) else 0

    def nn_at(self, x: int, y: int) -> int:
        """NN of tag (x, y); 0 off the grid."""
        return int(self.nn[x - self.x0, y - self.y0]) if self.contains(x, y) else 0


def neighbour_count_grid(bitmap: np.ndarray) -> np.ndarray:
    """(H, W) int64: number of 1s among each pixel's six skew-lattice neighbours."""
    b = np.asarray(bitmap, dtype=bool)
    h, w = b.shape
    p = np.zeros((h + 2, w + 2), dtype=np.int64)
    p[1:-1, 1:-1] = b
    c = slice(1, h + 1), slice(1, w + 1)
    total = np.zeros((h, w), dtype=np.int64)
    for di, dj in ((-1, 0), (-1, 1), (0, 1), (1, 0), (1, -1), (0, -1)):
        total += p[c[0].start + di : c[0].stop + di, c[1].start + dj : c[1].stop + dj]
    return total


def bitmap_origin(bitmap: np.ndarray) -> tuple[int, int]:
    """(row0, col0) of the central pixel of an (H, W) bitmap."""
    h, w = np.shape(bitmap)
    return (h - 1) // 2, (w - 1) // 2


def bitmap_cells(bitmap: np.ndarray) -> np.ndarray:
    """(P, 2) int64 tags (X, Y) of the 1-pixels, sorted by (X, Y)."""
    b = np.asarray(bitmap, dtype=bool)
    row0, col0 = bitmap_origin(b)
    # column-major over (j, reversed i) is (X, Y) order
    t = b[::-1, :].T
    xs, rev_i = np.nonzero(t)
    h = b.shape[0]
    i = h - 1 - rev_i
    return np.stack([xs - col0, row0 - i], axis=1).astype(np.int64)


def compute_gene(bitmap: np.ndarray) -> Gene:
    """The gene of an (H, W) bool bitmap (row 0 = top): H·W rows sorted by (X, Y)."""
    b = np.asarray(bitmap, dtype=bool)
    if b.ndim != 2 or b.size == 0:
        raise ValueError(f"bitmap must be a non-empty 2-D array, got shape {b.shape}")
    h, w = b.shape
    row0, col0 = bitmap_origin(b)
    nn = neighbour_count_grid(b)
    # (X, Y) order: X = j - col0 ascending, then Y = row0 - i ascending (i descending)
    flag_t = b[::-1, :].T
    nn_t = nn[::-1, :].T
    xs = np.repeat(np.arange(w, dtype=np.int64) - col0, h)
    ys = np.tile(row0 - np.arange(h - 1, -1, -1, dtype=np.int64), w)
    return Gene(x=xs, y=ys, flag=flag_t.ravel().astype(np.int64), nn=nn_t.ravel())


def gene_grid(gene: Gene) -> GeneGrid:
    """Dense (NX, NY) flag and NN arrays of ``gene`` with their offsets (x0, y0)."""
    if len(gene) == 0:
        raise ValueError("empty gene")
    x0, y0 = int(gene.x.min()), int(gene.y.min())
    nx, ny = int(gene.x.max()) - x0 + 1, int(gene.y.max()) - y0 + 1
    flag = np.zeros((nx, ny), dtype=np.int8)
    nn = np.zeros((nx, ny), dtype=np.int8)
    flag[gene.x - x0, gene.y - y0] = gene.flag
    nn[gene.x - x0, gene.y - y0] = gene.nn
    return GeneGrid(x0=x0, y0=y0, flag=_frozen(flag), nn=_frozen(nn))


def cells_bitmap(cells: np.ndarray) -> tuple[np.ndarray, int, int]:
    """Rasterise a cell set into its bounding box.

    Returns ``(grid, x0, y0)``: ``grid`` (NX, NY) bool indexed ``[X - x0, Y - y0]``.
    """
    cells = as_cells(cells)
    if len(cells) == 0:
        raise ValueError("empty cell set")
    x0, y0 = (int(v) for v in cells.min(axis=0))
    nx, ny = (int(v) + 1 for v in cells.max(axis=0) - (x0, y0))
    grid = np.zeros((nx, ny), dtype=bool)
    grid[cells[:, 0] - x0, cells[:, 1] - y0] = True
    return grid, x0, y0


def scaled_gene(cells: np.ndarray) -> Gene:
    """Gene of an arbitrary cell set (P, 2), in the cells' own tag frame.

    Rows cover the bounding box of the cells (zeros included), sorted by (X, Y); NN counts
    neighbours within the set. Use it for a scaled shape from :func:`etswarm.shapes.scale`.
    """
    grid, x0, y0 = cells_bitmap(cells)
    nx, ny = grid.shape
    p = np.zeros((nx + 2, ny + 2), dtype=np.int64)
    p[1:-1, 1:-1] = grid
    nn = np.zeros((nx, ny), dtype=np.int64)
    for ox, oy in ((0, 1), (1, 1), (1, 0), (0, -1), (-1, -1), (-1, 0)):
        nn += p[1 + ox : nx + 1 + ox, 1 + oy : ny + 1 + oy]
    xs = np.repeat(np.arange(nx, dtype=np.int64) + x0, ny)
    ys = np.tile(np.arange(ny, dtype=np.int64) + y0, nx)
    return Gene(x=xs, y=ys, flag=grid.ravel().astype(np.int64), nn=nn.ravel())


def cells_to_bitmap(cells: np.ndarray) -> np.ndarray:
    """(H, W) bool bitmap (row 0 = top) of a cell set, cropped to its bounding box.

    The bitmap's own origin convention applies when it is read back, so tags come back
    translated by a lattice vector (the shape itself is unchanged).
    """
    grid, _, _ = cells_bitmap(cells)  # [X - x0, Y - y0]
    return np.ascontiguousarray(grid.T[::-1, :])
