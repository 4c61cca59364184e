"""Regeneration figures: per shape and damage, over seeds, how remnants fare.

    .venv/bin/python benchmarks/bench_regeneration.py [--seeds 10] [--max-time 14400]

For each case: runs whose first formation completed, runs in which every remnant of at least
three robots re-formed its scaled target, exact census, at most one Leader per remnant, runs
with a tag held twice in a remnant, and the median time from damage to re-formed.
"""

from __future__ import annotations

import argparse
import os
import statistics

from etswarm.algorithm.run import ETRun, RunConfig

CASES = (
    ("triangle", "split x=0"),
    ("triangle", "remove random=0.2"),
    ("triangle", "kill ids=3,4,5"),
    ("hexagon", "split x=0"),
    ("T", "split x=0"),
)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--max-time", type=float, default=4 * 3600.0)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()}")
    for shape, damage in CASES:
        formed = reformed = census = leaders = dups = 0
        times: list[float] = []
        for seed in range(args.seeds):
            config = RunConfig(shape=shape, seed=seed, max_time_s=args.max_time, damage=(damage,))
            s = ETRun(config).run()
            if not s["formed"]:
                continue
            formed += 1
            comps = [c for c in s["components"] if c["robots"] >= 3]
            reformed += all(c["formed"] for c in comps)
            census += all(c["census_count"] == c["robots"] for c in comps)
            leaders += s["max_leaders_per_component"] <= 1
            dups += bool(s["duplicate_tags"])
            times += [c["time_to_stable_s"] / 60 for c in comps if c["formed"]]
        median = f"{statistics.median(times):.1f} min" if times else "-"
        print(
            f"{shape:9s} {damage:18s} formed {formed}/{args.seeds}, all remnants reformed "
            f"{reformed}/{formed}, census exact {census}/{formed}, <=1 leader {leaders}/{formed}, "
            f"runs with a shared tag {dups}, median re-formation {median}",
            flush=True,
        )


if __name__ == "__main__":
    main()
