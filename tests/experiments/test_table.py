"""The tidy table: flattening summaries, parameter/measure columns, Parquet round trip."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from etswarm.errors import EtswarmError
from etswarm.experiments.table import build_table, flatten_summary, read_table, write_table
from etswarm.experiments.task import execute_run

FAKE = "fake_task:run"


@pytest.fixture(autouse=True)
def _fake_task_importable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.syspath_prepend(str(Path(__file__).parent))


def test_flatten_summary_derives_component_event_and_state_measures() -> None:
    summary = {
        "formed": True,
        "states": {"Stable": 8, "Queued": 2},
        "components": [
            {"robots": 6, "formed": True, "jaccard": 1.0, "census_count": 5,
             "time_to_stable_s": 40.0, "stretched_links": 2},
            {"robots": 4, "formed": False, "jaccard": 0.5, "census_count": 6,
             "time_to_stable_s": 70.0, "stretched_links": 1},
        ],
        "events": [{"t_s": 0, "kind": "damage"}, {"t_s": 3, "kind": "leader"},
                   {"t_s": 4, "kind": "leader"}],
        "tags": [1, 2, 3],
    }
    flat = flatten_summary(summary)
    assert flat["formed"] is True
    assert flat["states.Stable"] == 8 and flat["states.Queued"] == 2
    assert flat["n_components"] == 2 and flat["components_formed"] == 1
    assert flat["component_jaccard_min"] == 0.5
    assert flat["component_jaccard_mean"] == pytest.approx(0.75)
    assert flat["census_error_mean"] == pytest.approx(((5 - 6) + (6 - 4)) / 2)
    assert flat["census_error_max_abs"] == 2
    assert flat["reform_time_s"] == 70.0
    assert flat["stretched_links"] == 3
    assert flat["n_events"] == 3 and flat["events.leader"] == 2 and flat["events.damage"] == 1
    assert flat["n_tags"] == 3
    summary["components"][1]["time_to_stable_s"] = None
    assert flatten_summary(summary)["reform_time_s"] is None
    for comp in summary["components"]:
        del comp["stretched_links"]  # as in summaries older than the measure
    assert flatten_summary(summary)["stretched_links"] is None


def test_execute_run_records_summary_and_crash() -> None:
    ok = execute_run(FAKE, {"robots": 10, "seed": 1}, "a1")
    assert ok["status"] == "ok" and ok["error"] is None and ok["summary"]["robots"] == 10
    assert ok["wall_time_s"] > 0 and ok["version"]
    bad = execute_run(FAKE, {"robots": 13, "crash_robots": 13, "seed": 1}, "a2")
    assert bad["status"] == "error" and bad["summary"] is None
    assert bad["error"] == "ValueError: fake task crashed on robots=13"
    assert "Traceback" in bad["traceback"] and "fake_task.py" in bad["traceback"]
    bye = execute_run("fake_task:exits", {"seed": 4}, "a4")
    assert bye["status"] == "error" and bye["error"] == "SystemExit: bye from seed 4"
    missing = execute_run("no_such_module_xyz:run", {"seed": 0}, "a3")
    assert missing["status"] == "error" and "no_such_module_xyz" in missing["error"]
    json.dumps([ok, bad, missing])


def test_table_rows_columns_and_repeated_measures(tmp_path: Path) -> None:
    records = [
        execute_run(FAKE, {"robots": r, "loss": 0.2, "seed": s, "crash_robots": 13}, f"r{r}{s}")
        for r in (10, 13)
        for s in (0, 1)
    ]
    frame = build_table(records, ["robots", "loss", "crash_robots", "seed"])
    assert len(frame) == 4
    assert list(frame.columns[:6]) == ["run_id", "robots", "loss", "crash_robots", "seed", "status"]
    assert list(frame["status"]) == ["ok", "ok", "error", "error"]
    for column in ("formed", "formation_time_s", "states.Stable", "n_components",
                   "component_jaccard_min", "census_error_mean", "wall_time_s", "version"):
        assert column in frame.columns, column
    # the summary repeats robots/loss/seed exactly: no result.* duplicates
    assert not [c for c in frame.columns if c.startswith("result.") and c != "result.wall_time_s"]
    assert frame["error"].isna().sum() == 2

    path = write_table(frame, tmp_path / "t.parquet", {"parameters": ["robots", "seed"]})
    back, meta = read_table(path)
    assert meta == {"parameters": ["robots", "seed"]}
    assert list(back.columns) == list(frame.columns)
    assert back["robots"].tolist() == [10, 10, 13, 13]


def test_measure_that_differs_from_its_parameter_is_kept_as_result_column() -> None:
    record = execute_run(FAKE, {"shape": "T", "seed": 0}, "x")
    record["params"] = {"shape": "T", "robots": "auto", "seed": 0}
    other = execute_run(FAKE, {"robots": 20, "seed": 0}, "y")
    frame = build_table([record, other])
    assert "result.robots" in frame.columns
    # a column mixing text and numbers is stored as text
    assert frame["robots"].tolist() == ["auto", "20"]
    assert isinstance(frame, pd.DataFrame)


def test_read_table_errors_are_one_line(tmp_path: Path) -> None:
    with pytest.raises(EtswarmError, match="no such results"):
        read_table(tmp_path / "nothing.parquet")
    (tmp_path / "bad.parquet").write_text("not parquet")
    with pytest.raises(EtswarmError, match="not a readable Parquet"):
        read_table(tmp_path / "bad.parquet")
    with pytest.raises(EtswarmError, match="no run records"):
        read_table(tmp_path)
