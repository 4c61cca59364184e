"""A fake sweep task with the real runner's contract: params dict -> JSON-able summary.

Numbers are deterministic functions of the parameters. Extra parameters steer it:
``log`` (a file to append one line per call, to count executions), ``sleep_s`` (seconds
to wait), ``crash_robots`` (raise ValueError when ``robots`` equals it), ``gate`` (a file
that must exist before the call returns: lets a test hold runs in flight).
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any


def run(params: dict[str, Any]) -> dict[str, Any]:
    """Return a summary shaped like etswarm.algorithm.api.run_experiment's."""
    start = time.perf_counter()
    if params.get("log"):
        with open(params["log"], "a", encoding="utf-8") as handle:
            handle.write(json.dumps(params, sort_keys=True) + "\n")
            handle.flush()
            os.fsync(handle.fileno())
    gate = params.get("gate")
    while gate and not Path(gate).exists():
        time.sleep(0.02)
    time.sleep(float(params.get("sleep_s", 0.02)))
    robots = int(params.get("robots", 10))
    loss = float(params.get("loss", 0.0))
    seed = int(params["seed"])
    if params.get("crash_robots") == robots:
        raise ValueError(f"fake task crashed on robots={robots}")
    formed = (seed + robots) % 4 != 0 or loss == 0.0
    census_count = robots + (seed % 3) - 1
    return {
        "shape": params.get("shape", "T"),
        "robots": robots,
        "seed": seed,
        "loss": loss,
        "formed": formed,
        "formation_time_s": 100.0 * robots * (1 + loss) + seed if formed else None,
        "sim_time_s": 100.0 * robots * (1 + loss) + seed,
        "wall_time_s": time.perf_counter() - start,
        "jaccard": 1.0 if formed else 0.5,
        "placement_error_mm": 1.5 + 0.1 * seed,
        "states": {"Stable": robots - 1, "Queued": 1},
        "components": [
            {
                "robots": robots,
                "target_cells": robots,
                "formed": formed,
                "jaccard": 1.0 if formed else 0.5,
                "census_count": census_count,
                "time_to_stable_s": 50.0 + seed if formed else None,
            }
        ],
        "events": [{"t_s": 0.0, "kind": "start"}, {"t_s": 5.0, "kind": "placed", "id": 3}],
    }


def strict(params: dict[str, Any]) -> dict[str, Any]:
    """Like ``run`` but declares the parameters it accepts (the runner checks them)."""
    return run(params)


strict.parameters = frozenset({"robots", "loss", "shape", "log", "sleep_s", "crash_robots"})  # type: ignore[attr-defined]


def exits(params: dict[str, Any]) -> dict[str, Any]:
    """A task that calls sys.exit: must be recorded as a failed run, not end the worker."""
    raise SystemExit(f"bye from seed {params['seed']}")
