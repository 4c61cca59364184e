"""Recorder round trip, interrupted runs, the sim command, kernel disk cache, slow path."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numba import njit

from etswarm.errors import EtswarmError
from etswarm.sim import RandomWalk, SimParams, Simulator, World, random_world
from etswarm.sim.recorder import Recorder, load_recording, write_final_state
from etswarm.sim.runner import run_for


def small_sim(seed: int = 2, n: int = 40) -> Simulator:
    p = SimParams(arena_mm=400.0)
    return Simulator(random_world(n, p, seed), RandomWalk(n), p, seed)


def test_recording_round_trip(tmp_path: Path) -> None:
    sim = small_sim()
    path = tmp_path / "run.npz"
    with Recorder(path, sim.world, every=5, meta={"note": "x"}) as rec:
        assert run_for(sim, 100, rec) == 100
    r = load_recording(path)
    assert r.tick.tolist() == list(range(0, 101, 5))
    assert r.pos.shape == (21, 40, 2) and r.pos.dtype == np.float32
    assert r.header["every"] == 5 and r.header["note"] == "x" and r.n_robots == 40
    assert np.array_equal(r.pos[-1], sim.world.pos.astype(np.float32))
    assert np.array_equal(r.led[-1], sim.world.led)
    assert not np.array_equal(r.pos[0], r.pos[-1])
    write_final_state(tmp_path / "final.json", sim.world, seed=2)
    final = json.loads((tmp_path / "final.json").read_text())
    assert final["tick"] == 100 and len(final["pos"]) == 40 and final["seed"] == 2


def test_recorder_keeps_frames_when_the_run_is_interrupted(tmp_path: Path) -> None:
    sim = small_sim()
    path = tmp_path / "cut.npz"
    calls = 0

    def stop_after_three(_: int) -> None:
        nonlocal calls
        calls += 1
        if calls == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt), Recorder(path, sim.world, every=1) as rec:
        run_for(sim, 1000, rec, stop_after_three)
    r = load_recording(path)
    assert r.n_frames == 4  # tick 0 and after each of the three one-tick calls
    assert r.tick.tolist() == [0, 1, 2, 3]


def test_loading_a_non_recording_is_a_clear_error(tmp_path: Path) -> None:
    bad = tmp_path / "x.npz"
    bad.write_bytes(b"not a zip")
    with pytest.raises(EtswarmError, match="not a readable etswarm recording"):
        load_recording(bad)
    with pytest.raises(EtswarmError, match="not found"):
        load_recording(tmp_path / "missing.npz")


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "etswarm.cli.main", *args],
                          capture_output=True, text=True, timeout=300)


def test_sim_command_runs_and_writes_outputs(tmp_path: Path) -> None:
    out = run_cli("sim", "--robots", "30", "--seconds", "3", "--seed", "4", "--loss", "0.2",
                  "--out", str(tmp_path), "--every", "31", "--no-progress")
    assert out.returncode == 0, out.stderr
    assert "robot-ticks/s" in out.stdout and "ticks             93" in out.stdout
    rec = load_recording(tmp_path / "recording.npz")
    assert rec.tick.tolist() == [0, 31, 62, 93]
    assert json.loads((tmp_path / "final_state.json").read_text())["tick"] == 93


def test_sim_command_errors_are_one_line(tmp_path: Path) -> None:
    cfg = tmp_path / "c.toml"
    cfg.write_text("colour = 3\n")
    out = run_cli("sim", "--config", str(cfg), "--no-progress")
    assert out.returncode == 2
    assert out.stderr.strip() == f"etswarm: error: unknown sim parameter 'colour' in {cfg}"
    out = run_cli("sim", "--noise", "-1", "--no-progress")
    assert out.returncode == 2 and "dist_noise_mm" in out.stderr and "Traceback" not in out.stderr


def test_a_second_process_loads_the_kernel_from_the_disk_cache() -> None:
    code = (
        "from etswarm.sim import RandomWalk, SimParams, Simulator, random_world\n"
        "p = SimParams(arena_mm=300.0)\n"
        "s = Simulator(random_world(20, p, 1), RandomWalk(20), p, 1)\n"
        "print(len(s._kernel.stats.cache_hits), len(s._kernel.stats.cache_misses))\n"
    )
    first = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert first.returncode == 0, first.stderr
    second = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert second.stdout.split() == ["1", "0"], second.stdout + second.stderr


@njit(cache=True)
def pattern_step(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on,
                 out_type, out_data, mem, rng):
    for i in range(alive.shape[0]):
        if alive[i]:
            motor[i] = 1 + (tick // 20 + i) % 3
            led[i] = in_count[i]
            out_on[i] = True
            out_data[i, 0] = i


class PatternFast:
    def __init__(self) -> None:
        self.step = pattern_step
        self.mem = (np.zeros(1, dtype=np.int64),)


class PatternSlow:
    """The same controller written over arrays in numpy (slow path)."""

    def step(self, view) -> None:
        idx = np.arange(view.alive.shape[0])
        on = view.alive
        view.motor[on] = (1 + (view.tick // 20 + idx) % 3)[on]
        view.led[on] = view.in_count[on]
        view.out_on[on] = True
        view.out_data[on, 0] = idx[on]


def test_slow_path_runs_the_same_phases_as_the_compiled_loop() -> None:
    p = SimParams(arena_mm=350.0, loss=0.3, dist_noise_mm=1.0)
    worlds = [random_world(50, p, 6) for _ in range(2)]
    worlds[0].kill([3, 7])
    worlds[1].kill([3, 7])
    fast = Simulator(worlds[0], PatternFast(), p, 6)
    slow = Simulator(worlds[1], PatternSlow(), p, 6)
    assert fast.fast and not slow.fast
    fast.run_ticks(150)
    slow.run_ticks(150)
    for name, arr in fast.world.state_arrays().items():
        assert np.array_equal(arr, slow.world.state_arrays()[name]), name
    assert np.array_equal(fast.world.counters, slow.world.counters)


def test_world_and_simulator_inputs_are_checked() -> None:
    with pytest.raises(EtswarmError, match="shape"):
        World.from_positions(np.zeros((3, 3)))
    with pytest.raises(EtswarmError, match="inbox capacity"):
        Simulator(World(2, inbox_capacity=4), PatternSlow(), SimParams())
