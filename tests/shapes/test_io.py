"""Reading bitmaps: text variants, PBM P1/P4 and images give the same gene."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from PIL import Image

from etswarm.shapes import compute_gene, load_shape
from etswarm.shapes.bitmap_io import parse_pbm, parse_text

from .helpers import any_bitmaps, grown_bitmaps, text_of


def write_p1(path: Path, b: np.ndarray) -> None:
    h, w = b.shape
    body = "\n".join(" ".join("1" if v else "0" for v in row) for row in b)
    path.write_text(f"P1\n# made by a test\n{w} {h}\n{body}\n")


def write_p4(path: Path, b: np.ndarray) -> None:
    h, w = b.shape
    packed = np.packbits(b.astype(np.uint8), axis=1)
    path.write_bytes(f"P4\n{w} {h}\n".encode() + packed.tobytes())


def write_png(path: Path, b: np.ndarray, mode: str = "L") -> None:
    grey = np.where(b, 0, 255).astype(np.uint8)  # dark = inside
    img = Image.fromarray(grey, "L")
    if mode != "L":
        img = img.convert(mode)
    img.save(path)


@settings(
    max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(grown_bitmaps(max_size=40))
def test_same_gene_from_text_pbm_and_png(tmp_path: Path, bitmap: np.ndarray) -> None:
    paths = {
        "txt": tmp_path / "s.txt",
        "dots": tmp_path / "s2.txt",
        "p1": tmp_path / "s.pbm",
        "p4": tmp_path / "s4.pbm",
        "png": tmp_path / "s.png",
        "rgb": tmp_path / "rgb.png",
    }
    paths["txt"].write_text(text_of(bitmap))
    paths["dots"].write_text("; a comment\n\n" + text_of(bitmap, "#", "."))
    write_p1(paths["p1"], bitmap)
    write_p4(paths["p4"], bitmap)
    write_png(paths["png"], bitmap)
    write_png(paths["rgb"], bitmap, "RGB")
    want = compute_gene(bitmap)
    for kind, path in paths.items():
        got = load_shape(path).gene()
        assert got == want, kind


@settings(max_examples=60, deadline=None)
@given(any_bitmaps())
def test_parsers_read_any_pattern(bitmap: np.ndarray) -> None:
    assert np.array_equal(parse_text(text_of(bitmap), "t"), bitmap)
    h, w = bitmap.shape
    p1 = f"P1 {w} {h}\n" + "".join("1" if v else "0" for v in bitmap.ravel())
    assert np.array_equal(parse_pbm(p1.encode(), "t"), bitmap)


def test_comment_lines_and_hash_rows(tmp_path: Path) -> None:
    p = tmp_path / "c.txt"
    p.write_text("# T-ish shape, drawn with hashes\n; another comment\n###\n.#.  \n\n.#.\n")
    b = parse_text(p.read_text(), "c")
    assert b.tolist() == [[True] * 3, [False, True, False], [False, True, False]]


def test_invert_and_transparency(tmp_path: Path) -> None:
    b = np.zeros((5, 5), dtype=bool)
    b[1:4, 1:4] = True
    # white shape on black, read with invert
    Image.fromarray(np.where(b, 255, 0).astype(np.uint8), "L").save(tmp_path / "w.png")
    assert load_shape(tmp_path / "w.png", invert=True).gene() == compute_gene(b)
    # opaque black shape on a transparent background
    rgba = np.zeros((5, 5, 4), dtype=np.uint8)
    rgba[b] = (0, 0, 0, 255)
    Image.fromarray(rgba, "RGBA").save(tmp_path / "a.png")
    assert load_shape(tmp_path / "a.png").gene() == compute_gene(b)


def test_library_name_and_path_agree() -> None:
    from etswarm.shapes import library_path

    assert load_shape("T").gene() == load_shape(library_path("T")).gene()
    assert load_shape(str(library_path("T"))).name == "T"


def test_utf8_bom_and_crlf(tmp_path: Path) -> None:
    p = tmp_path / "bom.txt"
    p.write_bytes(b"\xef\xbb\xbf111\r\n111\r\n111\r\n")
    assert load_shape(p).gene() == compute_gene(np.ones((3, 3), dtype=bool))
