"""Recording runs: frames every k ticks into a compressed .npz, plus a final-state JSON.

File layout (``numpy.savez_compressed``), F frames of N robots:

- ``tick``    (F,) int64
- ``pos``     (F, N, 2) float32 mm
- ``heading`` (F, N) float32 rad
- ``led``     (F, N) uint8 (ET: state code)
- ``alive``, ``present`` (F, N) bool
- ``header``  0-d str: JSON with ``format`` ("etswarm-recording"), ``version`` (1), ``n``,
  ``every``, ``ticks_per_s``, ``params`` and any caller metadata.

The recorder keeps frames in memory and writes the file when closed; used as a context
manager (or with :meth:`Recorder.close` in a ``finally``) it also writes what it has when
the run ends by an exception or Ctrl-C, and an ``atexit`` hook covers a plain exit.
"""

from __future__ import annotations

import atexit
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.sim.world import World

FORMAT = "etswarm-recording"
VERSION = 1


class Recorder:
    """Collects frames of ``world`` every ``every`` ticks and saves them to ``path``."""

    def __init__(self, path: str | Path, world: World, every: int = 1,
                 meta: dict[str, Any] | None = None) -> None:
        if every < 1:
            raise EtswarmError(f"recording interval must be >= 1 tick, got {every}")
        self.path = Path(path)
        self.world = world
        self.every = int(every)
        self.meta = dict(meta or {})
        self._ticks: list[int] = []
        self._pos: list[np.ndarray] = []
        self._heading: list[np.ndarray] = []
        self._led: list[np.ndarray] = []
        self._alive: list[np.ndarray] = []
        self._present: list[np.ndarray] = []
        self._closed = False
        atexit.register(self.close)

    @property
    def n_frames(self) -> int:
        """Frames captured so far."""
        return len(self._ticks)

    def due(self) -> bool:
        """True when the world's current tick should be captured (and was not yet)."""
        t = self.world.tick
        return t % self.every == 0 and (not self._ticks or self._ticks[-1] != t)

    def capture(self) -> None:
        """Store a frame of the world as it is now (regardless of the interval)."""
        w = self.world
        if self._ticks and self._ticks[-1] == w.tick:
            return
        self._ticks.append(w.tick)
        self._pos.append(w.pos.astype(np.float32))
        self._heading.append(w.heading.astype(np.float32))
        self._led.append(w.led.copy())
        self._alive.append(w.alive.copy())
        self._present.append(w.present.copy())

    def ticks_to_next_frame(self) -> int:
        """Ticks from now until the next tick that is a multiple of ``every`` (>= 1)."""
        return self.every - self.world.tick % self.every

    def close(self) -> None:
        """Write the file (once). Safe to call more than once."""
        if self._closed:
            return
        self._closed = True
        atexit.unregister(self.close)
        n = self.world.n
        header = {"format": FORMAT, "version": VERSION, "n": n, "every": self.every,
                  **self.meta}
        self.path.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_name(self.path.name + ".part")
        with open(tmp, "wb") as fh:
            np.savez_compressed(
                fh,
                header=np.array(json.dumps(header)),
                tick=np.array(self._ticks, dtype=np.int64),
                pos=_stack(self._pos, (0, n, 2), np.float32),
                heading=_stack(self._heading, (0, n), np.float32),
                led=_stack(self._led, (0, n), np.uint8),
                alive=_stack(self._alive, (0, n), np.bool_),
                present=_stack(self._present, (0, n), np.bool_),
            )
        os.replace(tmp, self.path)

    def __enter__(self) -> Recorder:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _stack(frames: list[np.ndarray], empty_shape: tuple[int, ...], dtype: Any) -> np.ndarray:
    return np.stack(frames) if frames else np.zeros(empty_shape, dtype=dtype)


@dataclass
class Recording:
    """A loaded recording (arrays as in the module docstring)."""

    header: dict[str, Any]
    tick: np.ndarray
    pos: np.ndarray
    heading: np.ndarray
    led: np.ndarray
    alive: np.ndarray
    present: np.ndarray

    @property
    def n_frames(self) -> int:
        return int(self.tick.shape[0])

    @property
    def n_robots(self) -> int:
        return int(self.header["n"])


def load_recording(path: str | Path) -> Recording:
    """Read a file written by :class:`Recorder`; EtswarmError if it is not one."""
    path = Path(path)
    try:
        with np.load(path, allow_pickle=False) as data:
            header = json.loads(str(data["header"]))
            if header.get("format") != FORMAT:
                raise EtswarmError(f"{path} is not an etswarm recording")
            return Recording(header, data["tick"], data["pos"], data["heading"], data["led"],
                             data["alive"], data["present"])
    except FileNotFoundError:
        raise EtswarmError(f"recording {path} not found") from None
    except (OSError, KeyError, ValueError) as err:
        raise EtswarmError(f"{path} is not a readable etswarm recording ({err})") from None


def final_state(world: World, **extra: Any) -> dict[str, Any]:
    """The world's final state as JSON-ready data (positions in mm, headings in rad)."""
    return {
        "tick": world.tick,
        "n": world.n,
        "pos": np.round(world.pos, 6).tolist(),
        "heading": np.round(world.heading, 9).tolist(),
        "led": world.led.tolist(),
        "alive": world.alive.tolist(),
        "present": world.present.tolist(),
        "counters": world.counter_dict(),
        **extra,
    }


def write_final_state(path: str | Path, world: World, **extra: Any) -> None:
    """Write :func:`final_state` to ``path`` as JSON."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(final_state(world, **extra)))
