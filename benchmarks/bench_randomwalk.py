"""Random-walk benchmark of the world simulator (issue 3).

N robots placed uniformly at random (no overlap) in a walled square of side
50 mm * sqrt(N); comm range 70 mm, no loss, no distance noise, one control loop per tick,
300 simulated seconds by default. The whole run is one compiled call per 30 simulated
seconds (the kernel is loaded or compiled before timing). Prints, per N, robot-ticks per
second (wall clock and CPU time of this process) and times real time, with the machine's
load average, since other jobs on the machine change the figures.

    .venv/bin/python benchmarks/bench_randomwalk.py                 # N = 100 ... 30 000
    .venv/bin/python benchmarks/bench_randomwalk.py -n 1000 -n 10000 --seconds 60
    .venv/bin/python benchmarks/bench_randomwalk.py --repeat 3   # best of 3 runs per N
    .venv/bin/python benchmarks/bench_randomwalk.py --threads 2  # SimParams.threads = 2

On a shared machine the figures swing by tens of percent with the other jobs; ``--repeat``
keeps the fastest run of each size (every run simulates the same seed, so the same work).
Where the time goes: ``benchmarks/profile_phases.py``. Column "multi": share of the
ticks that ran on more than one thread (with ``--threads``; the simulator uses one
thread for a call when that is faster, unless ``--fixed-threads``).
"""

from __future__ import annotations

import json
import os
import time

import click

from etswarm.sim import RandomWalk, SimParams, Simulator, arena_side_for, random_world


def bench_one(n: int, seconds: float, seed: int, threads: int = 1,
              fixed: bool = False) -> dict[str, float]:
    """Run the benchmark for ``n`` robots on ``threads`` threads; return its figures.

    ``fixed``: always run on ``threads`` threads (by default the simulator runs a call
    on one thread when that is faster, e.g. on a machine busy with other work)."""
    params = SimParams(arena_mm=arena_side_for(n), loss=0.0, dist_noise_mm=0.0,
                       threads=threads)
    world = random_world(n, params, seed)
    sim = Simulator(world, RandomWalk(n), params, seed)  # kernel compiled/loaded here
    if threads > 1:
        sim._chooser.adaptive = not fixed
    ticks = round(seconds * params.ticks_per_s)
    chunk = 30 * params.ticks_per_s
    load_before = os.getloadavg()[0]
    wall0, cpu0 = time.perf_counter(), time.process_time()
    done = 0
    while done < ticks:
        done += sim.run_ticks(min(chunk, ticks - done))
    wall = time.perf_counter() - wall0
    cpu = time.process_time() - cpu0
    c = world.counter_dict()
    ticks_on = sim._chooser.ticks_on if threads > 1 else {1: done}
    return {
        "robots": n,
        "threads": threads,
        "ticks": done,
        "wall_s": wall,
        "cpu_s": cpu,
        "mrt_per_s_wall": n * done / wall / 1e6,
        "mrt_per_s_cpu": n * done / cpu / 1e6,
        "x_real_time": done / params.ticks_per_s / wall,
        "ns_per_robot_tick": wall / (n * done) * 1e9,
        "pushes_per_robot_tick": c["pushes"] / (n * done),
        "load_before": load_before,
        "load_after": os.getloadavg()[0],
        "share_multi": 1.0 - ticks_on.get(1, 0) / max(done, 1) if threads > 1 else 0.0,
    }


@click.command()
@click.option("--robots", "-n", "sizes", type=int, multiple=True,
              default=(100, 1000, 3000, 10_000, 30_000), show_default=True)
@click.option("--seconds", type=float, default=300.0, show_default=True,
              help="Simulated seconds per size.")
@click.option("--seed", type=int, default=1, show_default=True)
@click.option("--repeat", type=int, default=1, show_default=True,
              help="Runs per size; the fastest (wall clock) is reported.")
@click.option("--threads", type=int, default=1, show_default=True,
              help="SimParams.threads: threads the tick phases run on.")
@click.option("--fixed-threads", is_flag=True,
              help="Never fall back to one thread (see etswarm.sim.simulator.ThreadChooser).")
@click.option("--json", "json_out", type=click.Path(), default=None,
              help="Also write the figures to this JSON file.")
def main(sizes: tuple[int, ...], seconds: float, seed: int, repeat: int, threads: int,
         fixed_threads: bool, json_out: str | None) -> None:
    """Random-walk benchmark: robot-ticks per second for each N."""
    print(f"random walk, {seconds:g} s simulated, walls at 50 mm*sqrt(N), range 70 mm, "
          f"no loss, no noise; {threads} thread(s), {os.cpu_count()} CPUs "
          f"(cpu rate: robot-ticks per CPU second of all threads)")
    print(f"{'N':>7} {'ticks':>6} {'wall s':>8} {'M rt/s':>7} {'M rt/s cpu':>10} "
          f"{'ns/rt':>6} {'x real':>7} {'push/rt':>7} {'multi':>5}  load before/after")
    rows = []
    for n in sizes:
        runs = [bench_one(n, seconds, seed, threads, fixed_threads)
                for _ in range(max(repeat, 1))]
        r = min(runs, key=lambda row: row["wall_s"])
        rows.append(r)
        print(f"{n:>7} {r['ticks']:>6} {r['wall_s']:>8.2f} {r['mrt_per_s_wall']:>7.2f} "
              f"{r['mrt_per_s_cpu']:>10.2f} {r['ns_per_robot_tick']:>6.0f} "
              f"{r['x_real_time']:>7.0f} {r['pushes_per_robot_tick']:>7.2f} "
              f"{r['share_multi']:>5.2f}  "
              f"{r['load_before']:.2f}/{r['load_after']:.2f}", flush=True)
    if json_out:
        with open(json_out, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
