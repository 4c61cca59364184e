"""ET speed and formation figures.

Speed: robot-ticks per wall second and x real time of an ET run (formation in progress)
for a shape of N cells with N robots, after the kernel is compiled.
Formation: formed share, median formation time (simulated) and median wall time over seeds,
and the number of runs that ended with a tag held by two robots.

    .venv/bin/python benchmarks/bench_et.py speed [--seconds 600] [--threads 2]
        [--control-threads 2] [--message-delay 1] [--window 1800]
    .venv/bin/python benchmarks/bench_et.py formation [--seeds 20] [--first-seed 0]
        [--shapes T,dumbbell,starfish] [--et NAME=VALUE ...]
        [--jobs 2] [--et NAME=VALUE ...] [--out runs.jsonl] [--layout queue|cluster]
    .venv/bin/python benchmarks/bench_et.py hash [--seconds 600] [--threads 2] [--control-threads 2]
        [--shapes T,disc1000] [--hash-seeds 0,1] [--layout queue] [--damage SPEC]

``speed --shapes T,disc1000`` times only those shapes (default T, bigdisc, disc1000).
``--window S`` also prints each S simulated s's speed and the robots' states: a formation
slows as more robots search and more are placed.
Hash: a SHA-256 digest of the final ``pos``, ``heading`` and ``ri`` (the robots' memory)
of each run, to check that a change of the code keeps the results byte-identical.

With ``--threads T`` the speed runs use ``SimParams(threads=T)`` (the threaded loop; the ET
controller's per-robot work runs on every thread; "on T" is the share of ticks the thread
chooser ran on T threads). With ``--control-threads C`` they use
``SimParams(control_threads=C)``: the serial loop with the controller's per-robot work on C
threads, results identical to one thread ("on C" as above). ``--message-delay 1``
(``SimParams.message_delay_ticks``) reads every message one tick later; with
``--control-threads`` the radio then runs beside the controller's work. It changes the
results (the same for any thread count), so ``formation`` takes it too. With ``--jobs J`` the
formation runs go to J worker processes (one per core: the wall times stay per run, as long
as nothing else loads the machine).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import statistics
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any, TextIO

import numpy as np

from etswarm.algorithm.params import ETParams, parse_et_option
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.sim.params import SimParams


def disc_rows(radius: float) -> list[str]:
    """Text bitmap rows of the lattice sites within ``radius`` spacings of the origin."""
    r = int(np.ceil(radius)) + 1
    rows = []
    for i in range(-r, r + 1):
        y = -i
        row = ""
        for j in range(-2 * r, 2 * r + 1):
            xx = j - y / 2  # skewed lattice: each row half a spacing left of the one below
            yy = y * np.sqrt(3) / 2
            row += "1" if xx * xx + yy * yy <= radius * radius else "0"
        rows.append(row)
    return rows


def disc_bitmap(cells: int, path: Path) -> Path:
    """Write a round text bitmap with the number of 1s nearest to ``cells``.

    A lattice site covers sqrt(3)/2 square spacings, so the radius starts from
    sqrt(cells * sqrt(3) / (2 pi)) and steps by 0.01 spacing to the nearest count.
    """
    start = np.sqrt(cells * np.sqrt(3) / (2 * np.pi))
    radii = start + np.arange(-50, 51) * 0.01
    counts = [sum(row.count("1") for row in disc_rows(radius)) for radius in radii]
    best = radii[int(np.argmin([abs(c - cells) for c in counts]))]
    path.write_text("\n".join(disc_rows(best)) + "\n")
    return path


SPEED_SHAPES = ("T", "bigdisc", "disc1000")
#: The written discs, by name: the number of cells asked for. Until session 20 "disc1000"
#: was a disc of 1311 cells (its radius was worked out for square pixels); "disc1300" keeps
#: about that size (1303 cells) for comparison with the earlier figures.
DISCS = {"disc1000": 1000, "disc1300": 1300}


def shape_path(name: str, tmp: Path) -> str:
    """The shape argument for ``name`` (a name in ``DISCS``: a written disc bitmap)."""
    if name in DISCS:
        return str(disc_bitmap(DISCS[name], tmp / f"{name}.txt"))
    return name


def speed(
    seconds: float, sim: SimParams, shapes: tuple[str, ...] = SPEED_SHAPES, window: float = 0.0,
    et_options: dict[str, Any] | None = None, seed: int = 0,
) -> None:
    """Print each shape's speed over ``seconds`` simulated s of seed ``seed``'s run; with
    ``window`` > 0, first a line per ``window`` simulated s with that stretch's speed and
    the robots' states (``et_options``: ETParams fields, as ``--et`` gives them)."""
    tmp = Path(tempfile.mkdtemp())
    print(f"load average {os.getloadavg()}, threads {sim.threads}, control threads "
          f"{sim.control_threads}, message delay {sim.message_delay_ticks}, "
          f"ET options {et_options or 'default'}")
    header = ("shape", "robots", "sim s", "wall s", "cpu s", "robot-ticks/s", "x real")
    print("{:>10} {:>7} {:>7} {:>7} {:>7} {:>14} {:>8}".format(*header))
    for name in shapes:
        shape = shape_path(name, tmp)
        run = ETRun(
            RunConfig(shape=shape, seed=seed, max_time_s=seconds, layout="cluster",
                      et=ETParams(**(et_options or {}))),
            sim_params=sim,
        )
        run.advance(31)  # compile / load the kernel outside the timing
        t0 = time.perf_counter()
        c0 = time.process_time()
        ticks0 = run.world.tick
        end = round(seconds * 31)
        step = round(window * 31) if window > 0 else end
        while run.world.tick < end:
            w0 = time.perf_counter()
            t_from = run.world.tick
            run.advance(min(step, end - run.world.tick))
            if window > 0:
                span = (run.world.tick - t_from) / 31
                states = np.bincount(run.controller.states, minlength=len(State))
                counts = " ".join(f"{st.name.lower()} {states[st]}" for st in State if states[st])
                print(f"{name:>10} {t_from / 31:>7.0f}-{run.world.tick / 31:.0f} s "
                      f"{span / (time.perf_counter() - w0):>6.0f}x  {counts}", flush=True)
        wall = time.perf_counter() - t0
        cpu = time.process_time() - c0
        ticks = run.world.tick - ticks0
        rt = run.world.n * ticks / wall
        multi = ""
        most = max(sim.threads, sim.control_threads)
        if most > 1 and hasattr(run.sim, "_chooser"):
            on = run.sim._chooser.ticks_on
            multi = f"  on {most}: {on.get(most, 0) / max(1, sum(on.values())):.2f}"
        print(
            f"{name:>10} {run.world.n:>7} {ticks / 31:>7.0f} {wall:>7.2f} {cpu:>7.2f} {rt:>14,.0f} "
            f"{ticks / 31 / wall:>8.0f}{multi}"
        )


