"""``etswarm view``, ``etswarm replay`` and ``etswarm plot``: watching swarms."""

from __future__ import annotations

from pathlib import Path

import click

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


@click.command()
@click.option(
    "--controller",
    type=click.Choice(["randomwalk"]),
    default="randomwalk",
    show_default=True,
    help="Robot program to watch.",
)
@click.option("--robots", type=int, default=200, show_default=True, help="Number of robots.")
@click.option("--seed", type=int, default=0, show_default=True)
@click.option(
    "--speed", type=float, default=10.0, show_default=True, help="Target x real time (+/- keys)."
)
@click.option("--max-time", type=float, default=None, help="Stop simulating after this many s.")
@click.option(
    "--video",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="Write a video (.mp4/.gif) headless instead of opening a window.",
)
@window_options
def view(
    controller: str,
    robots: int,
    seed: int,
    speed: float,
    max_time: float | None,
    video: Path | None,
    size: str,
    fps: float,
    paused: bool,
    out: Path,
    frames: int | None,
) -> None:
    """Open the live viewer on a simulated swarm.

    Keys: space pause, . step, +/- speed, wheel zoom, arrows pan, l/t/n links/trails/
    labels, click a robot to inspect it, drag to split, shift-drag to remove, right-click
    to kill, r record video, s snapshot, h help, q quit.
    """
    from etswarm.viewer.simrun import randomwalk_live_run
    from etswarm.viewer.window import run_viewer

    if robots < 1:
        raise EtswarmError(f"--robots must be >= 1, got {robots}")
    if seed < 0:
        raise EtswarmError(f"--seed must be >= 0, got {seed}")
    live = randomwalk_live_run(robots, seed=seed, max_time_s=max_time)
    if video is not None:
        _write_video(live, video, fps, speed, frames or 300, _parse_size(size))
        return
    _check_display(frames)
    result = run_viewer(
        live,
        size=_parse_size(size),
        fps=fps,
        speed=speed,
        start_paused=paused,
        output_dir=out,
        caption=f"etswarm view: {controller}",
        max_frames=frames,
    )
    _report(result)


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
