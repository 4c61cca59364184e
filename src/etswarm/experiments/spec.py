"""Sweep specifications: read a TOML file, validate it, expand it into runs.

A spec looks like::

    [sweep]
    name = "size"                                      # required, used in messages
    task = "etswarm.algorithm.api:run_experiment"      # optional, "module:function"
    seeds = {start = 0, count = 20}                    # or seeds = [1, 2, 3]

    [fixed]                                            # optional: same for every run
    shape = "T"

    [grid]                                             # optional: cartesian product
    robots = [20, 50, 100]
    loss = [0.0, 0.2]

    [[cases]]                                          # optional: explicit combinations
    shape = "dumbbell"
    damage = ["split x=0"]
    seeds = [0, 1, 2]                                  # optional: this case's own seeds

The runs are (every grid point, then every case) × every seed (a case's own ``seeds``
replace the sweep's for that case); each run's parameters are ``fixed`` overlaid by the
grid point or case, plus ``seed``. A run's id is a hash of the
canonical JSON of its parameters, so it names the same run in every session and on every
machine.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from etswarm.errors import EtswarmError

#: The task a spec runs unless it names another.
DEFAULT_TASK = "etswarm.algorithm.api:run_experiment"

_SWEEP_KEYS = frozenset({"name", "task", "seeds", "description"})
_TOP_KEYS = frozenset({"sweep", "grid", "fixed", "cases"})
_RESERVED_PARAMS = frozenset({"seed", "run_id", "status", "error", "wall_time_s", "version"})

#: One parameter value: a TOML scalar or a list of scalars (e.g. damage = ["split x=0"]).
ParamValue = str | int | float | bool | list


@dataclass(frozen=True)
class Run:
    """One task of a sweep: its parameters (seed included) and its stable id."""

    run_id: str
    params: dict[str, Any]


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: what to run and with which parameter points and seeds.

    ``points`` are the parameter dicts without the seed, in spec order (grid first, then
    cases), duplicates removed; ``point_seeds[i]`` are the seeds of ``points[i]`` (the
    sweep's, or a case's own); ``swept`` names the parameters that differ between points.
    """

    path: Path
    name: str
    task: str
    seeds: tuple[int, ...]
    points: tuple[dict[str, Any], ...]
    description: str = ""
    swept: tuple[str, ...] = field(default=())
    point_seeds: tuple[tuple[int, ...], ...] = field(default=())

    def seeds_of(self, index: int) -> tuple[int, ...]:
        """The seeds of ``points[index]``."""
        return self.point_seeds[index] if self.point_seeds else self.seeds

    def runs(self) -> list[Run]:
        """Every (point, seed) as a Run, point-major, duplicates removed."""
        seen: set[str] = set()
        out: list[Run] = []
        for index, point in enumerate(self.points):
            for seed in self.seeds_of(index):
                params = {**point, "seed": seed}
                rid = run_id(params)
                if rid not in seen:
                    seen.add(rid)
                    out.append(Run(rid, params))
        return out

    @property
    def parameters(self) -> tuple[str, ...]:
        """Every parameter name used by some run, in first-seen order, ``seed`` last."""
        names: dict[str, None] = {}
        for point in self.points:
            names.update(dict.fromkeys(point))
        return (*names, "seed")


def canonical_json(params: dict[str, Any]) -> str:
    """The canonical JSON text of a parameter dict: sorted keys, no spaces, UTF-8."""
    return json.dumps(params, sort_keys=True, separators=(",", ":"), ensure_ascii=False)


def run_id(params: dict[str, Any]) -> str:
    """The stable id of a run: the first 16 hex digits of SHA-256 of its canonical JSON."""
    return hashlib.sha256(canonical_json(params).encode("utf-8")).hexdigest()[:16]


