"""``paper_run`` on the real ET runner: snapshots, and a run that snapshots is the same run."""

from __future__ import annotations

from etswarm.algorithm.api import run_experiment
from etswarm.experiments.reproduce import paper_run

PARAMS = {"shape": "triangle", "seed": 3, "max_time_s": 120.0}


def test_paper_run_takes_snapshots_without_changing_the_run() -> None:
    summary = paper_run({**PARAMS, "snapshot_every_s": 30.0, "figure": "test"})
    snaps = summary.pop("snapshots")
    times = [s["t_s"] for s in snaps]
    assert times[0] == 0.0 and times == sorted(times)
    assert times[-1] == summary["sim_time_s"]
    assert len(times) >= 4  # at 0, ~30, ~60, ~90 s and the end
    for snap in snaps:
        n = len(snap["x_mm"])
        assert n == summary["robots"] == len(snap["y_mm"]) == len(snap["state"])
        assert all(0 <= s <= 7 for s in snap["state"])
    plain = run_experiment(dict(PARAMS))
    for key in ("wall_time_s",):
        summary.pop(key)
        plain.pop(key)
    assert summary == plain
