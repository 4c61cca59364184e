"""Why a run did not form: every free target site of every unformed remnant at the end.

Runs SHAPE (with optional damage) to its time limit and, for each remnant that has not
formed, lists each free site of its target with the robots on the six neighbour sites:
how far each stands from the site's position (the rigid fit of the remnant's placed
robots' tags to where they stand), its state and the offset it estimates for itself;
the distance between the holders of two adjacent neighbour sites, and between two
opposite ones (the site's mouth: 2 d = 80 mm on the ideal lattice; a 33 mm body needs
66); and the searchers of the remnant with their distance from the site.

    .venv/bin/python benchmarks/stuck_sites.py dumbbell --damage "split y=mid" --seed 5 \\
        --et capture_mouth_mm=0
    .venv/bin/python benchmarks/stuck_sites.py --from-runs runs.jsonl --jobs 2 [--probe]

With ``--from-runs`` it re-runs every run of a ``bench_regeneration.py --out`` file in which
a remnant of 6 or more robots did not re-form, and counts those remnants' free sites by
kind: takeable, torn (below), "inactive" (every placed neighbour Inactive: the front that
would let a searcher take it has stalled elsewhere), "no pair" (no two adjacent neighbour
sites held: it waits for another free site) or "no holder" (no neighbour site held). With
``--probe`` (with ``--from-runs`` or for one run) it then puts a searcher of the remnant on
each takeable site's best point (below) and reports whether it takes the site within 120 s.

A neighbour nearer than about 33 mm to the site's position pinches it (no body fits);
one farther than d + 15 mm or so stretches it (no searcher reads its pair at d).

Each free site also gets its *room*: over points 1 mm apart near the site where a body fits
(a body diameter from every robot), the least possible worst disagreement between the
distances a robot there would read from the remnant's placed robots (those in radio range
and the holders of the site's neighbour sites) and their lattice distances from the site.
A few millimetres means a searcher could stand where every reading fits the site (a
*takeable* site: what stops it is the search, not the lattice); 15 mm or more means no
such point exists (a *torn* site: the robots round it stand too far apart or too near).
"""

from __future__ import annotations

import json
from collections import Counter
from concurrent.futures import ProcessPoolExecutor

import click
import numpy as np

from etswarm.algorithm.memory import (
    NB_ID,
    R_CREEP_UNTIL,
    R_OFF_X,
    R_OFF_Y,
    R_PINCH_REFUSED,
    R_SHAPE_SINCE,
)
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.params import ETParams, parse_et_option
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.measures.formation import apply_fit, rigid_fit
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS, tags_to_xy

#: With --from-runs, only remnants of at least this many robots count (the issue's bar).
MIN_ROBOTS = 6
#: A free site whose room (see the module docstring) is at most this (mm) is takeable.
TAKEABLE_MM = 8.0
#: Half-width (mm) of the square of points searched round the site's holders for its room.
ROOM_REACH_MM = 60.0
#: With --probe, a searcher put on a takeable site's best point has this long (simulated
#: s) to take it.
PROBE_S = 120.0


def site_room(run: ETRun, group: np.ndarray, held: dict,
              site: tuple[int, int]) -> tuple[float, np.ndarray | None]:
    """The free site's room (mm) and the point (2,) mm where it is reached; ``(inf, None)``
    when no placed neighbour holds a neighbour site or no body fits near it."""
    d = run.config.et.spacing_mm
    pos = run.world.pos
    body = 2.0 * run.sim_params.body_radius_mm
    reach = run.sim_params.comm_range_mm
    holders = [held[t] for t in ((site[0] + dx, site[1] + dy) for dx, dy in NEIGHBOUR_OFFSETS)
               if t in held]
    if not holders:
        return float("inf"), None
    placed = np.array(sorted(held.values()), dtype=np.int64)
    tags = run.controller.tags[placed]
    expected = np.hypot(*(tags_to_xy(tags, d) - tags_to_xy(np.array([site]), d)[0]).T)
    holds_neighbour = np.isin(placed, holders)
    steps = np.arange(-ROOM_REACH_MM, ROOM_REACH_MM + 1.0)
    grid = pos[holders].mean(axis=0) + np.stack(np.meshgrid(steps, steps), -1).reshape(-1, 2)
    clear = np.ones(len(grid), dtype=bool)
    for chunk in np.array_split(np.arange(len(grid)), 8):
        gaps = np.linalg.norm(grid[chunk, None, :] - pos[None, :, :], axis=2)
        clear[chunk] = gaps.min(axis=1) >= body
    if not clear.any():
        return float("inf"), None
    points = grid[clear]
    reading = np.linalg.norm(points[:, None, :] - pos[placed][None, :, :], axis=2)
    counted = (reading <= reach) | holds_neighbour[None, :]
    worst = np.where(counted, np.abs(reading - expected[None, :]), 0.0).max(axis=1)
    best = int(np.argmin(worst))
    return float(worst[best]), points[best]


