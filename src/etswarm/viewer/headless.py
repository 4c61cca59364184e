"""Frames of a live run without a window: for videos written headless."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from etswarm.viewer.live import LiveRun
from etswarm.viewer.render import render
from etswarm.viewer.video import record_video
from etswarm.viewer.view import ViewState


def live_frames(
    live_run: LiveRun,
    view: ViewState | None = None,
    fps: float = 30.0,
    speed: float = 60.0,
    max_frames: int | None = None,
    size: tuple[int, int] = (1200, 800),
) -> Iterator[np.ndarray]:
    """Render ``live_run`` as it advances ``speed`` simulated seconds per video second.

    Yields (H, W, 3) uint8 frames: the current state first, then one frame per
    ``speed / fps`` simulated seconds, until the run finishes (its last state is
    included) or ``max_frames`` frames were made. The status line shows ``speed`` as
    the × real-time factor of the video. ``view`` defaults to a fit of the first scene.
    """
    if fps <= 0 or speed <= 0:
        raise ValueError("fps and speed must be > 0")
    tps = int(live_run.ticks_per_second)
    debt = 0.0
    k = 0
    while max_frames is None or k < max_frames:
        if k > 0:
            if live_run.finished:
                return
            debt += speed * tps / fps
            ticks = int(debt)
            debt -= ticks
            if ticks:
                live_run.advance(ticks)
        scene = dataclasses.replace(live_run.scene(), speedup=speed)
        if view is None:
            view = ViewState.fitted(scene, *size)
        yield render(scene, view)
        k += 1


def frames_for(live_run: LiveRun, fps: float, speed: float, seconds_left: float) -> int:
    """Number of frames :func:`live_frames` makes to cover ``seconds_left`` of simulated time."""
    return int(np.ceil(max(seconds_left, 0.0) * fps / speed)) + 1


def write_live_video(
    live_run: LiveRun,
    path: str | Path,
    fps: float = 30.0,
    speed: float = 60.0,
    max_frames: int | None = None,
    size: tuple[int, int] = (1200, 800),
    total: int | None = None,
    progress: bool = True,
    view: ViewState | None = None,
) -> int:
    """Write ``live_run`` to a video file (see :func:`live_frames`); returns frames written."""
    frames = live_frames(live_run, view, fps, speed, max_frames, size)
    return record_video(frames, path, fps, progress=progress, total=total)
