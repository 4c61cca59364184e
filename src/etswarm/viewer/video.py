"""Videos and snapshots of rendered frames.

``.mp4`` goes through imageio-ffmpeg's bundled ffmpeg binary (H.264, yuv420p; no
system ffmpeg needed), streamed frame by frame. ``.gif`` goes through Pillow: frames
are reduced to 256-colour palettes as they arrive and written on close (keep GIFs
short: they are held in memory at one byte per pixel). Identical consecutive GIF
frames are merged into one longer frame by Pillow, which plays the same.

Frames are the renderer's (H, W, 3) uint8 RGB arrays, all of one size.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np
from PIL import Image

from etswarm.errors import EtswarmError

#: File suffixes :class:`VideoWriter` can write.
VIDEO_SUFFIXES = (".mp4", ".gif")


def _check_frame(frame: np.ndarray) -> np.ndarray:
    arr = np.asarray(frame)
    if arr.ndim != 3 or arr.shape[2] != 3:
        raise ValueError(f"a frame must be (H, W, 3) RGB, got shape {arr.shape}")
    if arr.dtype != np.uint8:
        arr = np.clip(arr, 0, 255).astype(np.uint8)
    return np.ascontiguousarray(arr)


class VideoWriter:
    """Write RGB frames to ``path`` (.mp4 or .gif) at ``fps`` frames per second.

    Use as a context manager; the file is finalized on exit, including when the block
    is left by an exception or Ctrl-C (KeyboardInterrupt), so what was written so far
    is kept. ffmpeg runs in its own process group and does not see the Ctrl-C.

    Args:
        path: output file; its suffix picks the format. Parent folders are created.
        fps: frames per second (> 0).
        quality: mp4 quality 0..10 (imageio-ffmpeg's scale; 10 is best).
    """

    def __init__(self, path: str | Path, fps: float = 30.0, quality: float = 7.0) -> None:
        self.path = Path(path)
        suffix = self.path.suffix.lower()
        if suffix not in VIDEO_SUFFIXES:
            raise EtswarmError(
                f"{self.path}: video format {suffix or '(none)'} not supported; use .mp4 or .gif"
            )
        if not fps > 0:
            raise EtswarmError(f"--fps must be > 0, got {fps}")
        self.format = suffix[1:]
        self.fps = float(fps)
        self.quality = float(quality)
        self.frame_count = 0
        self.size: tuple[int, int] | None = None  # (width, height) of the input frames
        self.closed = False
        self._ffmpeg: Any = None  # the imageio-ffmpeg write_frames generator
        self._gif_frames: list[Image.Image] = []
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise EtswarmError(f"{self.path}: cannot create the folder ({err.strerror})") from err

    # ------------------------------------------------------------------ writing
    def write(self, frame: np.ndarray) -> None:
        """Append one (H, W, 3) uint8 RGB frame."""
        if self.closed:
            raise ValueError(f"{self.path}: writer is closed")
        arr = _check_frame(frame)
        h, w = arr.shape[:2]
        if self.size is None:
            self.size = (w, h)
        elif self.size != (w, h):
            raise ValueError(
                f"{self.path}: frame size {w}x{h} differs from the first frame's "
                f"{self.size[0]}x{self.size[1]}"
            )
        if self.format == "mp4":
            self._write_mp4(arr)
        else:
            self._gif_frames.append(
                Image.fromarray(arr).quantize(
                    256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE
                )
            )
        self.frame_count += 1

    def _write_mp4(self, arr: np.ndarray) -> None:
        # H.264 in yuv420p needs even sizes: pad one edge row/column when odd
        h, w = arr.shape[:2]
        if h % 2 or w % 2:
            arr = np.pad(arr, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
        if self._ffmpeg is None:
            import imageio_ffmpeg

            self._ffmpeg = imageio_ffmpeg.write_frames(
                str(self.path),
                (arr.shape[1], arr.shape[0]),
                fps=self.fps,
                codec="libx264",
                pix_fmt_out="yuv420p",
                quality=self.quality,
                macro_block_size=1,
                ffmpeg_log_level="error",
                output_params=["-preset", "veryfast"],
            )
            self._ffmpeg.send(None)  # start the generator
        self._ffmpeg.send(arr.tobytes())

    # ------------------------------------------------------------------ closing
    def close(self) -> Path:
        """Finalize the file (safe to call twice). Returns the path."""
        if self.closed:
            return self.path
        self.closed = True
        if self.format == "mp4":
            if self._ffmpeg is not None:
                self._ffmpeg.close()
                self._ffmpeg = None
        elif self._gif_frames:
            first, *rest = self._gif_frames
            first.save(
                self.path,
                save_all=True,
                append_images=rest,
                duration=max(20, round(1000 / self.fps)),
                loop=0,
                optimize=False,
            )
            self._gif_frames = []
        return self.path

    def __enter__(self) -> VideoWriter:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        # finalize on every exit, KeyboardInterrupt included; a second Ctrl-C during the
        # finalization is ignored so the file is not left half-written
        try:
            self.close()
        except KeyboardInterrupt:
            with contextlib.suppress(Exception):
                self.close()


def record_video(
    frames: Iterable[np.ndarray],
    path: str | Path,
    fps: float = 30.0,
    progress: bool = True,
    total: int | None = None,
    description: str = "video",
) -> int:
    """Write every frame of ``frames`` to ``path``; returns the number written.

    Shows a rich progress bar when ``progress`` (with ``total`` frames when known).
    Ctrl-C stops early but keeps the frames written so far (then re-raises).
    """
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    with VideoWriter(path, fps) as writer:
        if not progress:
            for frame in frames:
                writer.write(frame)
            return writer.frame_count
        columns = [
            TextColumn("[bold]{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            TimeRemainingColumn(),
        ]
        with Progress(*columns, transient=False) as bar:
            task = bar.add_task(f"{description} -> {Path(path).name}", total=total)
            for frame in frames:
                writer.write(frame)
                bar.advance(task)
        return writer.frame_count


def save_png(rgb: np.ndarray, path: str | Path) -> Path:
    """Save an (H, W, 3) uint8 RGB image as PNG at ``path`` (folders created)."""
    out = Path(path)
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(_check_frame(rgb)).save(out, format="PNG")
    except OSError as err:
        raise EtswarmError(f"{out}: cannot write the PNG ({err.strerror or err})") from err
    return out
