"""Sweep specs: expansion into runs, stable run ids, one-line validation errors."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest

from etswarm.errors import EtswarmError
from etswarm.experiments.spec import DEFAULT_TASK, load_spec, run_id

GOOD = """
[sweep]
name = "size"
seeds = {start = 5, count = 3}

[fixed]
shape = "T"

[grid]
robots = [10, 20]
loss = [0.0, 0.2]

[[cases]]
shape = "dumbbell"
damage = ["split x=0"]
"""


def spec_file(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "sweep.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_grid_and_cases_expand_to_points_times_seeds(tmp_path: Path) -> None:
    spec = load_spec(spec_file(tmp_path, GOOD))
    assert spec.name == "size"
    assert spec.task == DEFAULT_TASK
    assert spec.seeds == (5, 6, 7)
    assert spec.points[0] == {"shape": "T", "robots": 10, "loss": 0.0}
    assert spec.points[3] == {"shape": "T", "robots": 20, "loss": 0.2}
    assert spec.points[4] == {"shape": "dumbbell", "damage": ["split x=0"]}
    runs = spec.runs()
    assert len(runs) == 5 * 3
    assert runs[0].params == {"shape": "T", "robots": 10, "loss": 0.0, "seed": 5}
    assert len({r.run_id for r in runs}) == 15
    assert spec.parameters == ("shape", "robots", "loss", "damage", "seed")
    assert set(spec.swept) == {"shape", "robots", "loss", "damage"}


def test_run_id_is_a_hash_of_canonical_json_independent_of_key_order() -> None:
    params = {"robots": 10, "shape": "T", "seed": 1}
    text = '{"robots":10,"seed":1,"shape":"T"}'
    assert run_id(params) == hashlib.sha256(text.encode()).hexdigest()[:16]
    assert run_id(dict(reversed(list(params.items())))) == run_id(params)
    assert run_id({**params, "seed": 2}) != run_id(params)
    assert json.loads(text) == params


def test_duplicate_points_run_once_and_seed_list_form(tmp_path: Path) -> None:
    text = """
[sweep]
name = "dup"
task = "fake_task:run"
seeds = [3, 1]
[grid]
robots = [10]
[[cases]]
robots = 10
"""
    spec = load_spec(spec_file(tmp_path, text))
    assert [r.params for r in spec.runs()] == [{"robots": 10, "seed": 3}, {"robots": 10, "seed": 1}]
    assert spec.swept == ()


def test_only_fixed_gives_one_point(tmp_path: Path) -> None:
    text = '[sweep]\nname = "one"\nseeds = [0]\n[fixed]\nshape = "T"\n'
    assert load_spec(spec_file(tmp_path, text)).points == ({"shape": "T"},)


@pytest.mark.parametrize(
    ("text", "key"),
    [
        ('[sweep]\nname = "x"\nseeds = [0]\n[grids]\nrobots = [1]\n', "grids"),
        ('[sweep]\nname = "x"\nseeds = [0]\nworkers = 3\n', "sweep.workers"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[grid]\nrobots = []\n', "grid.robots"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[grid]\nrobots = 10\n', "grid.robots"),
        ('[sweep]\nname = "x"\nseeds = "0..9"\n', "sweep.seeds"),
        ('[sweep]\nname = "x"\nseeds = []\n', "sweep.seeds"),
        ('[sweep]\nname = "x"\nseeds = [-1]\n', "sweep.seeds"),
        ('[sweep]\nname = "x"\nseeds = {start = 0}\n', "sweep.seeds.count"),
        ('[sweep]\nname = "x"\nseeds = {start = 0, count = 2, step = 1}\n', "sweep.seeds.step"),
        ('[sweep]\nseeds = [0]\n', "sweep.name"),
        ('[sweep]\nname = "x"\n', "sweep.seeds"),
        ('[sweep]\nname = "x"\ntask = "no_colon"\nseeds = [0]\n', "sweep.task"),
        ('[grid]\nrobots = [1]\n', "sweep"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[fixed]\nrobots = 1\n[grid]\nrobots = [1]\n',
         "grid.robots"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[grid]\nseed = [1, 2]\n', "grid.seed"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[grid]\nrobots = [{a = 1}]\n', "grid.robots"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[fixed]\nwhen = 1979-05-27\n', "fixed.when"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[[cases]]\n', "cases[1]"),
        ('[sweep]\nname = "x"\nseeds = [0]\n[fixed]\nloss = nan\n', "fixed.loss"),
    ],
)
def test_invalid_specs_raise_one_line_naming_file_and_key(
    tmp_path: Path, text: str, key: str
) -> None:
    path = spec_file(tmp_path, text)
    with pytest.raises(EtswarmError) as info:
        load_spec(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: {key}:"), message


def test_missing_file_and_bad_toml_are_one_line_errors(tmp_path: Path) -> None:
    with pytest.raises(EtswarmError, match="cannot read sweep spec"):
        load_spec(tmp_path / "absent.toml")
    with pytest.raises(EtswarmError, match="not valid TOML") as info:
        load_spec(spec_file(tmp_path, "[sweep\nname = 1\n"))
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    "path", sorted((Path(__file__).parents[2] / "examples" / "sweeps").glob("*.toml")),
    ids=lambda p: p.name,
)
def test_example_specs_are_valid(path: Path) -> None:
    spec = load_spec(path)
    assert spec.runs() and spec.task == DEFAULT_TASK


def test_a_case_may_have_its_own_seeds(tmp_path: Path) -> None:
    text = """
[sweep]
name = "own"
seeds = {start = 0, count = 3}
[[cases]]
shape = "T"
[[cases]]
shape = "starfish"
seeds = [7]
[[cases]]
shape = "T"
seeds = [2, 5]
"""
    spec = load_spec(spec_file(tmp_path, text))
    assert spec.points == ({"shape": "T"}, {"shape": "starfish"})
    assert [(r.params["shape"], r.params["seed"]) for r in spec.runs()] == [
        ("T", 0), ("T", 1), ("T", 2), ("T", 5), ("starfish", 7),
    ]
    bad = text.replace("seeds = [7]", "seeds = []")
    with pytest.raises(EtswarmError, match=r"cases\[2\]\.seeds: empty list"):
        load_spec(spec_file(tmp_path, bad))
