"""A validated target shape and :func:`load_shape`, which reads and checks one."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.shapes.bitmap_io import read_bitmap
from etswarm.shapes.gene import Gene, GeneGrid, bitmap_cells, bitmap_origin, compute_gene, gene_grid
from etswarm.shapes.lattice import Constructibility, component_labels
from etswarm.shapes.library import LIBRARY_NAMES, library_description, library_path

#: Most 1-cells (robots) a shape may have.
MAX_CELLS = 10_000
#: How many offending cells an error message lists before "and K more".
_LIST_LIMIT = 8


@dataclass(frozen=True, eq=False)
class Shape:
    """A target shape.

    Attributes:
        name: library name or file stem.
        bitmap: (H, W) bool, row 0 = top, True = inside (read-only).
        dropped: tags (X, Y) removed by ``repair`` (empty when nothing was dropped).
        description: one line about the shape (library shapes have one).
        source: the file it was read from ("" when built in memory).
    """

    name: str
    bitmap: np.ndarray
    dropped: tuple[tuple[int, int], ...] = ()
    description: str = ""
    source: str = ""

    def __post_init__(self) -> None:
        b = np.array(self.bitmap, dtype=bool)
        if b.ndim != 2 or b.size == 0:
            raise ValueError(f"bitmap must be a non-empty 2-D array, got shape {b.shape}")
        b.setflags(write=False)
        object.__setattr__(self, "bitmap", b)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Shape):
            return NotImplemented
        return (
            self.name == other.name
            and self.bitmap.shape == other.bitmap.shape
            and bool(np.array_equal(self.bitmap, other.bitmap))
            and self.dropped == other.dropped
        )

    def __hash__(self) -> int:
        return hash((self.name, self.bitmap.shape, self.bitmap.tobytes(), self.dropped))

    @cached_property
    def cells(self) -> np.ndarray:
        """(P, 2) int64 tags (X, Y) of the 1-pixels, sorted by (X, Y)."""
        c = bitmap_cells(self.bitmap)
        c.setflags(write=False)
        return c

    @property
    def n_cells(self) -> int:
        """Number of 1-pixels (robots in the full shape)."""
        return int(self.bitmap.sum())

    @property
    def size(self) -> tuple[int, int]:
        """(H, W) of the bitmap."""
        return (int(self.bitmap.shape[0]), int(self.bitmap.shape[1]))

    @property
    def origin(self) -> tuple[int, int]:
        """(row0, col0): the bitmap pixel with tag (0, 0)."""
        return bitmap_origin(self.bitmap)

    @cached_property
    def _gene(self) -> Gene:
        return compute_gene(self.bitmap)

    def gene(self) -> Gene:
        """The gene: one row per pixel, sorted by (X, Y)."""
        return self._gene

    def gene_grid(self) -> GeneGrid:
        """Dense flag/NN lookup of the gene (see :func:`etswarm.shapes.gene.gene_grid`)."""
        return gene_grid(self.gene())


def _list_cells(tags: list[tuple[int, int]], why: list[str] | None = None) -> str:
    shown = []
    for k, (x, y) in enumerate(tags[:_LIST_LIMIT]):
        shown.append(f"({x},{y})" + (f" {why[k]}" if why else ""))
    more = len(tags) - _LIST_LIMIT
    return ", ".join(shown) + (f" and {more} more" if more > 0 else "")


def _pixel(tag: tuple[int, int], origin: tuple[int, int]) -> str:
    row0, col0 = origin
    return f"row {row0 - tag[1] + 1} col {tag[0] + col0 + 1}"


def validate_bitmap(
    bitmap: np.ndarray, label: str, *, repair: bool = False
) -> tuple[np.ndarray, tuple[tuple[int, int], ...]]:
    """Check a bitmap as a target shape; return (bitmap, dropped tags).

    Raises EtswarmError (one line starting with ``label``) when it has no 1s, more than
    :data:`MAX_CELLS` 1s, 1s that are not connected on the skewed lattice, or cells no robot can
    ever localize in (unless ``repair``, which drops those cells and reports them as dropped).
    """
    b = np.asarray(bitmap, dtype=bool)
    n = int(b.sum())
    if n == 0:
        raise EtswarmError(f"{label}: no 1s: the shape has no cells")
    if n > MAX_CELLS:
        raise EtswarmError(f"{label}: {n} cells (1s), more than the limit of {MAX_CELLS}")
    cells = bitmap_cells(b)
    origin = bitmap_origin(b)
    labels = component_labels(cells)
    n_pieces = int(labels.max()) + 1
    if n_pieces > 1:
        firsts = [tuple(cells[int(np.argmax(labels == k))].tolist()) for k in range(n_pieces)]
        pieces = ", ".join(
            f"({x},{y}) at {_pixel((x, y), origin)}" for x, y in firsts[:_LIST_LIMIT]
        )
        raise EtswarmError(
            f"{label}: the 1s form {n_pieces} separate pieces on the skewed lattice "
            f"(one cell of each: {pieces}); pixels touching only at (i-1,j-1)/(i+1,j+1) "
            "corners are not neighbours"
        )
    an = Constructibility(cells)
    if an.constructible:
        return b, ()
    bad_idx = np.flatnonzero(~an.buildable)
    bad = [(int(cells[i, 0]), int(cells[i, 1])) for i in bad_idx]
    if not an.buildable.any():
        raise EtswarmError(
            f"{label}: no three mutually adjacent 1s, so no robot can ever localize; "
            "arms must be at least 2 cells wide on the lattice"
        )
    if not repair:
        why = [
            f"[{_pixel(t, origin)}: {an.reason(int(i))}]"
            for t, i in zip(bad, bad_idx, strict=True)
        ]
        raise EtswarmError(
            f"{label}: {len(bad)} cell(s) no robot can ever localize in: "
            f"{_list_cells(bad, why)}; widen those parts or use --repair to drop them"
        )
    row0, col0 = origin
    fixed = b.copy()
    for x, y in bad:
        fixed[row0 - y, x + col0] = False
    return fixed, tuple(bad)


def _resolve(spec: str | Path) -> tuple[Path, str, str, str]:
    """Return (path, label for errors, shape name, description)."""
    if isinstance(spec, Path):
        return spec, str(spec), spec.stem, ""
    text = str(spec)
    candidate = Path(text)
    if text in LIBRARY_NAMES and not candidate.exists():
        return library_path(text), f"library shape {text!r}", text, library_description(text)
    if not candidate.exists() and not any(sep in text for sep in "/\\") and "." not in text:
        library_path(text)  # raises: unknown library name, listing the choices
    return candidate, text, candidate.stem, ""


def load_shape(spec: str | Path, *, invert: bool = False, repair: bool = False) -> Shape:
    """Read and validate a shape: a library name (``"T"``) or a path (text, PBM, image).

    ``invert`` swaps 1s and 0s after reading. ``repair`` drops the cells no robot can ever
    localize in (recorded in ``Shape.dropped``) instead of failing. Raises EtswarmError with
    one line naming the file for any problem (see :func:`validate_bitmap`).
    """
    path, label, name, description = _resolve(spec)
    bitmap = read_bitmap(path, label)
    if invert:
        bitmap = ~bitmap
    bitmap, dropped = validate_bitmap(bitmap, label, repair=repair)
    return Shape(
        name=name, bitmap=bitmap, dropped=dropped, description=description, source=str(path)
    )


def shape_from_bitmap(
    bitmap: np.ndarray, name: str = "bitmap", *, repair: bool = False
) -> Shape:
    """Validate an in-memory (H, W) bitmap as a :class:`Shape` (same checks as load_shape)."""
    fixed, dropped = validate_bitmap(np.asarray(bitmap, dtype=bool), name, repair=repair)
    return Shape(name=name, bitmap=fixed, dropped=dropped)