def room_kind(room: float, point: np.ndarray | None) -> str:
    """"takeable" when a body fits where every reading is within ``TAKEABLE_MM`` of the
    site's, else "torn" (``site_room``'s answer)."""
    return "takeable" if point is not None and room <= TAKEABLE_MM else "torn"


def describe_site(run: ETRun, group: np.ndarray, held: dict, site: tuple[int, int],
                  fit: tuple) -> list[str]:
    """Lines describing free site ``site`` of remnant ``group`` (robot IDs)."""
    d = run.config.et.spacing_mm
    pos = run.world.pos
    ri = run.controller.ri
    states = run.controller.states
    centre = apply_fit(fit, tags_to_xy(np.array([site]), d))[0]
    lines = [f"  free site {site} at {np.round(centre, 1).tolist()} mm"]
    holders: list[int | None] = []
    for k, (dx, dy) in enumerate(NEIGHBOUR_OFFSETS):
        tag = (int(site[0] + dx), int(site[1] + dy))
        r = held.get(tag)
        holders.append(r)
        if r is None:
            lines.append(f"    dir {k} {tag}: free")
            continue
        off = (ri[r, R_OFF_X] / FINE_PER_MM, ri[r, R_OFF_Y] / FINE_PER_MM)
        lines.append(
            f"    dir {k} {tag}: robot {r} ({State(states[r]).name}) "
            f"{np.hypot(*(pos[r] - centre)):.1f} mm from the site, "
            f"offset ({off[0]:.1f}, {off[1]:.1f}) mm"
        )
    for k in range(6):
        for step, name in ((1, "adjacent"), (3, "mouth")):
            if step == 3 and k >= 3:
                continue
            a, b = holders[k], holders[(k + step) % 6]
            if a is not None and b is not None:
                gap = float(np.hypot(*(pos[a] - pos[b])))
                lines.append(f"    {name} {k}-{(k + step) % 6}: {gap:.1f} mm")
    room, point = site_room(run, group, held, site)
    if point is not None:
        lines.append(f"    room: {room:.1f} mm at {np.round(point, 1).tolist()} "
                     f"({room_kind(room, point)})")
    tick = run.world.tick
    for r in group[states[group] == State.SEARCH]:
        at_shape = (tick - ri[r, R_SHAPE_SINCE]) / run.ticks_per_s
        lines.append(
            f"    searcher {r}: {np.hypot(*(pos[r] - centre)):.1f} mm away, "
            f"{at_shape:.0f} s at the shape, {ri[r, R_PINCH_REFUSED]} pinch refusals"
        )
    return lines


def remnants(run: ETRun) -> list[tuple[np.ndarray, dict, list[tuple[int, int]], int]]:
    """Per remnant of a finished run: its robots (IDs), its held sites (tag -> robot), its
    target's free sites and its target's size."""
    holds, _ = run._masks()
    tags = run.controller.tags
    out = []
    for group in run._groups():
        target = run.controller.slot_cells[run._slot_of(group)]
        held = {tuple(int(v) for v in tags[r]): int(r) for r in group[holds[group]]}
        free = [site for site in map(tuple, target.tolist()) if site not in held]
        out.append((group, held, free, len(target)))
    return out