def load_spec(path: str | Path) -> SweepSpec:
    """Read and validate the sweep spec at ``path``.

    Raises EtswarmError (one line naming the file and key) when the file is missing, is not
    TOML, has unknown keys, empty lists or values of the wrong type.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise EtswarmError(f"{path}: cannot read sweep spec ({err.strerror})") from err
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise EtswarmError(f"{path}: not valid TOML: {err}") from err
    return parse_spec(data, path)


def parse_spec(data: dict[str, Any], path: str | Path = "<spec>") -> SweepSpec:
    """Validate an already-parsed spec dict (the TOML document) and build the SweepSpec."""
    path = Path(path)

    def fail(key: str, what: str) -> EtswarmError:
        return EtswarmError(f"{path}: {key}: {what}")

    unknown = sorted(set(data) - _TOP_KEYS)
    if unknown:
        raise fail(unknown[0], "unknown section (expected sweep, grid, fixed, cases)")
    sweep = data.get("sweep")
    if not isinstance(sweep, dict):
        raise fail("sweep", "missing [sweep] table")
    unknown = sorted(set(sweep) - _SWEEP_KEYS)
    if unknown:
        raise fail(f"sweep.{unknown[0]}", "unknown key (expected name, task, seeds, description)")

    name = sweep.get("name")
    if not isinstance(name, str) or not name.strip():
        raise fail("sweep.name", "must be a non-empty string")
    task = sweep.get("task", DEFAULT_TASK)
    if not isinstance(task, str) or task.count(":") != 1 or not all(task.split(":")):
        raise fail("sweep.task", f"must be 'module:function', got {task!r}")
    description = sweep.get("description", "")
    if not isinstance(description, str):
        raise fail("sweep.description", "must be a string")
    if "seeds" not in sweep:
        raise fail("sweep.seeds", "missing (a list of integers or {start = 0, count = 20})")
    seeds = _parse_seeds(sweep["seeds"], fail)

    fixed = data.get("fixed", {})
    if not isinstance(fixed, dict):
        raise fail("fixed", "must be a table of parameter = value")
    for key, value in fixed.items():
        _check_param(f"fixed.{key}", key, value, fail)

    grid = data.get("grid", {})
    if not isinstance(grid, dict):
        raise fail("grid", "must be a table of parameter = [values]")
    for key, values in grid.items():
        if not isinstance(values, list):
            raise fail(f"grid.{key}", f"must be a list of values, got {_kind(values)}")
        if not values:
            raise fail(f"grid.{key}", "empty list")
        for value in values:
            _check_param(f"grid.{key}", key, value, fail)
        if key in fixed:
            raise fail(f"grid.{key}", "also set in [fixed]; set it in one place")

    cases = data.get("cases", [])
    if not isinstance(cases, list) or not all(isinstance(c, dict) for c in cases):
        raise fail("cases", "must be an array of tables ([[cases]])")
    cases = [dict(c) for c in cases]
    case_seeds: list[tuple[int, ...]] = []
    for number, case in enumerate(cases, start=1):
        where = f"cases[{number}]"
        own = seeds
        if "seeds" in case:
            own = _parse_seeds(case.pop("seeds"), fail, f"{where}.seeds")
        if not case:
            raise fail(where, "empty case")
        for key, value in case.items():
            _check_param(f"{where}.{key}", key, value, fail)
        case_seeds.append(own)

    planned: list[tuple[dict[str, Any], tuple[int, ...]]] = []
    if grid or not cases:
        keys = list(grid)
        for combo in itertools.product(*(grid[k] for k in keys)):
            planned.append(({**fixed, **dict(zip(keys, combo, strict=True))}, seeds))
    for case, own in zip(cases, case_seeds, strict=True):
        planned.append(({**fixed, **case}, own))
    unique: dict[str, tuple[dict[str, Any], tuple[int, ...]]] = {}
    for point, own in planned:
        text = canonical_json(point)
        if text in unique:  # the same point twice: run the union of its seeds
            before = unique[text][1]
            own = before + tuple(s for s in own if s not in before)
        unique[text] = (unique.get(text, (point, ()))[0], own)
    points = [point for point, _ in unique.values()]

    names: dict[str, None] = {}
    for point in points:
        names.update(dict.fromkeys(point))
    swept = tuple(
        n for n in names if len({canonical_json({"v": p.get(n)}) for p in points}) > 1
    )
    return SweepSpec(
        path=path,
        name=name.strip(),
        task=task,
        seeds=seeds,
        points=tuple(points),
        description=description,
        swept=swept,
        point_seeds=tuple(own for _, own in unique.values()),
    )


def _parse_seeds(value: Any, fail: Any, where: str = "sweep.seeds") -> tuple[int, ...]:
    if isinstance(value, list):
        if not value:
            raise fail(where, "empty list")
        for seed in value:
            if not _is_int(seed) or seed < 0:
                raise fail(where, f"seeds must be integers >= 0, got {seed!r}")
        if len(set(value)) != len(value):
            raise fail(where, "repeated seed")
        return tuple(value)
    if isinstance(value, dict):
        unknown = sorted(set(value) - {"start", "count"})
        if unknown:
            raise fail(f"{where}.{unknown[0]}", "unknown key (expected start, count)")
        start: Any = value.get("start", 0)
        count: Any = value.get("count")
        if not _is_int(start) or start < 0:
            raise fail(f"{where}.start", f"must be an integer >= 0, got {start!r}")
        if not _is_int(count) or count < 1:
            raise fail(f"{where}.count", f"must be an integer >= 1, got {count!r}")
        return tuple(range(start, start + count))
    raise fail(where, f"must be a list of integers or a table, got {_kind(value)}")


def _check_param(where: str, key: str, value: Any, fail: Any) -> None:
    if key in _RESERVED_PARAMS:
        hint = " (seeds go in [sweep] seeds)" if key == "seed" else ""
        raise fail(where, f"'{key}' is reserved and cannot be a parameter{hint}")
    if isinstance(value, list):
        for item in value:
            if not _is_scalar(item):
                raise fail(where, f"list items must be strings or numbers, got {_kind(item)}")
        return
    if not _is_scalar(value):
        raise fail(where, f"must be a string, number, boolean or list, got {_kind(value)}")
    if isinstance(value, float) and not math.isfinite(value):
        raise fail(where, f"must be finite, got {value}")


def _is_scalar(value: Any) -> bool:
    return isinstance(value, str | int | float | bool)


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _kind(value: Any) -> str:
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "a list"
    return type(value).__name__