def run_hash(run: ETRun) -> str:
    """SHA-256 (first 16 hex digits) of the run's final positions, headings and memory."""
    digest = hashlib.sha256()
    for array in (run.world.pos, run.world.heading, run.controller.ri):
        digest.update(np.ascontiguousarray(array).tobytes())
    return digest.hexdigest()[:16]


def hashes(
    seconds: float, sim: SimParams, shapes: list[str], seeds: list[int], layout: str,
    damage: tuple[str, ...] = (), et_options: dict[str, Any] | None = None,
) -> None:
    """Print the final-state hash of each (shape, seed) run of ``seconds`` simulated s
    (``et_options``: ETParams fields, as ``--et`` gives them)."""
    tmp = Path(tempfile.mkdtemp())
    for name in shapes:
        for seed in seeds:
            run = ETRun(
                RunConfig(shape=shape_path(name, tmp), seed=seed, max_time_s=seconds,
                          layout=layout, damage=damage, et=ETParams(**(et_options or {}))),
                sim_params=sim,
            )
            run.advance(round(seconds * 31))
            states = np.bincount(run.controller.states, minlength=8).tolist()
            ctl = run.controller
            world = run.world
            # the whole memory and radio state, and what the host noted
            more = hashlib.sha256()
            for array in (ctl.nb, ctl.nb_dist, ctl.walk_seen, ctl.held, world.out_on,
                          world.out_type, world.out_data, world.motor, world.led):
                more.update(np.ascontiguousarray(array).tobytes())
            more.update(repr((run.events, run.formed_at_s, run.settled_at_s,
                              sorted(run.reformed_at.items()))).encode())
            print(f"{name:>10} seed {seed} threads {sim.threads} layout {layout} {seconds:.0f} s: "
                  f"{run_hash(run)}  states {states}  events {len(run.events)}  "
                  f"memory+events {more.hexdigest()[:16]}", flush=True)


def formation_run(
    shape: str, seed: int, max_time_s: float, et_options: dict[str, Any], sim: SimParams,
    layout: str = "queue",
) -> dict[str, Any]:
    """The summary of one formation run (``shape``: a shape argument or a name in
    ``DISCS``)."""
    config = RunConfig(shape=shape_path(shape, Path(tempfile.mkdtemp())), seed=seed,
                       max_time_s=max_time_s, layout=layout, et=ETParams(**et_options))
    return ETRun(config, sim_params=sim).run()


def parse_option(text: str) -> tuple[str, Any]:
    """``NAME=VALUE`` for ``--et``: any ETParams field."""
    try:
        return parse_et_option(text)
    except EtswarmError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


