"""CLI commands ``shapes``, ``gene`` and ``scale`` (the shape pipeline).

Every command that takes SHAPE accepts a library name (``etswarm shapes`` lists them) or a
path to a text bitmap, PBM or image.
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import click
import numpy as np

from etswarm.errors import EtswarmError
from etswarm.shapes import LIBRARY_NAMES, load_shape
from etswarm.shapes.gene import scaled_gene
from etswarm.shapes.library import library_description
from etswarm.shapes.scale import scale as scale_shape
from etswarm.shapes.shape import Shape

_shape_arg = click.argument("shape_spec", metavar="SHAPE")
_invert_opt = click.option("--invert", is_flag=True, help="Swap 1s and 0s after reading.")
_repair_opt = click.option(
    "--repair", is_flag=True, help="Drop cells no robot can localize in instead of failing."
)


def _load(spec: str, invert: bool, repair: bool) -> Shape:
    shape = load_shape(spec, invert=invert, repair=repair)
    if shape.dropped:
        cells = ", ".join(f"({x},{y})" for x, y in shape.dropped)
        click.echo(
            f"etswarm: repaired {spec}: dropped {len(shape.dropped)} cell(s) no robot can "
            f"localize in: {cells}",
            err=True,
        )
    return shape


def lattice_picture(cells: np.ndarray) -> str:
    """Text drawing of a cell set on the lattice: ``o`` a cell, ``.`` an empty site.

    Each row is indented half a cell per row, as the robots stand (x = X − Y/2).
    """
    cells = np.asarray(cells, dtype=np.int64)
    have = {(int(x), int(y)) for x, y in cells.tolist()}
    xmin, ymin = (int(v) for v in cells.min(axis=0))
    xmax, ymax = (int(v) for v in cells.max(axis=0))
    col_min = min(2 * x - y for x in (xmin, xmax) for y in (ymin, ymax))
    lines = []
    for y in range(ymax, ymin - 1, -1):
        row = {2 * x - y - col_min: ("o" if (x, y) in have else ".") for x in range(xmin, xmax + 1)}
        width = max(row) + 1
        lines.append("".join(row.get(c, " ") for c in range(width)).rstrip())
    return "\n".join(lines)


def _plot(kind: str, shape: Shape, target: str, n: int | None = None) -> None:
    from etswarm.shapes.plotting import plot_gene, plot_scaled

    try:
        if kind == "gene":
            plot_gene(shape, target)
        else:
            assert n is not None
            plot_scaled(shape, n, target)
    except (OSError, ValueError) as err:
        detail = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise EtswarmError(f"{target}: cannot write plot ({detail})") from None


@click.command("shapes")
def shapes() -> None:
    """List the built-in library shapes with their cell counts."""
    rows = []
    for name in LIBRARY_NAMES:
        shape = load_shape(name)
        h, w = shape.size
        rows.append((name, str(shape.n_cells), f"{w}x{h}", library_description(name)))
    header = ("name", "cells", "size", "description")
    widths = [max(len(r[k]) for r in [header, *rows]) for k in range(3)]
    for r in [header, *rows]:
        click.echo(
            f"{r[0]:<{widths[0]}}  {r[1]:>{widths[1]}}  {r[2]:<{widths[2]}}  {r[3]}".rstrip()
        )


@click.command("gene")
@_shape_arg
@click.option("--json", "as_json", is_flag=True, help="Print a JSON list of {x, y, flag, nn}.")
@click.option("--csv", "as_csv", is_flag=True, help="Print CSV with header x,y,flag,nn.")
@click.option("--plot", "plot_file", metavar="FILE.png", help="Draw bitmap and lattice to FILE.")
@_invert_opt
@_repair_opt
def gene(
    shape_spec: str, as_json: bool, as_csv: bool, plot_file: str | None, invert: bool,
    repair: bool,
) -> None:
    """Print the gene (X, Y, F, NN for every pixel, sorted by X then Y) of SHAPE.

    SHAPE is a library name (see `etswarm shapes`) or a file: text rows of 0/1 or ./#, PBM
    (P1/P4), or an image (dark pixels are inside; --invert for light on dark).
    """
    if as_json and as_csv:
        raise click.UsageError("choose one of --json and --csv")
    shape = _load(shape_spec, invert, repair)
    g = shape.gene()
    if plot_file:
        _plot("gene", shape, plot_file)
    if as_json:
        click.echo(json.dumps(g.records()))
    elif as_csv:
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(["x", "y", "flag", "nn"])
        writer.writerows(g.as_array().tolist())
        click.echo(buf.getvalue(), nl=False)
    elif plot_file:
        click.echo(f"wrote {plot_file} ({shape.name}: {shape.n_cells} cells)")
    else:
        h, w = shape.size
        click.echo(f"# gene of {shape.name}: {w}x{h} pixels, {shape.n_cells} cells")
        click.echo(f"{'X':>4} {'Y':>4} {'F':>2} {'NN':>3}")
        for x, y, f, nn in g.as_array().tolist():
            click.echo(f"{x:>4} {y:>4} {f:>2} {nn:>3}")


@click.command("scale")
@_shape_arg
@click.argument("n", metavar="N", type=int)
@click.option("--json", "as_json", is_flag=True, help="Print a JSON list of {x, y, nn}.")
@click.option("--plot", "plot_file", metavar="FILE", help="Draw original and scaled shape.")
@_invert_opt
@_repair_opt
def scale(
    shape_spec: str, n: int, as_json: bool, plot_file: str | None, invert: bool, repair: bool
) -> None:
    """Scale SHAPE down to exactly N cells (3 <= N <= its cell count), as robots do after damage.

    The result is connected and constructible, in the original's tag frame, and the same on
    every machine. SHAPE is a library name or a file, as for `etswarm gene`.
    """
    shape = _load(shape_spec, invert, repair)
    cells = scale_shape(shape, n)
    if plot_file:
        _plot("scale", shape, plot_file, n)
    g = scaled_gene(cells)
    keep = g.flag == 1
    if as_json:
        recs = [
            {"x": x, "y": y, "nn": k}
            for x, y, k in zip(g.x[keep].tolist(), g.y[keep].tolist(), g.nn[keep].tolist(),
                               strict=True)
        ]
        click.echo(json.dumps(recs))
        return
    click.echo(f"{shape.name} scaled from {shape.n_cells} to {n} cells (original tag frame)")
    click.echo(lattice_picture(cells))
    if plot_file:
        click.echo(f"wrote {Path(plot_file)}")
