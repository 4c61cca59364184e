"""`etswarm demo`, the README's first command: the `T` forms, the cut halves re-form, and
the video, snapshots and summary are written."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from etswarm.cli.main import cli


def test_the_demo_forms_cuts_and_regrows_the_t_and_saves_its_files(tmp_path: Path) -> None:
    out = tmp_path / "demo"
    result = CliRunner().invoke(cli, ["demo", "--out", str(out)])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["formed"] and summary["settled"], summary["components"]
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1
    halves = summary["components"]
    assert len(halves) == 2 and sum(c["robots"] for c in halves) == 45
    for half in halves:
        assert half["formed"] and half["jaccard"] == 1.0, half
        assert half["census_count"] == half["robots"] == half["target_cells"]
    assert [e["kind"] for e in summary["events"]].count("leader") == 2
    assert (out / "demo.mp4").stat().st_size > 10_000
    assert any((out / "snapshots").iterdir())
    assert "reformed" in result.output
