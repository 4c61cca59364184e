"""Where the random-walk benchmark's time goes: cycles per phase inside one compiled loop.

Runs the benchmark setup (walls at 50 mm * sqrt(N), range 70 mm, no loss, no noise) with a
copy of the simulator's tick loop that reads the CPU cycle counter around each phase
(radio, control, move, collide), so the phases are timed where they really run: in one
compiled call, with each other's data in the caches. Cycles are converted to ns with
the wall time of the whole call. Also prints the collision work (robots examined and
pushes per robot-tick) over the timed ticks, since it grows as the swarm clusters.

    .venv/bin/python benchmarks/profile_phases.py                    # N = 1000, 10 000
    .venv/bin/python benchmarks/profile_phases.py -n 30000 --warmup 600 --ticks 600
    .venv/bin/python benchmarks/profile_phases.py --threads 2   # the threaded loop
    .venv/bin/python benchmarks/profile_phases.py --et disc1000 [--start 0 --seconds 300]

The loop is compiled on every start (about 20 s), not cached. With ``--threads T`` (> 1)
the threaded tick loop is timed instead, phase for phase as the kernel template in
etswarm.sim.kernel runs it: per thread, the cycles of each phase and of waiting at the
barriers. "control" is the controller's part on every thread plus its one-thread rest;
the contact lists the other threads build meanwhile count as "collide"; work one thread
does alone between phases (grid rebuilds, strip cuts, pass bookkeeping) is "upkeep",
and the others wait for it. The cycle counter runs on while a thread is descheduled, so
on a busy machine every column grows.
"""

from __future__ import annotations

import os
import time

import click
import numpy as np
from numba import njit, prange

from etswarm.algorithm.controller import et_step
from etswarm.sim import RandomWalk, SimParams, Simulator, arena_side_for, random_world
from etswarm.sim.balance import cycle_count
from etswarm.sim.collide import collide_phase
from etswarm.sim.controllers.randomwalk import (
    randomwalk_part,
    randomwalk_rest,
    randomwalk_step,
)
from etswarm.sim.motion import move_phase
from etswarm.sim.neighbours import grid_sync
from etswarm.sim.parallel import (
    CS_CONT,
    CS_DONE,
    CS_STOP,
    collide_after_pass,
    collide_begin,
    collide_end,
    collide_pass_grab,
    control_begin,
    control_done,
    grid_sync_flags,
    move_finish,
    move_part,
    part_bounds,
    prebuild_lists,
    radio_bad,
    radio_count,
    radio_file_part,
    radio_list_part,
)
from etswarm.sim.radio import radio_phase, senders_by_phase
from etswarm.sim.simulator import _NumbaThreads
from etswarm.sim.sync import arrive, atomic_load, release

PHASES = ("radio", "control", "move", "collide")
#: phases of the threaded loop, per thread ("upkeep": grid rebuilds and strip cuts, pass
#: bookkeeping; "wait": at barriers)
MT_PHASES = ("radio", "control", "move", "collide", "upkeep", "wait")


@njit
def _timed_ticks(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                 turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
                 in_dist, counters, dirty, dirty_flag, spare, trig, rng_motion, rng_radio,
                 rng_ctl, mem, cycles):
    """The simulator's tick loop (see etswarm.sim.kernel) with ``cycles`` (4,) int64
    accumulating the cycles of radio, control, move and collide."""
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    n_dirty = grid_sync(grid, pos, present, dirty, dirty_flag, grid.state[2])
    for k in range(n):
        tick = tick0 + k
        t0 = cycle_count()
        radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, in_count, in_type, in_data, in_dist, counters, rng_radio,
                    order, first)
        t1 = cycle_count()
        randomwalk_step(tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                        out_on, out_type, out_data, mem, rng_ctl)
        t2 = cycle_count()
        n_dirty = move_phase(cfg, grid, pos, heading, motor, alive, present, speed,
                             turn_rate, dirty, dirty_flag, n_dirty, trig, rng_motion)
        t3 = cycle_count()
        n_dirty = collide_phase(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare,
                                counters)
        t4 = cycle_count()
        cycles[0] += t1 - t0
        cycles[1] += t2 - t1
        cycles[2] += t3 - t2
        cycles[3] += t4 - t3
    return n


