"""The paper report from synthetic run records: figures, comparison table, what went wrong."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from etswarm.experiments.reproduce import (
    CUT_HORIZONTAL,
    CUT_VERTICAL,
    PAPER_T_FORMATION_S,
    comparison_rows,
    damage_snapshots,
    paper_spec_text,
    write_paper_report,
)
from etswarm.experiments.spec import load_spec
from etswarm.experiments.store import RunStore


def snapshot(t_s: float, n: int, stable: int) -> dict[str, Any]:
    """``n`` robots on a lattice, the first ``stable`` Stable (5), the rest Active (3)."""
    return {
        "t_s": t_s,
        "x_mm": [40.0 * (i % 4) - 20.0 * (i // 4) for i in range(n)],
        "y_mm": [34.64 * (i // 4) for i in range(n)],
        "state": [5] * stable + [3] * (n - stable),
        "alive": [True] * n,
    }


def summary(params: dict[str, Any]) -> dict[str, Any]:
    seed = params["seed"]
    if params.get("damage"):
        return damaged_summary(seed)
    formed = seed != 3
    stuck = 2 if seed == 1 else 0
    t_form = 9000.0 + 500 * seed if formed else None
    return {
        "shape": params["shape"],
        "formed": formed,
        "formation_time_s": t_form,
        "jaccard": 1.0 if formed else 0.8,
        "states": {"Stable": 10 - stuck, "Active": stuck},
        "components": [{"robots": 10, "formed": formed, "jaccard": 1.0}],
        "duplicate_tags": [[0, 1]] if seed == 3 else [],
        "snapshots": [snapshot(120.0 * k, 10, min(10, 2 * k)) for k in range(6)]
        + [snapshot(t_form or 14400.0, 10, 10 - stuck)],
    }


def damaged_summary(seed: int) -> dict[str, Any]:
    """A T formed at 1 h, cut at 1 h 1 min and 2 h (seed 0 only), re-formed by 3 h."""
    cuts = [3660.0, 7200.0] if seed == 0 else []
    return {
        "shape": "T", "formed": True, "formation_time_s": 3600.0, "settled": seed == 0,
        "jaccard": 1.0, "states": {"Stable": 10},
        "components": [
            {"robots": 6, "formed": True, "jaccard": 1.0, "census_count": 6},
            {"robots": 4, "formed": True, "jaccard": 1.0, "census_count": 3},
        ],
        "events": [{"t_s": t, "kind": "damage", "spec": "split"} for t in cuts],
        "snapshots": [snapshot(600.0 * k, 10, 10) for k in range(19)],
    }


def test_report_from_records(tmp_path: Path) -> None:
    (tmp_path / "paper.toml").write_text(paper_spec_text(4, 2, 14400.0, damage=True))
    spec = load_spec(tmp_path / "paper.toml")
    assert [p.get("shape") for p in spec.points] == ["T", "dumbbell", "starfish", "T"]
    assert spec.points[3]["damage"] == [CUT_VERTICAL, CUT_HORIZONTAL]
    assert spec.points[3]["max_time_s"] == 2 * 14400.0
    assert spec.seeds_of(3) == (0,) and spec.seeds_of(1) == (0, 1)
    store = RunStore(tmp_path / "sweep")
    store.create()
    for run in spec.runs():
        store.write({"run_id": run.run_id, "status": "ok", "params": run.params,
                     "summary": summary(run.params), "error": None, "task": spec.task})

    path = write_paper_report(tmp_path, ["a note"])
    text = path.read_text()
    figures = sorted(p.name for p in (tmp_path / "figures").glob("*.png"))
    assert figures == ["T_formation_times.png", "fig10_starfish.png", "fig5_T_formation.png",
                       "fig6_T_loss.png", "fig8_T_regeneration.png", "fig9_dumbbell.png"]
    assert "| `T` cut twice (each cut a minute after the shape formed) | 1 of 1 runs got" in text
    assert "| every remnant re-formed its scaled `T` after the second cut | 1 of 1 |" in text
    assert "| census of the remnants: exact counts | 1 of 2 (errors from -1 to +0) |" in text
    assert "Shown: seed 0, cut at 1 h 1 min 0 s, 2 h 0 min 0 s; every remnant re-formed: yes." \
        in text
    assert "| `T` formed within the time limit (loss 0.2) | 3 of 4 seeds | yes (one run shown) |" \
        in text
    # formed seeds 0, 1, 2: 9000, 9500, 10000 s -> median 9500 s = 2 h 38 min 20 s
    assert "| `T` formation time, simulated | 2 h 38 min 20 s (IQR" in text
    assert "| 2 h 50 min 8 s |" in text
    # seed 1 formed but 2 robots stayed Active: closer (Jaccard 1.0) than seed 3 (0.8)
    assert "Shown: seed 1, the failed run closest to the target (Jaccard 1.0, formed: yes);" \
        " robots not Stable at the end: 2 Active." in text
    assert "Robots not Stable at the end, all runs together: Active 2." in text
    assert "1 runs ended with a tag held by two robots." in text
    assert "Not formed within the time limit: seeds 3." in text
    assert "Seed 1 (the median formed run)." in text
    assert "- a note" in text and (tmp_path / "comparison.json").is_file()


def test_comparison_rows_ratio() -> None:
    records = [
        {"status": "ok", "params": {"figure": "5-6", "seed": s, "shape": "T"},
         "summary": {"formed": True, "formation_time_s": PAPER_T_FORMATION_S * f,
                     "states": {"Stable": 45}, "jaccard": 1.0}}
        for s, f in enumerate((0.5, 1.0, 2.0))
    ]
    rows = dict((m, o) for m, o, _ in comparison_rows(records))
    assert rows["ratio ours / paper (median)"] == "1.00"
    assert rows["`T` robots not Stable at the end (median, max)"] == "0, 0"
    assert np.isclose(float(rows["ratio ours / paper (median)"]), 1.0)


def test_damage_snapshots_bracket_each_cut() -> None:
    record = {"summary": damaged_summary(0)}
    times = [s["t_s"] for s in damage_snapshots(record)]
    # before/after the cut at 3660 s, before/after 7200 s, the middle of the rest, the end
    assert times == [3600.0, 4200.0, 6600.0, 7800.0, 9000.0, 10800.0]
    assert len(damage_snapshots({"summary": damaged_summary(1)})) == 6
