"""Where the random-walk benchmark's time goes: cycles per phase inside one compiled loop.

Runs the benchmark setup (walls at 50 mm * sqrt(N), range 70 mm, no loss, no noise) with a
copy of the simulator's tick loop that reads the CPU cycle counter around each phase
(radio, control, move, collide), so the phases are timed where they really run: in one
compiled call, with each other's data in the caches. Cycles are converted to ns with
the wall time of the whole call. Also prints the collision work (robots examined and
pushes per robot-tick) over the timed ticks, since it grows as the swarm clusters.

    .venv/bin/python benchmarks/profile_phases.py                    # N = 1000, 10 000
    .venv/bin/python benchmarks/profile_phases.py -n 30000 --warmup 600 --ticks 600

The loop is compiled on every start (about 20 s), not cached.
"""

from __future__ import annotations

import os
import time

import click
import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic

from etswarm.sim import RandomWalk, SimParams, Simulator, arena_side_for, random_world
from etswarm.sim.collide import collide_phase
from etswarm.sim.controllers.randomwalk import randomwalk_step
from etswarm.sim.motion import move_phase
from etswarm.sim.neighbours import grid_sync
from etswarm.sim.radio import radio_phase

PHASES = ("radio", "control", "move", "collide")


@intrinsic
def _cycles(typingctx):
    """The CPU cycle counter (``llvm.readcyclecounter``) as uint64."""

    def codegen(context, builder, signature, args):
        fnty = ir.FunctionType(ir.IntType(64), [])
        fn = builder.module.declare_intrinsic("llvm.readcyclecounter", fnty=fnty)
        return builder.call(fn, [])

    return types.uint64(), codegen


@njit
def _timed_ticks(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                 turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
                 in_dist, counters, dirty, dirty_flag, spare, trig, rng_motion, rng_radio,
                 rng_ctl, mem, cycles):
    """The simulator's tick loop (see etswarm.sim.kernel) with ``cycles`` (4,) uint64
    accumulating the cycles of radio, control, move and collide."""
    n_dirty = grid_sync(grid, pos, present, dirty, dirty_flag, grid.state[2])
    for k in range(n):
        tick = tick0 + k
        t0 = _cycles()
        radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, in_count, in_type, in_data, in_dist, counters, rng_radio)
        t1 = _cycles()
        randomwalk_step(tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                        out_on, out_type, out_data, mem, rng_ctl)
        t2 = _cycles()
        n_dirty = move_phase(cfg, grid, pos, heading, motor, alive, present, speed,
                             turn_rate, dirty, dirty_flag, n_dirty, trig, rng_motion)
        t3 = _cycles()
        n_dirty = collide_phase(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare,
                                counters)
        t4 = _cycles()
        cycles[0] += t1 - t0
        cycles[1] += t2 - t1
        cycles[2] += t3 - t2
        cycles[3] += t4 - t3
    return n


def profile(n: int, warmup: int, ticks: int, seed: int) -> dict[str, float]:
    """Run ``warmup`` ticks with the simulator, then time ``ticks`` ticks phase by phase.

    Returns ns per robot-tick for each phase and in total (wall), and the collision work.
    """
    params = SimParams(arena_mm=arena_side_for(n), loss=0.0, dist_noise_mm=0.0)
    world = random_world(n, params, seed)
    ctl = RandomWalk(n)
    sim = Simulator(world, ctl, params, seed)
    sim.run_ticks(warmup)
    cycles = np.zeros(len(PHASES), dtype=np.uint64)

    def call(k: int) -> float:
        w = world
        t = time.perf_counter()
        _timed_ticks(k, w.tick, sim.cfg, sim.grid, w.pos, w.heading, w.motor, w.led, w.alive,
                     w.present, w.speed, w.turn_rate, w.tx_phase, w.out_on, w.out_type,
                     w.out_data, w.in_count, w.in_type, w.in_data, w.in_dist, w.counters,
                     sim._dirty, sim._dirty_flag, sim._spare, sim._trig, sim.rng_motion,
                     sim.rng_radio, sim.rng_controller, ctl.mem, cycles)
        w.tick += k
        return time.perf_counter() - t

    call(1)  # compile
    cycles[:] = 0
    before = world.counters.copy()
    wall = call(ticks)
    done = world.counters - before
    robot_ticks = n * ticks
    ns_per_cycle = wall / max(int(cycles.sum()), 1) * 1e9
    row: dict[str, float] = {p: float(c) * ns_per_cycle / robot_ticks
                             for p, c in zip(PHASES, cycles, strict=True)}
    row["total"] = wall / robot_ticks * 1e9
    row["examined"] = done[6] / robot_ticks
    row["pushes"] = done[4] / robot_ticks
    return row


@click.command()
@click.option("--robots", "-n", "sizes", type=int, multiple=True, default=(1000, 10_000),
              show_default=True)
@click.option("--warmup", type=int, default=3100, show_default=True,
              help="Ticks run before timing (the swarm clusters over the first minutes).")
@click.option("--ticks", type=int, default=1550, show_default=True, help="Ticks timed.")
@click.option("--seed", type=int, default=1, show_default=True)
def main(sizes: tuple[int, ...], warmup: int, ticks: int, seed: int) -> None:
    """Per-phase ns per robot-tick of the random-walk benchmark."""
    print(f"ns per robot-tick after {warmup} ticks, over {ticks} ticks; "
          f"load average {os.getloadavg()[0]:.2f}")
    print(f"{'N':>7} " + " ".join(f"{p:>8}" for p in PHASES)
          + f" {'total':>8} {'examined/rt':>11} {'pushes/rt':>9}")
    for n in sizes:
        r = profile(n, warmup, ticks, seed)
        print(f"{n:>7} " + " ".join(f"{r[p]:>8.1f}" for p in PHASES)
              + f" {r['total']:>8.1f} {r['examined']:>11.2f} {r['pushes']:>9.2f}", flush=True)


if __name__ == "__main__":
    main()
