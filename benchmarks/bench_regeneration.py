"""Regeneration figures: per shape, damage and census method, over seeds, how remnants fare.

    .venv/bin/python benchmarks/bench_regeneration.py [--seeds 10] [--max-time 14400]
        [--census tree|walk|both] [--jobs 2] [--case "triangle:split x=0" ...]
    .venv/bin/python benchmarks/bench_regeneration.py --suite issue5 --seeds 20 --jobs 2 \
        --census tree --out runs.jsonl    # the 18 cases the closing notes report

A case is ``SHAPE:DAMAGE`` or ``SHAPE/N:DAMAGE`` (N robots forming scale(SHAPE, N), --fit).
For each case and census method, one Markdown table row: runs whose first formation
completed (only those count further); runs in which every remnant of at least
``--min-robots`` robots (6, the issue's bar) re-formed its scaled target (success); runs
in which each such remnant has as many robots as its census counted ("counted": not so
when a remnant took over a sibling remnant's smaller target, or its census missed
robots); of the re-formed runs, those with a remnant whose robots stand torn apart ("torn",
``stretched_links``); how many of the smaller remnants of 3 or more robots re-formed; at
most one Leader per remnant; runs with a tag held twice in a remnant; the median time from damage to
re-formed. Then the census over all censuses taken (one per remnant that elected a
Leader): exact ones, error (count minus the remnant's robots at the census; mean and max
|error|), mean time from Leader to count and from the election's start to count
(simulated s), and how the censuses ended (tree; walks: returned, enclosed, stuck,
timeout, lost). ``--out FILE`` keeps every run's JSON summary.

By default a run has ``--max-time`` in all, so a slow first formation leaves less time to
regrow. With ``--regrow-time S`` the first formation has ``--max-time`` (runs whose first
formation took longer do not count) and every remnant has S simulated seconds from the
damage to re-form.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
from collections import Counter
from concurrent.futures import ProcessPoolExecutor
from typing import Any

from etswarm.algorithm.params import ETParams, parse_et_option
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError
from etswarm.sim.params import SimParams

CASES = (
    ("triangle", "split x=0"),
    ("triangle", "remove random=0.2"),
    ("triangle", "kill ids=3,4,5"),
    ("hexagon", "split x=0"),
    ("T", "split x=0"),
)

#: The issue's bar (issue 5): seven shapes cut through the middle both ways, and random
#: removal and killing on two of them; ``--suite issue5``.
ISSUE5_CASES = (
    *(
        (shape, f"split {axis}=mid")
        for shape in ("T", "dumbbell", "starfish", "L", "arrow", "plus", "H")
        for axis in ("x", "y")
    ),
    ("T", "kill random=0.1"),
    ("T", "remove random=0.2"),
    ("L", "kill random=0.1"),
    ("L", "remove random=0.2"),
)
SUITES = {"default": CASES, "issue5": ISSUE5_CASES}


def one_run(
    args: tuple[str, str, str, int, float, dict[str, str], int, bool],
) -> dict[str, Any]:
    """Run one case with one seed and census method; return its JSON summary."""
    shape, damage, census, seed, max_time, et_options, delay, portable = args
    name, _, robots = shape.partition("/")
    config = RunConfig(
        shape=name,
        robots=int(robots) if robots else None,
        fit=bool(robots),
        seed=seed,
        max_time_s=max_time,
        damage=(damage,),
        census=census,
        et=ETParams(**et_options),
    )
    sim = SimParams(message_delay_ticks=delay, portable_math=portable)
    return ETRun(config, sim_params=sim).run()


HEADER = (
    "| shape | damage | census | formed | reformed | counted | torn | small remnants reformed "
    "| <=1 leader | shared tag | median re-formation min | censuses | exact | error mean | "
    "max abs error | s leader->count | s election->count | ends |\n" + "|---" * 18 + "|"
)


def report(
    shape: str, damage: str, census: str, seeds: int, runs: list[dict[str, Any]],
    min_robots: int = 6, first_limit_s: float | None = None,
    regrow_limit_s: float | None = None,
) -> str:
    """One table row for the summaries ``runs`` of a case and census method; a run
    succeeds when every remnant of at least ``min_robots`` robots re-formed. With
    ``regrow_limit_s`` only runs whose first formation completed within
    ``first_limit_s`` count, and a remnant re-formed only within ``regrow_limit_s``
    simulated seconds of the damage. "counted": runs in which every such remnant's robots
    at the end are as many as the census that counted them found (a remnant that grew a
    sibling remnant's smaller target, or that a census counted short, is not). "torn": re-formed
    runs in which such a remnant's robots stand torn apart somewhere (``stretched_links``)."""
    formed = reformed = counted = torn = leaders = dups = small = small_formed = 0
    times: list[float] = []
    errors: list[int] = []
    after_leader: list[float] = []
    after_election: list[float] = []
    results: Counter[str] = Counter()

    def in_time(component: dict[str, Any]) -> bool:
        return component["formed"] and (
            regrow_limit_s is None or component["time_to_stable_s"] <= regrow_limit_s
        )

    for s in runs:
        if not s["formed"]:
            continue
        if first_limit_s is not None and s["formation_time_s"] > first_limit_s:
            continue
        formed += 1
        comps = [c for c in s["components"] if c["robots"] >= min_robots]
        reformed += all(in_time(c) for c in comps)
        torn += all(in_time(c) for c in comps) and any(c.get("stretched_links") for c in comps)
        counted += all(c["census_count"] == c["robots"] for c in comps)
        smaller = [c for c in s["components"] if 3 <= c["robots"] < min_robots]
        small += len(smaller)
        small_formed += sum(c["formed"] for c in smaller)
        leaders += s["max_leaders_per_component"] <= 1
        dups += bool(s["duplicate_tags"])
        times += [c["time_to_stable_s"] / 60 for c in comps if in_time(c)]
        for e in s["events"]:
            if e["kind"] != "census":
                continue
            errors.append(e["count"] - e["robots"])
            after_leader.append(e["duration_s"])
            after_election.append(e["since_election_s"])
            results[e["result"]] += 1

    def mean(values: list[float] | list[int]) -> str:
        return f"{statistics.fmean(values):+.2f}" if values else "-"

    def avg(values: list[float]) -> str:
        return f"{statistics.fmean(values):.0f}" if values else "-"

    median = f"{statistics.median(times):.1f}" if times else "-"
    max_abs = max((abs(e) for e in errors), default=0) if errors else "-"
    exact_censuses = sum(e == 0 for e in errors)
    ends = ", ".join(f"{k} {v}" for k, v in sorted(results.items()))
    return (
        f"| {shape} | {damage} | {census} | {formed}/{seeds} | {reformed}/{formed} | "
        f"{counted}/{formed} | {torn}/{reformed} | {small_formed}/{small} | "
        f"{leaders}/{formed} | {dups} | {median} | {len(errors)} | "
        f"{exact_censuses}/{len(errors)} | {mean(errors)} | {max_abs} | {avg(after_leader)} | "
        f"{avg(after_election)} | {ends} |"
    )


def parse_case(text: str) -> tuple[str, str]:
    """``SHAPE:DAMAGE`` -> (shape, damage)."""
    shape, _, damage = text.partition(":")
    if not damage:
        raise argparse.ArgumentTypeError(f"--case {text!r}: expected SHAPE:DAMAGE")
    return shape, damage


def parse_option(text: str) -> tuple[str, float | int | str]:
    """``NAME=VALUE`` for ``--et``: any ETParams field."""
    try:
        return parse_et_option(text)
    except EtswarmError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument(
        "--max-time", type=float, default=4 * 3600.0,
        help="Simulated s per run, first formation included (with --regrow-time: for the "
        "first formation alone).",
    )
    parser.add_argument(
        "--regrow-time", type=float, default=None, metavar="S",
        help="Give every run S simulated s after the damage instead: runs last --max-time "
        "+ S, count only when their first formation took at most --max-time, and succeed "
        "when every remnant re-formed within S of the damage.",
    )
    parser.add_argument("--census", choices=("tree", "walk", "both"), default="both")
    parser.add_argument("--jobs", type=int, default=1, help="Processes running seeds.")
    parser.add_argument(
        "--min-robots", type=int, default=6,
        help="A run succeeds when every remnant of at least this many robots re-forms.",
    )
    parser.add_argument(
        "--out", type=argparse.FileType("a"), default=None, metavar="FILE",
        help="Also append every run's JSON summary to FILE (one line per run).",
    )
    parser.add_argument(
        "--case", type=parse_case, action="append", default=None, metavar="SHAPE:DAMAGE"
    )
    parser.add_argument(
        "--suite", choices=sorted(SUITES), default="default",
        help="The cases to run when no --case is given.",
    )
    parser.add_argument(
        "--et", type=parse_option, action="append", default=[], metavar="NAME=VALUE",
        help="An ETParams option for every run, e.g. release_order=id (repeatable).",
    )
    parser.add_argument("--message-delay", type=int, choices=(0, 1), default=0,
                        help="SimParams.message_delay_ticks of every run.")
    parser.add_argument("--native-math", dest="portable_math", action="store_false",
                        help="SimParams.portable_math off for every run: the platform's "
                             "maths library (the default's runs up to session 52).")
    args = parser.parse_args()
    et_options = dict(args.et)
    methods = ("tree", "walk") if args.census == "both" else (args.census,)
    cases = args.case or list(SUITES[args.suite])
    print(f"load average {os.getloadavg()}, message delay {args.message_delay}, "
          f"portable maths {args.portable_math}")
    print(HEADER)
    seeds = range(args.first_seed, args.first_seed + args.seeds)
    limit = args.max_time + (args.regrow_time or 0.0)  # simulated s per run
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for shape, damage in cases:
            for census in methods:
                work = [(shape, damage, census, seed, limit, et_options, args.message_delay,
                         args.portable_math)
                        for seed in seeds]
                runs = list(pool.map(one_run, work))
                if args.out:
                    for run in runs:
                        args.out.write(json.dumps(run) + "\n")
                    args.out.flush()
                row = report(
                    shape, damage, census, args.seeds, runs, args.min_robots,
                    args.max_time if args.regrow_time is not None else None, args.regrow_time,
                )
                print(row, flush=True)


if __name__ == "__main__":
    main()
