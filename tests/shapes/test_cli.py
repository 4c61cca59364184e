"""The shapes, gene and scale commands, run through etswarm.cli.main.main."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from etswarm.cli.main import main
from etswarm.shapes import LIBRARY_NAMES, load_shape, scale


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = 0
    try:
        main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def test_shapes_lists_the_library(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "shapes")
    assert code == 0
    lines = out.splitlines()
    assert lines[0].split()[:3] == ["name", "cells", "size"]
    names = [line.split()[0] for line in lines[1:]]
    assert names == list(LIBRARY_NAMES)
    t_line = lines[1].split()
    assert t_line[1] == str(load_shape("T").n_cells)


def test_gene_json_is_exactly_the_gene(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "gene", "T", "--json")
    assert code == 0
    data = json.loads(out)
    assert data == load_shape("T").gene().records()
    assert set(data[0]) == {"x", "y", "flag", "nn"}


def test_gene_csv_and_table(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "gene", "triangle", "--csv")
    rows = out.splitlines()
    assert code == 0 and rows[0] == "x,y,flag,nn"
    assert len(rows) - 1 == len(load_shape("triangle").gene())
    code, out, _ = run(capsys, "gene", "triangle")
    assert code == 0 and "NN" in out.splitlines()[1]


def test_gene_from_a_path_with_plot(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    src = tmp_path / "blk.txt"
    src.write_text("111\n111\n111\n")
    png = tmp_path / "g.png"
    code, out, _ = run(capsys, "gene", str(src), "--json", "--plot", str(png))
    assert code == 0 and png.stat().st_size > 1000
    rows = {(r["x"], r["y"]): (r["flag"], r["nn"]) for r in json.loads(out)}
    assert rows[(0, 0)] == (1, 6)


def test_gene_repair_reports_dropped_cells(capsys: pytest.CaptureFixture[str],
                                           tmp_path: Path) -> None:
    src = tmp_path / "tail.txt"
    src.write_text("1110\n1111\n")
    code, out, err = run(capsys, "gene", str(src))
    assert code == 2 and "etswarm: error:" in err and "(2,-1)" in err
    assert len(err.strip().splitlines()) == 1
    code, out, err = run(capsys, "gene", str(src), "--repair", "--json")
    assert code == 0 and "dropped 1 cell(s)" in err and "(2,-1)" in err
    assert sum(r["flag"] for r in json.loads(out)) == 6


def test_gene_invert(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    src = tmp_path / "neg.txt"
    src.write_text("0000\n0000\n0000\n")
    code, out, _ = run(capsys, "gene", str(src), "--invert", "--json")
    assert code == 0 and all(r["flag"] == 1 for r in json.loads(out))


def test_gene_errors_are_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    bad = tmp_path / "bad.txt"
    bad.write_text("11\n1?\n")
    for argv in (["gene", "nosuch"], ["gene", str(bad)], ["gene", str(tmp_path / "x.txt")]):
        code, out, err = run(capsys, *argv)
        assert code == 2 and out == ""
        assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    code, _, err = run(capsys, "gene", "T", "--json", "--csv")
    assert code != 0 and "--json" in err


def test_scale_json_and_picture(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, out, _ = run(capsys, "scale", "starfish", "40", "--json")
    assert code == 0
    data = json.loads(out)
    assert [[r["x"], r["y"]] for r in data] == scale(load_shape("starfish"), 40).tolist()
    png = tmp_path / "s.png"
    code, out, _ = run(capsys, "scale", "T", "20", "--plot", str(png))
    assert code == 0 and png.exists()
    lines = out.splitlines()
    assert lines[0].startswith("T scaled from 45 to 20") and lines[-1].startswith("wrote")
    assert sum(line.count("o") for line in lines[1:-1]) == 20


@pytest.mark.parametrize("n", ["2", "46", "1000"])
def test_scale_out_of_range(capsys: pytest.CaptureFixture[str], n: str) -> None:
    code, out, err = run(capsys, "scale", "T", n)
    assert code == 2 and out == ""
    assert f"N = {n}" in err and "3 <= N <= 45" in err
    assert len(err.strip().splitlines()) == 1


def test_console_entry_point_subprocess() -> None:
    out = subprocess.run(
        [sys.executable, "-m", "etswarm.cli.main", "scale", "T", "99"],
        capture_output=True, text=True, check=False,
    )
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.strip() == (
        "etswarm: error: scale: N = 99 is out of range for shape 'T': choose 3 <= N <= 45"
    )


def test_plot_to_a_bad_place_is_a_one_line_error(capsys: pytest.CaptureFixture[str],
                                                  tmp_path: Path) -> None:
    target = tmp_path / "missing" / "x.png"
    code, _, err = run(capsys, "gene", "T", "--plot", str(target))
    assert code == 2 and str(target) in err and "cannot write plot" in err
    assert len(err.strip().splitlines()) == 1