@njit
def _timed_thread(p, n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                  turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
                  in_dist, counters, flags, trig, rng_ctl, mem, scr, cycles, order, first):
    """Thread ``p`` of the threaded loop (the template in etswarm.sim.kernel, phase for
    phase), ``cycles[p]`` (6,) counting the cycles of MT_PHASES. The last thread to
    arrive at a barrier does the one-thread work ("upkeep"; the controller counts as
    "control"); the others' contact-list building during the controller counts as
    "collide"."""
    parts = scr.parts[0]
    sync = scr.sync
    cs = scr.cstate
    c = cycles[p]
    lo, hi = part_bounds(p, pos.shape[0], scr)
    for k in range(n):
        tick = tick0 + k
        t0 = cycle_count()
        radio_list_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                        out_data, scr, order, first)
        t1 = cycle_count()
        if arrive(sync, parts):
            release(sync)
        t2 = cycle_count()
        radio_file_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                        out_data, in_count, in_type, in_data, in_dist, counters, scr, order,
                        first)
        t3 = cycle_count()
        bad = radio_bad(scr)
        if not bad:
            randomwalk_part(lo, hi, tick, alive, in_count, in_type, in_data, in_dist, motor,
                            led, out_on, out_type, out_data, mem)
        t4 = cycle_count()
        c[0] += (t1 - t0) + (t3 - t2)
        c[1] += t4 - t3
        c[5] += t2 - t1
        if arrive(sync, parts):
            t45 = cycle_count()
            radio_count(counters, scr)
            control_begin(scr)
            release(sync)
            if bad:
                randomwalk_part(0, pos.shape[0], tick, alive, in_count, in_type, in_data,
                                in_dist, motor, led, out_on, out_type, out_data, mem)
            randomwalk_rest(tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                            out_on, out_type, out_data, mem, rng_ctl)
            control_done(scr)
            t5 = cycle_count()
            c[5] += t45 - t4
            c[1] += t5 - t45
        else:
            t45 = cycle_count()
            prebuild_lists(p, cfg, grid, scr)
            t5 = cycle_count()
            c[5] += t45 - t4
            c[3] += t5 - t45
        if arrive(sync, parts):
            release(sync)
        t6 = cycle_count()
        move_part(p, tick, cfg, grid, pos, heading, motor, alive, present, speed, turn_rate,
                  flags, trig, scr)
        t7 = cycle_count()
        c[5] += t6 - t5
        c[2] += t7 - t6
        if arrive(sync, parts):
            t8 = cycle_count()
            move_finish(grid, pos, present, flags, scr)
            collide_begin(grid, scr)
            release(sync)
            t9 = cycle_count()
            c[5] += t8 - t7
            c[4] += t9 - t8
        else:
            c[5] += cycle_count() - t7
        while atomic_load(cs, CS_CONT) != 0:
            t = cycle_count()
            collide_pass_grab(p, cfg, grid, pos, motor, flags, scr)
            t3 = cycle_count()
            c[3] += t3 - t
            if arrive(sync, parts):
                t4 = cycle_count()
                collide_after_pass(cfg, grid, pos, present, flags, scr)
                if cs[CS_CONT] == 0:
                    collide_end(grid, pos, present, flags, counters, scr)
                    cs[CS_STOP] = 1 if mem[0][0] != 0 else 0
                    cs[CS_DONE] = k + 1
                release(sync)
                t5 = cycle_count()
                c[5] += t4 - t3
                c[4] += t5 - t4
            else:
                c[5] += cycle_count() - t3


@njit(parallel=True)
def _timed_threaded(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                    turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type,
                    in_data, in_dist, counters, flags, trig, rng_ctl, mem, scr, cycles):
    grid_sync_flags(grid, pos, present, flags, scr.robot_flag)
    scr.cstate[CS_DONE] = 0
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    for p in prange(scr.parts[0]):
        _timed_thread(p, n, tick0, cfg, grid, pos, heading, motor, led, alive, present,
                      speed, turn_rate, tx_phase, out_on, out_type, out_data, in_count,
                      in_type, in_data, in_dist, counters, flags, trig, rng_ctl, mem, scr,
                      cycles, order, first)
    return n