def has_pair(held: dict, site: tuple[int, int]) -> bool:
    """Two adjacent neighbour sites of ``site`` are held: a searcher can localise there
    (DESIGN: a site is added next to two adjacent placed cells)."""
    ring = [(site[0] + dx, site[1] + dy) in held for dx, dy in NEIGHBOUR_OFFSETS]
    return any(ring[k] and ring[(k + 1) % 6] for k in range(6))


def site_kind(run: ETRun, group: np.ndarray, held: dict, site: tuple[int, int]) -> str:
    """"takeable", "torn", "inactive" (takeable or not, but every placed neighbour is
    Inactive, so no searcher may take it yet), "no pair" (no two adjacent neighbour sites
    held: it waits for a neighbour site to be taken first) or "no holder" (no neighbour
    site held)."""
    states = run.controller.states
    holders = [held[t] for t in ((site[0] + dx, site[1] + dy) for dx, dy in NEIGHBOUR_OFFSETS)
               if t in held]
    if not holders:
        return "no holder"
    if not has_pair(held, site):
        return "no pair"
    if all(states[r] == State.INACTIVE for r in holders):
        return "inactive"
    return room_kind(*site_room(run, group, held, site))


def probe_site(run: ETRun, group: np.ndarray, held: dict, site: tuple[int, int],
               searcher: int) -> str:
    """Put ``searcher`` on the point of ``site``'s room (``site_room``), standing still
    with an empty neighbour table, let it creep for ``PROBE_S`` and say what it did: the
    site it took, or how far it went. This bounds what better navigation could do: a
    searcher that does not take the site from its best point is stopped by the capture's
    rules and readings, not by its way there. Changes the run."""
    _, point = site_room(run, group, held, site)
    ctl = run.controller
    ctl.nb[searcher, :, NB_ID] = -1
    ctl.ri[searcher, R_CREEP_UNTIL] = run.world.tick + round(2 * PROBE_S * run.ticks_per_s)
    ctl.idle[searcher] = 0
    run.world.pos[searcher] = point
    run.advance(round(PROBE_S * run.ticks_per_s))
    if ctl.states[searcher] != State.SEARCH:
        took = tuple(int(v) for v in ctl.tags[searcher])
        return f"robot {searcher} took {took}" + (" (this site)" if took == site else "")
    gone = float(np.hypot(*(run.world.pos[searcher] - point)))
    return f"robot {searcher} did not take it, {gone:.0f} mm away after {PROBE_S:.0f} s"


def census_of_run(
    task: tuple[str, str, int, float, tuple[str, ...], int, bool],
) -> tuple[str, Counter, list[str]]:
    """Re-run one run (shape, damage, seed, max time, ET options, least remnant size,
    probe) and count the kinds of the free sites of its remnants of at least that many
    robots; with probe, also ``probe_site`` each takeable site with a searcher of its
    remnant (lines of what happened)."""
    shape, damage, seed, max_time, et_options, min_robots, probe = task
    et = ETParams(**dict(parse_et_option(o) for o in et_options))
    run = ETRun(RunConfig(shape=shape, seed=seed, damage=(damage,), max_time_s=max_time, et=et))
    run.run()
    kinds: Counter = Counter()
    probes: list[str] = []
    takeable: list[tuple[np.ndarray, dict, tuple[int, int]]] = []
    for group, held, free, _ in remnants(run):
        if len(group) >= min_robots:
            site_kinds = [site_kind(run, group, held, site) for site in free]
            kinds.update(site_kinds)
            takeable += [(group, held, s) for s, k in zip(free, site_kinds, strict=True)
                         if k == "takeable"]
    for group, held, site in takeable if probe else []:
        searchers = group[run.controller.states[group] == State.SEARCH]
        if len(searchers) == 0:
            probes.append(f"  {site}: no searcher in the remnant")
            continue
        probes.append(f"  {site}: " + probe_site(run, group, held, site, int(searchers[0])))
    return f"{shape} {damage} seed {seed}", kinds, probes


