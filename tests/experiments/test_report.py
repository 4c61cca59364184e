"""Reports: plots drawn only where the data varies, Markdown summary grouped by swept params."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from etswarm.cli.main import main as cli_main
from etswarm.experiments.report import format_duration, wilson_interval, write_report
from etswarm.experiments.runner import write_results
from etswarm.experiments.spec import load_spec
from etswarm.experiments.store import RunStore
from etswarm.experiments.task import execute_run

SPEC = """
[sweep]
name = "rep"
task = "fake_task:run"
seeds = {{start = 0, count = 4}}
[fixed]
sleep_s = 0.0
crash_robots = 30
[grid]
robots = {robots}
loss = {loss}
damage = {damage}
"""


def sweep_folder(
    folder: Path, write_spec: Callable[..., Path], robots: str, loss: str, damage: str
) -> Path:
    """Run the spec's runs in this process (no Dask) and store them as a sweep would."""
    spec = load_spec(write_spec(folder, SPEC.format(robots=robots, loss=loss, damage=damage)))
    store = RunStore(folder / "out")
    store.create()
    for run in spec.runs():
        store.write(execute_run(spec.task, run.params, run.run_id, str(folder)))
    write_results(spec, store)
    return store.out_dir


def test_full_report_has_every_plot_and_a_grouped_table(
    tmp_path: Path, write_spec: Callable[..., Path], capsys: pytest.CaptureFixture[str]
) -> None:
    out = sweep_folder(tmp_path, write_spec, "[10, 20, 30]", "[0.0, 0.2]", '[[], ["split x=0"]]')
    cli_main(["report", str(out), "--out", str(tmp_path / "rep")])
    printed = capsys.readouterr().out
    names = sorted(p.name for p in (tmp_path / "rep").glob("*.png"))
    assert names == [
        "census_error.png", "formation_time_vs_robots.png", "reform_time.png",
        "success_vs_loss.png",
    ]
    for name in names:
        assert (tmp_path / "rep" / name).stat().st_size > 5000
    text = (tmp_path / "rep" / "report.md").read_text()
    assert printed.strip() == text.strip()
    assert "| robots | loss | damage | runs | errors | formed |" in text
    table_rows = [line for line in text.splitlines() if line.startswith("| 10 ")]
    assert len(table_rows) == 4  # 2 losses x 2 damages
    assert "- runs: 48 (32 ok, 16 errors)" in text
    assert "16 × `ValueError: fake task crashed on robots=30`" in text
    # at loss 0 every fake run forms; the crashed group has no measures
    assert "| 10 | 0.0 | [] | 4 | 0 | 4/4 (100 %) |" in text
    assert "| 30 | 0.0 | [] | 4 | 4 | - |" in text


def test_plots_are_skipped_when_their_parameter_does_not_vary(
    tmp_path: Path, write_spec: Callable[..., Path]
) -> None:
    out = sweep_folder(tmp_path, write_spec, "[10]", "[0.0]", "[[]]")
    (out / "results.parquet").unlink()  # a killed sweep: the table is rebuilt from runs/
    files = write_report(out, tmp_path / "rep")
    assert [p.name for p in files.plots] == ["census_error.png"]
    text = files.markdown_path.read_text()
    assert "swept: nothing" in text and "| runs | errors | formed |" in text


def test_report_from_parquet_file(tmp_path: Path, write_spec: Callable[..., Path]) -> None:
    out = sweep_folder(tmp_path, write_spec, "[10, 20]", "[0.2]", "[[]]")
    files = write_report(out / "results.parquet", tmp_path / "rep")
    assert "formation_time_vs_robots.png" in [p.name for p in files.plots]
    assert "success_vs_loss.png" not in [p.name for p in files.plots]


def test_helpers() -> None:
    assert format_duration(10208) == "2 h 50 min 8 s"
    assert format_duration(754) == "12 min 34 s"
    assert format_duration(18.24) == "18.2 s"
    assert format_duration(0.0234) == "0.02 s"
    assert format_duration(None) == "-"
    low, high = wilson_interval(5, 10)
    assert low == pytest.approx(0.2366, abs=1e-3) and high == pytest.approx(0.7634, abs=1e-3)
    assert wilson_interval(0, 10)[0] == 0.0


def test_summary_groups_rows_where_a_parameter_is_missing() -> None:
    import pandas as pd

    from etswarm.experiments.report import summary_table

    frame = pd.DataFrame(
        {
            "damage": [None, None, '["split x=0"]'],
            "shape": ["T", "T", "T"],
            "status": ["ok", "error", "ok"],
            "formed": [True, None, False],
        }
    ).convert_dtypes()
    table = summary_table(frame, ["damage"])
    assert table["damage"].tolist() == ["-", '["split x=0"]']
    assert table["runs"].tolist() == [2, 1] and table["errors"].tolist() == [1, 0]
    assert list(table.columns[:4]) == ["damage", "runs", "errors", "formed"]
