"""``etswarm view``, ``etswarm replay`` and ``etswarm plot``: watching swarms."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np

from etswarm.errors import EtswarmError


def _parse_size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise EtswarmError(f"--size {text!r}: expected WIDTHxHEIGHT, e.g. 1200x800") from None
    if w < 200 or h < 150:
        raise EtswarmError(f"--size {text!r}: the window must be at least 200x150")
    return w, h


def _check_display(frames: int | None) -> None:
    from etswarm.viewer.pg import has_display

    if frames is None and not has_display():
        raise EtswarmError(
            "no display available for the viewer window (set DISPLAY, or write a video "
            "headless with --video FILE.mp4)"
        )


_window_options = [
    click.option("--size", default="1200x800", show_default=True, help="Window size WxH (px)."),
    click.option("--fps", type=float, default=30.0, show_default=True, help="Frame rate cap."),
    click.option("--paused", is_flag=True, help="Start paused (space resumes)."),
    click.option(
        "--out",
        type=click.Path(file_okay=False, path_type=Path),
        default=Path("."),
        show_default=True,
        help="Folder for snapshots (s) and recordings (r).",
    ),
    click.option(
        "--frames", type=int, default=None, help="Stop after this many frames (headless checks)."
    ),
]


def window_options(func):  # type: ignore[no-untyped-def]
    """Attach the options every viewer window takes."""
    for option in reversed(_window_options):
        func = option(func)
    return func


#: Default target speed (x real time) per controller: ET runs take simulated hours.
DEFAULT_SPEED = {"et": 60.0, "randomwalk": 10.0}


@click.command()
@click.argument("shape", required=False)
@click.option(
    "--controller",
    type=click.Choice(["et", "randomwalk"]),
    default="et",
    show_default=True,
    help="Robot program: the ET algorithm growing SHAPE, or a random walk (no SHAPE).",
)
@click.option(
    "--robots",
    type=int,
    default=None,
    help="Swarm size (ET: default the cells of the shape; random walk: 200).",
)
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--loss", type=float, default=0.2, show_default=True, help="ET: message loss.")
@click.option("--noise", type=float, default=2.0, show_default=True, help="ET: distance noise, mm.")
@click.option(
    "--max-time",
    type=float,
    default=None,
    help="Simulated seconds to run (ET default 3 h; random walk: unlimited).",
)
@click.option(
    "--layout", type=click.Choice(["queue", "cluster"]), default="queue", show_default=True
)
@click.option("--release-interval", type=float, default=None, help="ET: seconds between releases.")
@click.option("--fit", is_flag=True, help="ET: with fewer robots than cells, form scale(shape, N).")
@click.option("--et", "et_options", multiple=True, metavar="NAME=VALUE",
              help="ET: set any ETParams field, as for 'etswarm run', e.g. --et wave_s=0 "
                   "(repeatable).")
@click.option(
    "--speed",
    type=float,
    default=None,
    help="Target x real time (+/- keys change it). Default: ET 60, random walk 10.",
)
@click.option(
    "--video",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write a video (.mp4/.gif) headless instead of opening a window.",
)
@click.option("--portable-math/--native-math", default=True, show_default=True,
              help="ET: the robots' maths by etswarm's own functions (the same run for a "
                   "seed on every machine) or by this machine's library, as in 'etswarm run'.")
@window_options
def view(
    shape: str | None,
    controller: str,
    robots: int | None,
    seed: int,
    loss: float,
    noise: float,
    max_time: float | None,
    layout: str,
    release_interval: float | None,
    fit: bool,
    et_options: tuple[str, ...],
    speed: float | None,
    video: Path | None,
    portable_math: bool,
    size: str,
    fps: float,
    paused: bool,
    out: Path,
    frames: int | None,
) -> None:
    """Watch SHAPE grow with the ET algorithm in a live window (or a swarm random-walk).

    Keys: space pause, . step, +/- speed, wheel zoom, arrows pan, l/t/n links/trails/
    labels, click a robot to inspect it, drag to split, shift-drag to remove, right-click
    to kill, r record video, s snapshot, h help, q quit. See docs/viewer.md.
    """
    if seed < 0:
        raise EtswarmError(f"--seed must be >= 0, got {seed}")
    if robots is not None and robots < 1:
        raise EtswarmError(f"--robots must be >= 1, got {robots}")
    speed = DEFAULT_SPEED[controller] if speed is None else speed
    if speed <= 0:
        raise EtswarmError(f"--speed must be > 0, got {speed}")
    window_size = _parse_size(size)
    if controller == "randomwalk":
        if shape is not None:
            raise EtswarmError("--controller randomwalk takes no SHAPE")
        from etswarm.viewer.simrun import randomwalk_live_run

        live = randomwalk_live_run(robots or 200, seed=seed, max_time_s=max_time)
    else:
        if shape is None:
            raise EtswarmError(
                "missing SHAPE (a library name or a bitmap file); or use --controller randomwalk"
            )
        live = _et_live(shape, robots, seed, loss, noise, max_time, layout, release_interval, fit,
                        et_options, portable_math)
    if video is not None:
        _write_video(live, video, fps, speed, frames or 300, window_size)
        return
    _open_window(
        live, window_size, fps, speed, paused, out, f"etswarm view: {shape or controller}", frames
    )


def _open_window(live, size, fps, speed, paused, out, caption, frames) -> None:  # type: ignore[no-untyped-def]
    """Show ``live`` in the pygame window (a display is needed) and report what was saved."""
    _check_display(frames)
    from etswarm.viewer.window import run_viewer

    result = run_viewer(
        live,
        size=size,
        fps=fps,
        speed=speed,
        start_paused=paused,
        output_dir=out,
        caption=caption,
        max_frames=frames,
    )
    _report(result)


def _et_live(  # type: ignore[no-untyped-def]
    shape: str,
    robots: int | None,
    seed: int,
    loss: float,
    noise: float,
    max_time: float | None,
    layout: str,
    release_interval: float | None,
    fit: bool,
    et_options: tuple[str, ...] = (),
    portable_math: bool = True,
):
    """The ET run of ``etswarm run`` with the same options, as a LiveRun."""
    from dataclasses import replace

    from etswarm.algorithm.live import ETLive
    from etswarm.algorithm.params import ETParams, parse_et_option
    from etswarm.algorithm.run import ETRun, RunConfig
    from etswarm.sim.params import SimParams

    et = ETParams() if release_interval is None else ETParams(release_interval_s=release_interval)
    et = replace(et, **dict(parse_et_option(text) for text in et_options))
    config = RunConfig(
        shape=shape,
        robots=robots,
        seed=seed,
        loss=loss,
        noise_mm=noise,
        max_time_s=3 * 3600.0 if max_time is None else max_time,
        layout=layout,
        fit=fit,
        et=et,
    )
    from rich.console import Console

    with Console(stderr=True).status(f"setting up {shape} (a first run compiles the controller)"):
        et_run = ETRun(config, sim_params=SimParams(portable_math=portable_math))
    for note in et_run.notes:
        click.echo(f"etswarm: {note}", err=True)
    return ETLive(et_run)


def _write_video(live, path: Path, fps: float, speed: float, frames: int, size) -> None:  # type: ignore[no-untyped-def]
    from etswarm.viewer.headless import write_live_video

    if fps <= 0 or speed <= 0:
        raise EtswarmError("--fps and --speed must be > 0 when writing a video")
    n = write_live_video(
        live, path, fps=fps, speed=speed, max_frames=frames, size=size, total=frames
    )
    click.echo(f"video: {path} ({n} frames, {n / fps:.1f} s at {fps:g} fps)")


def _report(result) -> None:  # type: ignore[no-untyped-def]
    for path in result.snapshots:
        click.echo(f"snapshot: {path}")
    for path in result.videos:
        click.echo(f"video: {path}")


@click.command()
@click.argument("run_dir", type=click.Path(path_type=Path))
@click.option(
    "--video",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write the run to a video (.mp4/.gif) headless instead of opening a window.",
)
@click.option(
    "--speed",
    type=float,
    default=None,
    help="Simulated seconds per wall (or video) second. Default: one recorded frame per frame.",
)
@window_options
def replay(
    run_dir: Path,
    video: Path | None,
    speed: float | None,
    size: str,
    fps: float,
    paused: bool,
    out: Path,
    frames: int | None,
) -> None:
    """Open a saved run (RUN_DIR with recording.npz) in the viewer, or write it to video."""
    from etswarm.viewer.headless import frames_for
    from etswarm.viewer.replay import ReplayRun
    from etswarm.viewer.runfiles import load_run_dir

    record = load_run_dir(run_dir)
    window_size = _parse_size(size)
    if speed is None:
        step_s = float(np.median(np.diff(record.t_s))) if record.frames > 1 else 1.0
        speed = max(step_s * (fps if fps > 0 else 30.0), 1e-3)
    if speed <= 0:
        raise EtswarmError(f"--speed must be > 0, got {speed}")
    live = ReplayRun(record)
    if video is not None:
        if fps <= 0:
            raise EtswarmError(f"--fps must be > 0 for a video, got {fps}")
        total = frames_for(live, fps, speed, float(record.t_s[-1] - record.t_s[0]))
        if frames is not None:
            total = min(total, frames)
        _write_video(live, video, fps, speed, total, window_size)
        return
    _open_window(
        live, window_size, fps, speed, paused, out, f"etswarm replay: {record.title}", frames
    )


@click.command()
@click.argument("run_dir", type=click.Path(path_type=Path))
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Folder for the PNGs (default: RUN_DIR).",
)
def plot(run_dir: Path, out: Path | None) -> None:
    """Plot a saved run: robots per state over time, the formation/regeneration
    timeline and, when recorded, neighbour-count errors."""
    from etswarm.viewer.plots import plot_run
    from etswarm.viewer.runfiles import find_recording, load_run_dir

    record = load_run_dir(run_dir)
    target = out if out is not None else find_recording(run_dir).parent
    for path in plot_run(record, target):
        click.echo(f"wrote {path}")
    if record.nn is None:
        click.echo("(no NN values in the recording: neighbour-count errors not plotted)")