def formation(
    seeds: int, shapes: list[str], max_time_s: float, jobs: int, et_options: dict[str, Any],
    first_seed: int = 0, sim: SimParams | None = None, out: TextIO | None = None,
    layout: str = "queue",
) -> None:
    """Formation figures over seeds ``first_seed .. first_seed + seeds - 1`` of each shape;
    with ``out``, every run's JSON summary too, one line each (shape by shape, seed order).
    "false alarms": runs in which an election kept the target (``false_alarm``); "torn":
    formed runs whose robots stand torn apart somewhere (``stretched_links``)."""
    print(
        f"load average {os.getloadavg()}, {jobs} job(s), ET options {et_options or 'default'}, "
        f"seeds {first_seed}-{first_seed + seeds - 1}, "
        f"message delay {(sim or SimParams()).message_delay_ticks}, layout {layout}"
    )
    seed_range = range(first_seed, first_seed + seeds)
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = {
            (shape, seed): pool.submit(formation_run, shape, seed, max_time_s, et_options,
                                        sim or SimParams(), layout)
            for shape in shapes
            for seed in seed_range
        }
    print(
        f"{'shape':>10} {'formed':>8} {'median sim (min)':>17} {'median wall (s)':>16} "
        f"{'median jaccard':>15} {'shared tags':>12} {'false alarms':>13} {'torn':>5}"
    )
    for shape in shapes:
        times, walls, jac, formed, shared, kept, torn = [], [], [], 0, 0, 0, 0
        for seed in seed_range:
            s = futures[shape, seed].result()
            if out is not None:
                out.write(json.dumps(s) + "\n")
            kept += any(e["kind"] == "target_kept" for e in s["events"])
            formed += s["formed"]
            if s["formed"]:
                times.append(s["formation_time_s"] / 60)
                torn += any(c.get("stretched_links") for c in s["components"])
            walls.append(s["wall_time_s"])
            jac.append(s["jaccard"])
            shared += bool(s["duplicate_tags"])  # runs with a tag held by two robots
        med = f"{statistics.median(times):.1f}" if times else "-"
        print(
            f"{shape:>10} {formed:>4}/{seeds:<3} {med:>17} {statistics.median(walls):>16.1f} "
            f"{statistics.median(jac):>15.3f} {shared:>12} {kept:>13} {torn:>5}"
        )
        if out is not None:
            out.flush()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("what", choices=["speed", "formation", "hash"])
    parser.add_argument("--seconds", type=float, default=600.0)
    parser.add_argument("--window", type=float, default=0.0,
                        help="speed: also print the speed and states every WINDOW simulated s")
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--speed-seed", type=int, default=0,
                        help="speed: the seed of the timed runs (another course, another speed)")
    parser.add_argument(
        "--first-seed", type=int, default=0,
        help="formation: first seed (fresh seeds for comparisons: the defaults were tuned on 0-9)",
    )
    parser.add_argument(
        "--shapes", default=None,
        help="formation: default T,dumbbell,starfish; speed: T,bigdisc,disc1000; hash: T,disc1000",
    )
    parser.add_argument(
        "--layout", default=None, choices=["queue", "cluster"],
        help="repository layout: hash runs default to cluster, formation runs to queue",
    )
    parser.add_argument("--damage", action="append", default=[], help="hash: damage spec")
    parser.add_argument("--max-time", type=float, default=4 * 3600.0)
    parser.add_argument("--hash-seeds", default=None, help="hash: seeds, default 0,1")
    parser.add_argument("--threads", type=int, default=1, help="SimParams.threads (speed)")
    parser.add_argument("--control-threads", type=int, default=1,
                        help="SimParams.control_threads (speed, hash, formation)")
    parser.add_argument("--message-delay", type=int, default=0, choices=[0, 1],
                        help="SimParams.message_delay_ticks (speed, hash, formation)")
    parser.add_argument("--native-math", dest="portable_math", action="store_false",
                        help="SimParams.portable_math off: the platform's maths library "
                             "(speed, hash, formation; the default's runs up to session 52)")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes (formation)")
    parser.add_argument(
        "--et", type=parse_option, action="append", default=[], metavar="NAME=VALUE",
        help="An ETParams field for every formation, speed or hash run, e.g. pair_aim_mm=-1 "
        "(repeatable).",
    )
    parser.add_argument(
        "--out", type=argparse.FileType("a"), default=None, metavar="FILE",
        help="formation: also append every run's JSON summary to FILE (one line per run).",
    )
    args = parser.parse_args()
    try:
        sim = SimParams(threads=args.threads, control_threads=args.control_threads,
                        message_delay_ticks=args.message_delay,
                        portable_math=args.portable_math)
    except EtswarmError as err:
        parser.error(str(err))
    if args.what == "speed":
        speed(args.seconds, sim, tuple((args.shapes or ",".join(SPEED_SHAPES)).split(",")),
              args.window, dict(args.et), args.speed_seed)
    elif args.what == "hash":
        seeds = [int(s) for s in (args.hash_seeds or "0,1").split(",")]
        hashes(args.seconds, sim, (args.shapes or "T,disc1000").split(","), seeds,
               args.layout or "cluster", tuple(args.damage), dict(args.et))
    else:
        shapes = (args.shapes or "T,dumbbell,starfish").split(",")
        formation(args.seeds, shapes, args.max_time, args.jobs, dict(args.et), args.first_seed,
                  sim, args.out, args.layout or "queue")


if __name__ == "__main__":
    main()
