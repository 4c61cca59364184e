"""``etswarm run``: grow a shape headless (and damage it), print or save a summary."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import click

from etswarm.algorithm.layout import LAYOUTS


@click.command()
@click.argument("shape")
@click.option("--robots", type=int, default=None, help="Swarm size (default: cells of the shape).")
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--loss", type=float, default=0.2, show_default=True, help="Message loss.")
@click.option("--noise", type=float, default=2.0, show_default=True, help="Distance noise, mm.")
@click.option("--max-time", type=float, default=4 * 3600.0, show_default=True,
              help="Simulated seconds before giving up.")
@click.option("--layout", type=click.Choice(LAYOUTS), default="queue", show_default=True,
              help="Repository: the paper's queue, or a packed cluster.")
@click.option("--release-interval", type=float, default=None,
              help="Seconds between releases from the repository.")
@click.option("--census", type=click.Choice(("tree", "walk")), default="tree", show_default=True,
              help="How a remnant's Leader counts it: spanning tree, or the paper's walk "
                   "round the periphery.")
@click.option("--orbit", type=click.Choice(("clockwise", "bounce")), default="clockwise",
              show_default=True,
              help="Searchers go round the whole group clockwise (the paper), or turn back "
                   "where the shape meets the repository.")
@click.option("--creep/--no-creep", default=True, show_default=True,
              help="Searchers near a free site move stop-and-go (--no-creep: the paper's "
                   "steady edge-following).")
@click.option("--second-ring/--no-second-ring", default=True, show_default=True,
              help="Searchers also locate a site from two placed robots sqrt(3) d apart "
                   "(--no-second-ring: only from lattice neighbours, as in the paper).")
@click.option("--hole-memory/--no-hole-memory", default=True, show_default=True,
              help="Before taking a site, searchers check the whole shape for a hole it would "
                   "close, from every site they heard held (--no-hole-memory: only the sites "
                   "within three steps that they hear now).")
@click.option("--pocket/--no-pocket", default=False, show_default=True,
              help="A searcher 10 minutes at the shape may also take a free site from the "
                   "placed robots all round it where the lattice has stretched (experimental: "
                   "more compact shapes form, but starfish runs ended with shared tags).")
@click.option("--release-order", type=click.Choice(("far", "id")), default="far",
              show_default=True,
              help="After a regeneration, the Queued robot farthest from the scaled shape "
                   "leaves first, so the rest stay linked to it (id: the lowest ID, as at "
                   "the start and in the paper).")
@click.option("--silent-sites/--no-silent-sites", default=True, show_default=True,
              help="While electing, robots flood where placed neighbours fell silent (dead "
                   "robots) and the Leader keeps the scaled target off those sites "
                   "(--no-silent-sites: it places it from the robots it hears alone).")
@click.option("--queue-stride/--no-queue-stride", default=True, show_default=True,
              help="In the first formation, a searcher along the queue near its aim drives "
                   "straight on instead of pivoting (--no-queue-stride: the paper's "
                   "edge-following all the way).")
@click.option("--wave/--no-wave", default=True, show_default=True,
              help="In the first formation a searcher does not take a site while a site "
                   "beside it nearer the seeds is not known held, for its first 20 minutes "
                   "at the shape, so compact shapes grow outwards from the seeds; off for thin "
                   "shapes; in shapes with holes the wave runs out from the holes' edges "
                   "(--no-wave: the paper's first site found; --et wave_s=S and --et "
                   "rim_wave_s=S set the seconds).")
@click.option("--et", "et_options", multiple=True, metavar="NAME=VALUE",
              help="Set any ETParams field, e.g. --et pair_aim_mm=-1 (repeatable; see "
                   "docs/algorithm.md). Applied after the options above.")
@click.option("--fit", is_flag=True, help="With fewer robots than cells, form scale(shape, N).")
@click.option("--damage", "damage", multiple=True, metavar="SPEC",
              help="Damage 'KIND REGION [at=TIME]', e.g. 'split x=0' (repeatable).")
@click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Directory for summary.json, recording.npz (for replay/plot), snapshots.")
@click.option("--video", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write a video of the run (.mp4 or .gif).")
@click.option("--fps", type=float, default=10.0, show_default=True, help="Video frame rate.")
@click.option("--speedup", type=float, default=300.0, show_default=True,
              help="Simulated seconds per video second.")
@click.option("--snapshots", is_flag=True,
              help="Save PNGs at the start and at each event (into --out or ./snapshots).")
@click.option("--json", "as_json", is_flag=True, help="Print only the JSON summary.")
@click.option("--threads", type=int, default=1, show_default=True,
              help="Simulator threads (SimParams.threads): the phases and the robots' "
                   "control run on this many threads; results do not depend on the count "
                   "above 1, but differ from --threads 1's (other noise draws).")
@click.option("--control-threads", type=int, default=None,
              help="With --threads 1: run the robots' control on this many threads and "
                   "the rest on one, with results identical to --control-threads 1 "
                   "[default: 2 on a machine of two or more cores, else 1].")
@click.option("--message-delay", type=int, default=0, show_default=True,
              help="Ticks (0 or 1) between a broadcast and the control tick that reads it "
                   "(SimParams.message_delay_ticks). With 1, --control-threads also runs "
                   "the radio and the motion beside the control: faster, and other "
                   "results than 0.")
@click.option("--portable-math/--native-math", default=True, show_default=True,
              help="Compute sines, cosines, arctangents, logarithms and normal draws with "
                   "etswarm's own functions, so a seed gives the same run on every machine "
                   "(SimParams.portable_math), or with this machine's maths library "
                   "(--native-math: the runs of sessions up to 52, which differ by machine).")
def run(shape: str, robots: int | None, seed: int, loss: float, noise: float, max_time: float,
        layout: str, release_interval: float | None, census: str, orbit: str, creep: bool,
        second_ring: bool, hole_memory: bool, pocket: bool, release_order: str,
        silent_sites: bool, queue_stride: bool, wave: bool, et_options: tuple[str, ...], fit: bool,
        damage: tuple[str, ...],
        out: Path | None, video: Path | None, fps: float, speedup: float, snapshots: bool,
        as_json: bool, threads: int, control_threads: int | None, message_delay: int,
        portable_math: bool) -> None:
    """Grow SHAPE (a library name or a bitmap file) with the ET algorithm."""
    from etswarm.algorithm.params import ETParams, parse_et_option
    from etswarm.algorithm.run import ETRun, RunConfig
    from etswarm.cli.run_outputs import describe, drive, write_summary
    from etswarm.errors import EtswarmError
    from etswarm.sim.params import SimParams, default_control_threads

    if fps <= 0 or speedup <= 0:
        raise EtswarmError("--fps and --speedup must be > 0")
    if not 1 <= threads <= 256:
        raise EtswarmError(f"--threads must be in [1, 256], got {threads}")
    if control_threads is None:
        control_threads = default_control_threads(threads)
    if not 1 <= control_threads <= 256:
        raise EtswarmError(f"--control-threads must be in [1, 256], got {control_threads}")
    if control_threads > 1 and threads > 1:
        raise EtswarmError("--control-threads needs --threads 1 (--threads above 1 already "
                           "runs the control on every thread)")
    if message_delay not in (0, 1):
        raise EtswarmError(f"--message-delay must be 0 or 1, got {message_delay}")
    if message_delay and threads > 1:
        raise EtswarmError("--message-delay 1 needs --threads 1 (use --control-threads)")
    if video is not None and video.suffix.lower() not in (".mp4", ".gif"):
        raise EtswarmError(f"--video {video}: the file must end in .mp4 or .gif")
    et = ETParams(orbit=orbit, creep="on" if creep else "off",
                  second_ring="on" if second_ring else "off",
                  hole_memory="on" if hole_memory else "off",
                  pocket="on" if pocket else "off",
                  release_order=release_order,
                  silent_sites="on" if silent_sites else "off",
                  queue_stride="on" if queue_stride else "off")
    if not wave:
        et = replace(et, wave_s=0.0, rim_wave_s=0.0)
    if release_interval is not None:
        et = replace(et, release_interval_s=release_interval)
    et = replace(et, **dict(parse_et_option(text) for text in et_options))
    config = RunConfig(shape=shape, robots=robots, seed=seed, loss=loss, noise_mm=noise,
                       max_time_s=max_time, layout=layout, fit=fit, damage=damage, et=et,
                       census=census)
    et_run = ETRun(config, sim_params=SimParams(threads=threads, control_threads=control_threads,
                                                message_delay_ticks=message_delay,
                                                portable_math=portable_math))
    for note in et_run.notes:
        click.echo(f"etswarm: {note}", err=True)
    shots = None
    if snapshots:
        shots = (out or Path(".")) / "snapshots"
    record = out / "recording.npz" if out is not None else None
    summary = drive(et_run, video=video, fps=fps, speedup=speedup, snapshots=shots,
                    record=record, quiet=as_json)
    if out is not None:
        path = write_summary(summary, out)
        if not as_json:
            click.echo(f"summary: {path}")
    if as_json:
        click.echo(json.dumps(summary))
        return
    for line in describe(summary):
        click.echo(line)
    if video is not None:
        click.echo(f"video: {video}")
    if shots is not None:
        click.echo(f"snapshots: {shots}")