def profile_threaded(n: int, warmup: int, ticks: int, seed: int, threads: int,
                     one_thread: bool = False) -> list[dict[str, float]]:
    """As :func:`profile` for the threaded loop: one row per thread (ns per robot-tick
    of each of MT_PHASES), plus wall-clock and CPU ns per robot-tick in every row.
    ``one_thread``: run the threaded loop on one thread (its work without waiting)."""
    params = SimParams(arena_mm=arena_side_for(n), loss=0.0, dist_noise_mm=0.0,
                       threads=threads)
    world = random_world(n, params, seed)
    ctl = RandomWalk(n)
    sim = Simulator(world, ctl, params, seed)
    sim.run_ticks(warmup)
    scr = sim._scratch
    assert scr is not None
    scr.parts[0] = parts = sim._threads_used() if one_thread is False else 1
    cycles = np.zeros((parts, len(MT_PHASES)), dtype=np.int64)

    def call(k: int) -> tuple[float, float]:
        w = world
        t = time.perf_counter()
        c = time.process_time()
        with _NumbaThreads(parts):
            _timed_threaded(k, w.tick, sim.cfg, sim.grid, w.pos, w.heading, w.motor, w.led,
                            w.alive, w.present, w.speed, w.turn_rate, w.tx_phase, w.out_on,
                            w.out_type, w.out_data, w.in_count, w.in_type, w.in_data,
                            w.in_dist, w.counters, sim._dirty_flag, sim._trig,
                            sim.rng_controller, ctl.mem, scr, cycles)
        w.tick += k
        return time.perf_counter() - t, time.process_time() - c

    call(1)  # compile
    cycles[:] = 0
    wall, cpu = call(ticks)
    robot_ticks = n * ticks
    ns_per_cycle = wall / max(int(cycles[0].sum()), 1) * 1e9
    rows = []
    for p in range(parts):
        row = {ph: float(cycles[p, q]) * ns_per_cycle / robot_ticks
               for q, ph in enumerate(MT_PHASES)}
        row["total"] = wall / robot_ticks * 1e9
        row["cpu"] = cpu / robot_ticks * 1e9
        rows.append(row)
    return rows


def profile(n: int, warmup: int, ticks: int, seed: int) -> dict[str, float]:
    """Run ``warmup`` ticks with the simulator, then time ``ticks`` ticks phase by phase.

    Returns ns per robot-tick for each phase and in total (wall), and the collision work.
    """
    params = SimParams(arena_mm=arena_side_for(n), loss=0.0, dist_noise_mm=0.0)
    world = random_world(n, params, seed)
    ctl = RandomWalk(n)
    sim = Simulator(world, ctl, params, seed)
    sim.run_ticks(warmup)
    cycles = np.zeros(len(PHASES), dtype=np.int64)

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


@njit
def _timed_et_ticks(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                    turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
                    in_dist, counters, dirty, dirty_flag, spare, trig, rng_motion, rng_radio,
                    rng_ctl, mem, cycles):
    """:func:`_timed_ticks` with the ET controller (``et_step``); returns the ticks run
    (fewer when a robot raised the stop flag)."""
    stop = mem[0]
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    n_dirty = grid_sync(grid, pos, present, dirty, dirty_flag, grid.state[2])
    for k in range(n):
        tick = tick0 + k
        t0 = cycle_count()
        radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, in_count, in_type, in_data, in_dist, counters, rng_radio,
                    order, first)
        t1 = cycle_count()
        et_step(tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                out_on, out_type, out_data, mem, rng_ctl)
        t2 = cycle_count()
        n_dirty = move_phase(cfg, grid, pos, heading, motor, alive, present, speed,
                             turn_rate, dirty, dirty_flag, n_dirty, trig, rng_motion)
        t3 = cycle_count()
        n_dirty = collide_phase(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare,
                                counters)
        t4 = cycle_count()
        cycles[0] += t1 - t0
        cycles[1] += t2 - t1
        cycles[2] += t3 - t2
        cycles[3] += t4 - t3
        if stop[0] != 0:
            return k + 1
    return n


