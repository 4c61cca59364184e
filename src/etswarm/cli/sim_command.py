"""``etswarm sim``: run a shipped controller headless, with a progress bar and a summary."""

from __future__ import annotations

import time
from pathlib import Path

import click

from etswarm.errors import EtswarmError


@click.command("sim")
@click.option("--controller", "controller_name", default="randomwalk", show_default=True,
              help="Controller to run (shipped: randomwalk).")
@click.option("--robots", "-n", type=int, default=100, show_default=True,
              help="Number of robots.")
@click.option("--seconds", "-s", type=float, default=60.0, show_default=True,
              help="Simulated seconds.")
@click.option("--seed", type=int, default=0, show_default=True, help="Run seed.")
@click.option("--loss", type=float, default=None, help="Message loss probability.")
@click.option("--noise", type=float, default=None, help="Distance noise std (mm).")
@click.option("--arena", type=float, default=None,
              help="Side of the walled square arena (mm); default 50 mm * sqrt(N).")
@click.option("--config", "config_file", type=click.Path(path_type=Path), default=None,
              help="TOML file of sim parameters (keys at top level or in [sim]).")
@click.option("--out", "out_dir", type=click.Path(path_type=Path), default=None,
              help="Write recording.npz and final_state.json here.")
@click.option("--every", type=int, default=31, show_default=True,
              help="Record a frame every this many ticks (with --out).")
@click.option("--threads", type=int, default=None,
              help="Threads the tick phases run on (sim parameter threads; default 1). "
                   "More than 1: deterministic, the same for every count > 1, but not "
                   "the same results as 1.")
@click.option("--progress/--no-progress", default=True, show_default=True,
              help="Show a progress bar on stderr.")
def sim(controller_name: str, robots: int, seconds: float, seed: int, loss: float | None,
        noise: float | None, arena: float | None, config_file: Path | None,
        out_dir: Path | None, every: int, threads: int | None, progress: bool) -> None:
    """Run a swarm headless and print robots, ticks, wall time and speed."""
    from etswarm.sim.controllers import CONTROLLERS
    from etswarm.sim.params import SimParams
    from etswarm.sim.placement import arena_side_for, random_world
    from etswarm.sim.recorder import Recorder, write_final_state
    from etswarm.sim.runner import run_for
    from etswarm.sim.simulator import Simulator

    if controller_name not in CONTROLLERS:
        raise EtswarmError(f"--controller: unknown controller {controller_name!r} "
                           f"(known: {', '.join(sorted(CONTROLLERS))})")
    if robots < 1:
        raise EtswarmError(f"--robots must be >= 1, got {robots}")
    if seconds < 0:
        raise EtswarmError(f"--seconds must be >= 0, got {seconds}")
    if seed < 0:
        raise EtswarmError(f"--seed must be >= 0, got {seed}")
    if every < 1:
        raise EtswarmError(f"--every must be >= 1 tick, got {every}")
    params = SimParams.from_toml(config_file) if config_file else SimParams()
    if threads is not None and threads < 1:
        raise EtswarmError(f"--threads must be >= 1, got {threads}")
    params = params.with_overrides(loss=loss, dist_noise_mm=noise, arena_mm=arena,
                                   threads=threads)
    if params.arena_mm == 0:
        params = params.with_overrides(arena_mm=round(arena_side_for(robots), 3))
    t_setup = time.perf_counter()
    world = random_world(robots, params, seed)
    controller = CONTROLLERS[controller_name](robots)
    simulator = Simulator(world, controller, params, seed)  # loads or compiles the kernel
    setup = time.perf_counter() - t_setup
    ticks = round(seconds * params.ticks_per_s)

    recorder = None
    if out_dir is not None:
        meta = {"controller": controller_name, "seed": seed,
                "ticks_per_s": params.ticks_per_s, "params": params.to_dict()}
        recorder = Recorder(out_dir / "recording.npz", world, every, meta)
    t0 = time.perf_counter()
    try:
        done = _run_with_bar(simulator, ticks, recorder, progress, run_for)
    finally:
        if recorder is not None:
            recorder.close()
            write_final_state(out_dir / "final_state.json", world,
                              controller=controller_name, seed=seed,
                              params=params.to_dict())
    wall = time.perf_counter() - t0
    robot_ticks = robots * done
    rate = robot_ticks / wall if wall > 0 else float("inf")
    realtime = done / params.ticks_per_s / wall if wall > 0 else float("inf")
    click.echo(f"robots            {robots}")
    click.echo(f"ticks             {done} ({done / params.ticks_per_s:.1f} s simulated)")
    click.echo(f"wall seconds      {wall:.2f} (+ {setup:.2f} s placement and kernel load)")
    click.echo(f"robot-ticks/s     {rate / 1e6:.2f} M")
    click.echo(f"x real time       {realtime:.1f}")
    c = world.counter_dict()
    click.echo(f"messages          {c['messages_sent']} sent, {c['messages_delivered']} "
               f"delivered, {c['messages_lost']} lost, {c['inbox_overflow']} overflowed")
    if out_dir is not None:
        click.echo(f"wrote             {out_dir / 'recording.npz'}, "
                   f"{out_dir / 'final_state.json'}")


def _run_with_bar(simulator, ticks, recorder, show, run_for) -> int:  # type: ignore[no-untyped-def]
    if not show:
        return run_for(simulator, ticks, recorder)
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    columns = (TextColumn("simulating"), BarColumn(),
               TextColumn("{task.completed}/{task.total} ticks"), TimeRemainingColumn())
    with Progress(*columns, console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("sim", total=ticks)
        return run_for(simulator, ticks, recorder, lambda k: bar.advance(task, k))