def unformed_runs(path: str, min_robots: int) -> list[tuple[str, str, int]]:
    """(shape, damage, seed) of the runs in a ``bench_regeneration.py --out`` file whose
    first formation completed and in which a remnant of ``min_robots`` or more did not
    re-form."""
    out = []
    with open(path) as f:
        for row, line in enumerate(f, 1):
            try:
                s = json.loads(line)
            except json.JSONDecodeError as err:
                raise click.ClickException(f"{path}, line {row}: not JSON ({err.msg})") from err
            if s["formation_time_s"] is None or len(s["damage"]) != 1:
                continue
            if all(c["formed"] for c in s["components"] if c["robots"] >= min_robots):
                continue
            out.append((s["shape"], s["damage"][0], int(s["seed"])))
    return out


def stall_census(path: str, max_time: float, et_options: tuple[str, ...], jobs: int,
                 probe: bool = False) -> None:
    """Print the kinds of free sites of every unformed run of ``path``, and the totals
    (with ``probe``, what a searcher put on each takeable site's best point did)."""
    tasks = [(*k, max_time, et_options, MIN_ROBOTS, probe)
             for k in unformed_runs(path, MIN_ROBOTS)]
    total: Counter = Counter()
    only: Counter = Counter()
    with ProcessPoolExecutor(jobs) as pool:
        for name, kinds, probes in pool.map(census_of_run, tasks):
            click.echo(f"{name}: " + ", ".join(f"{k} {n}" for k, n in sorted(kinds.items())))
            for line in probes:
                click.echo(line)
            total.update(kinds)
            only["mixed" if len(kinds) > 1 else next(iter(kinds), "none")] += 1
    click.echo(f"{len(tasks)} runs; free sites: "
               + ", ".join(f"{k} {n}" for k, n in sorted(total.items())))
    click.echo("runs whose free sites are all of one kind: "
               + ", ".join(f"{k} {n}" for k, n in sorted(only.items())))


@click.command()
@click.argument("shape", required=False)
@click.option("--seed", type=int, default=0)
@click.option("--damage", multiple=True, help="A damage SPEC, as for `etswarm run`.")
@click.option("--max-time", type=float, default=4 * 3600.0)
@click.option("--et", "et_options", multiple=True, metavar="NAME=VALUE")
@click.option("--from-runs", "runs_file", type=click.Path(exists=True, dir_okay=False),
              help="Re-run the unformed runs of a bench_regeneration.py --out file and "
                   "count their free sites by kind instead.")
@click.option("--jobs", type=int, default=2, help="Processes for --from-runs.")
@click.option("--probe", is_flag=True,
              help="Also put a searcher on each takeable site's best point and report "
                   "whether it takes the site within 120 s.")
def main(shape: str | None, seed: int, damage: tuple[str, ...], max_time: float,
         et_options: tuple[str, ...], runs_file: str | None, jobs: int, probe: bool) -> None:
    """Run SHAPE and describe the free sites of every remnant that did not form."""
    if runs_file:
        stall_census(runs_file, max_time, et_options, jobs, probe)
        return
    if shape is None:
        raise click.UsageError("give a SHAPE, or --from-runs FILE")
    et = ETParams(**dict(parse_et_option(o) for o in et_options))
    run = ETRun(RunConfig(shape=shape, seed=seed, damage=damage, max_time_s=max_time, et=et))
    summary = run.run()
    click.echo(f"formed {summary['formed']}, {summary['sim_time_s']:.0f} s, {summary['states']}")
    d = et.spacing_mm
    tags = run.controller.tags
    for group, held, free, target_cells in remnants(run):
        click.echo(f"remnant of {len(group)} robots, target {target_cells} cells, "
                   f"{len(free)} free")
        tagged = np.array(sorted(held.values()), dtype=np.int64)
        if not free or len(tagged) < 2:
            continue
        fit = rigid_fit(tags_to_xy(tags[tagged], d), run.world.pos[tagged])
        for site in free:
            click.echo("\n".join(describe_site(run, group, held, site, fit)))
        searchers = group[run.controller.states[group] == State.SEARCH]
        for site in free if probe else []:
            if site_kind(run, group, held, site) != "takeable":
                continue
            if len(searchers) == 0:
                click.echo(f"  probe {site}: no searcher in the remnant")
                continue
            # (each probe moves a searcher: later probes start from a changed run)
            click.echo(f"  probe {site}: "
                       + probe_site(run, group, held, site, int(searchers[0])))


if __name__ == "__main__":
    main()