def profile_et(shape: str, start_s: float, seconds: float) -> dict[str, float]:
    """An ET run of ``shape`` (cluster layout, seed 0; "disc1000" as in bench_et.py) from
    ``start_s`` simulated s for ``seconds``: µs per tick of each phase (cycles scaled by
    the process's CPU time) and in total (CPU time), and the robots' states at the end.
    The host's answers to Leaders are given; its measure checks are left out."""
    import tempfile
    from pathlib import Path

    from bench_et import shape_path

    from etswarm.algorithm.run import ETRun, RunConfig

    run = ETRun(RunConfig(shape=shape_path(shape, Path(tempfile.mkdtemp())), seed=0,
                          max_time_s=1e9, layout="cluster"))
    run.advance(round(start_s * run.ticks_per_s))
    sim, w, ctl = run.sim, run.world, run.controller
    cycles = np.zeros(len(PHASES), dtype=np.int64)

    def call(k: int) -> int:
        return int(_timed_et_ticks(
            k, w.tick, sim.cfg, sim.grid, w.pos, w.heading, w.motor, w.led, w.alive,
            w.present, w.speed, w.turn_rate, w.tx_phase, w.out_on, w.out_type, w.out_data,
            w.in_count, w.in_type, w.in_data, w.in_dist, w.counters, sim._dirty,
            sim._dirty_flag, sim._spare, sim._trig, sim.rng_motion, sim.rng_radio,
            sim.rng_controller, ctl.mem, cycles))

    call(0)  # compile
    total = round(seconds * run.ticks_per_s)
    cpu0 = time.process_time()
    done = 0
    while done < total:
        k = call(min(310, total - done))
        w.tick += k
        done += k
        if ctl.stop[0]:
            run._answer_requests()
    cpu = time.process_time() - cpu0
    us_per_cycle = cpu / max(int(cycles.sum()), 1) * 1e6
    row: dict[str, float] = {p: float(c) * us_per_cycle / done
                             for p, c in zip(PHASES, cycles, strict=True)}
    row["total"] = cpu / done * 1e6
    row["states"] = np.bincount(ctl.states, minlength=8).tolist()  # type: ignore[assignment]
    return row


@click.command()
@click.option("--et", "et_shape", default=None,
              help="Time an ET run of this shape instead (e.g. disc1000, bigdisc, T).")
@click.option("--start", type=float, default=0.0, show_default=True,
              help="With --et: simulated s run before timing.")
@click.option("--seconds", type=float, default=300.0, show_default=True,
              help="With --et: simulated s timed.")
@click.option("--robots", "-n", "sizes", type=int, multiple=True, default=(1000, 10_000),
              show_default=True)
@click.option("--warmup", type=int, default=3100, show_default=True,
              help="Ticks run before timing (the swarm clusters over the first minutes).")
@click.option("--ticks", type=int, default=1550, show_default=True, help="Ticks timed.")
@click.option("--seed", type=int, default=1, show_default=True)
@click.option("--threads", type=int, default=1, show_default=True,
              help="> 1: time the threaded loop on this many threads.")
@click.option("--one-thread", is_flag=True, help="With --threads: run it on one thread.")
def main(et_shape: str | None, start: float, seconds: float, sizes: tuple[int, ...],
         warmup: int, ticks: int, seed: int, threads: int, one_thread: bool) -> None:
    """Per-phase ns per robot-tick of the random-walk benchmark (or, with --et, µs per tick
    of an ET run)."""
    if et_shape is not None:
        r = profile_et(et_shape, start, seconds)
        print(f"ET {et_shape} from {start:.0f} s for {seconds:.0f} s, µs per tick (CPU time); "
              f"load average {os.getloadavg()[0]:.2f}")
        print(" ".join(f"{p} {r[p]:.1f}" for p in (*PHASES, "total")) + f"; states {r['states']}")
        return
    if threads > 1:
        print(f"threaded loop: ns per robot-tick per thread after {warmup} ticks, over "
              f"{ticks} ticks; load average {os.getloadavg()[0]:.2f}")
        print(f"{'N':>7} {'thread':>6} " + " ".join(f"{p:>8}" for p in MT_PHASES)
              + f" {'wall':>8} {'cpu':>8}")
        for n in sizes:
            rows = profile_threaded(n, warmup, ticks, seed, threads, one_thread)
            for p, r in enumerate(rows):
                print(f"{n:>7} {p:>6} " + " ".join(f"{r[q]:>8.1f}" for q in MT_PHASES)
                      + f" {r['total']:>8.1f} {r['cpu']:>8.1f}", flush=True)
        return
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
