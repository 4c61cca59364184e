"""etswarm.shapes: bitmap -> skewed lattice -> gene -> scaled shapes.

Public API: :func:`load_shape` / :class:`Shape` (read and validate a target), :class:`Gene`,
:func:`compute_gene`, :func:`gene_grid` (the gene and its dense lookup), :func:`scale` and
:func:`scaled_gene` (scaled-down shapes for regeneration), and the submodules ``lattice``
(tags, adjacency, constructibility) and ``library`` (built-in shapes).
"""

from etswarm.shapes import lattice, library
from etswarm.shapes.gene import Gene, GeneGrid, compute_gene, gene_grid, scaled_gene
from etswarm.shapes.library import LIBRARY_NAMES, library_path
from etswarm.shapes.scale import scale
from etswarm.shapes.shape import MAX_CELLS, Shape, load_shape, shape_from_bitmap

__all__ = [
    "LIBRARY_NAMES",
    "MAX_CELLS",
    "Gene",
    "GeneGrid",
    "Shape",
    "compute_gene",
    "gene_grid",
    "lattice",
    "library",
    "library_path",
    "load_shape",
    "scale",
    "scaled_gene",
    "shape_from_bitmap",
]


def __getattr__(name: str) -> object:
    """``plot_gene``, ``plot_scaled`` and ``plot_cells`` load matplotlib only when first used."""
    if name in ("plot_gene", "plot_scaled", "plot_cells"):
        from etswarm.shapes import plotting

        return getattr(plotting, name)
    raise AttributeError(f"module 'etswarm.shapes' has no attribute {name!r}")
