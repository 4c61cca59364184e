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

A neighbour nearer than about 33 mm to the site's position pinches it (no body fits);
one farther than d + 15 mm or so stretches it (no searcher reads its pair at d).
"""

from __future__ import annotations

import click
import numpy as np

from etswarm.algorithm.memory import R_OFF_X, R_OFF_Y, R_PINCH_REFUSED, R_SHAPE_SINCE
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.params import ETParams, parse_et_option
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.measures.formation import apply_fit, rigid_fit
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS, tags_to_xy


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
    tick = run.world.tick
    for r in group[states[group] == State.SEARCH]:
        at_shape = (tick - ri[r, R_SHAPE_SINCE]) / run.ticks_per_s
        lines.append(
            f"    searcher {r}: {np.hypot(*(pos[r] - centre)):.1f} mm away, "
            f"{at_shape:.0f} s at the shape, {ri[r, R_PINCH_REFUSED]} pinch refusals"
        )
    return lines


@click.command()
@click.argument("shape")
@click.option("--seed", type=int, default=0)
@click.option("--damage", multiple=True, help="A damage SPEC, as for `etswarm run`.")
@click.option("--max-time", type=float, default=4 * 3600.0)
@click.option("--et", "et_options", multiple=True, metavar="NAME=VALUE")
def main(shape: str, seed: int, damage: tuple[str, ...], max_time: float,
         et_options: tuple[str, ...]) -> None:
    """Run SHAPE and describe the free sites of every remnant that did not form."""
    et = ETParams(**dict(parse_et_option(o) for o in et_options))
    run = ETRun(RunConfig(shape=shape, seed=seed, damage=damage, max_time_s=max_time, et=et))
    summary = run.run()
    click.echo(f"formed {summary['formed']}, {summary['sim_time_s']:.0f} s, {summary['states']}")
    holds, _ = run._masks()
    d = et.spacing_mm
    for group in run._groups():
        target = run.controller.slot_cells[run._slot_of(group)]
        tagged = group[holds[group]]
        tags = run.controller.tags
        held = {tuple(int(v) for v in tags[r]): int(r) for r in tagged}
        free = [tuple(int(v) for v in c) for c in target if tuple(int(v) for v in c) not in held]
        click.echo(f"remnant of {len(group)} robots, target {len(target)} cells, "
                   f"{len(free)} free")
        if not free or len(tagged) < 2:
            continue
        fit = rigid_fit(tags_to_xy(tags[tagged], d), run.world.pos[tagged])
        for site in free:
            click.echo("\n".join(describe_site(run, group, held, site, fit)))


if __name__ == "__main__":
    main()
