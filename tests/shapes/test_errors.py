"""Every bad input gets a one-line EtswarmError naming the file and the problem."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from etswarm.errors import EtswarmError
from etswarm.shapes import load_shape
from etswarm.shapes.gene import cells_to_bitmap

from .helpers import text_of


def error_of(spec: str | Path, **kw: bool) -> str:
    with pytest.raises(EtswarmError) as info:
        load_shape(spec, **kw)
    msg = str(info.value)
    assert "\n" not in msg
    return msg


def put(tmp_path: Path, name: str, content: str | bytes) -> Path:
    p = tmp_path / name
    if isinstance(content, bytes):
        p.write_bytes(content)
    else:
        p.write_text(content)
    return p


def test_missing_file(tmp_path: Path) -> None:
    p = tmp_path / "nope.txt"
    msg = error_of(p)
    assert str(p) in msg and "no such file" in msg


def test_unknown_library_name_lists_the_library() -> None:
    msg = error_of("no_such_shape")
    assert "no_such_shape" in msg and "library" in msg and "dumbbell" in msg


def test_directory(tmp_path: Path) -> None:
    msg = error_of(tmp_path)
    assert str(tmp_path) in msg and "directory" in msg


def test_unreadable_binary(tmp_path: Path) -> None:
    p = put(tmp_path, "junk.png", bytes(range(256)) * 4)
    msg = error_of(p)
    assert str(p) in msg and "not a text bitmap, PBM or readable image" in msg


def test_empty_file(tmp_path: Path) -> None:
    p = put(tmp_path, "empty.txt", "")
    msg = error_of(p)
    assert str(p) in msg and "empty" in msg


def test_only_comments(tmp_path: Path) -> None:
    p = put(tmp_path, "c.txt", "; nothing here\n# nor here\n\n")
    msg = error_of(p)
    assert str(p) in msg and "empty" in msg and "no pixel rows" in msg


def test_ragged_rows_name_the_row(tmp_path: Path) -> None:
    p = put(tmp_path, "r.txt", "; comment\n111\n111\n11\n")
    msg = error_of(p)
    assert str(p) in msg and "row 3 (line 4) has 2 pixels" in msg and "has 3" in msg


def test_bad_character_names_row_and_column(tmp_path: Path) -> None:
    p = put(tmp_path, "b.txt", "111\n1x1\n111\n")
    msg = error_of(p)
    assert str(p) in msg and "row 2 (line 2), column 2" in msg and "'x'" in msg


def test_no_ones(tmp_path: Path) -> None:
    p = put(tmp_path, "z.txt", "000\n000\n")
    msg = error_of(p)
    assert str(p) in msg and "no 1s" in msg


def test_too_many_cells(tmp_path: Path) -> None:
    p = put(tmp_path, "big.txt", text_of(np.ones((101, 100), dtype=bool)))
    msg = error_of(p)
    assert str(p) in msg and "10100 cells" in msg and "10000" in msg


def test_disconnected_on_the_lattice(tmp_path: Path) -> None:
    # two blocks touching only at a (i+1, j+1) corner: connected to the eye, not on the lattice
    p = put(tmp_path, "d.txt", "1100\n1100\n0011\n0011\n")
    msg = error_of(p)
    assert str(p) in msg and "2 separate pieces" in msg


def test_unconstructible_cells_are_listed_and_repair_drops_them(tmp_path: Path) -> None:
    # a 2x3 block with a one-pixel tail to the right
    p = put(tmp_path, "tail.txt", "1110\n1111\n")
    msg = error_of(p)
    assert str(p) in msg and "1 cell(s) no robot can ever localize in" in msg
    assert "(2,-1)" in msg and "row 2 col 4" in msg and "--repair" in msg
    shape = load_shape(p, repair=True)
    assert shape.dropped == ((2, -1),)
    assert shape.n_cells == 6


def test_no_triangle_at_all(tmp_path: Path) -> None:
    p = put(tmp_path, "line.txt", "11111\n")
    msg = error_of(p, repair=True)
    assert str(p) in msg and "no three mutually adjacent 1s" in msg


def test_pbm_errors(tmp_path: Path) -> None:
    p = put(tmp_path, "short.pbm", "P1\n3 2\n1 1 1\n1 1\n")
    assert "has 5 pixels, 3x2 needs 6" in error_of(p)
    p = put(tmp_path, "badp1.pbm", "P1\n2 1\n1 2\n")
    assert "only 0 and 1" in error_of(p)
    p = put(tmp_path, "p4.pbm", b"P4\n16 3\n\xff\xff")
    msg = error_of(p)
    assert str(p) in msg and "has 2 bytes" in msg
    p = put(tmp_path, "hdr.pbm", "P1\n3\n")
    assert "header ends early" in error_of(p)
    p = put(tmp_path, "hdr2.pbm", "P1\nx 3\n")
    assert "not integers" in error_of(p)


def test_library_shapes_need_no_repair() -> None:
    assert load_shape("T", repair=True).dropped == ()


def test_repaired_shape_is_valid() -> None:
    cells = np.array([[0, 0], [1, 0], [1, 1], [2, 1], [3, 2], [4, 2]])
    b = cells_to_bitmap(cells)
    from etswarm.shapes import shape_from_bitmap
    from etswarm.shapes.lattice import is_constructible

    with pytest.raises(EtswarmError):
        shape_from_bitmap(b, "x")
    fixed = shape_from_bitmap(b, "x", repair=True)
    assert len(fixed.dropped) == 2 and is_constructible(fixed.cells)
