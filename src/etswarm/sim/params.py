"""Simulator parameters: one dataclass, loadable from TOML, overridable by name.

Defaults follow DESIGN §2 (Kilombo's defaults unless noted). Every value is checked when
the object is built; a bad one raises :class:`~etswarm.errors.EtswarmError` naming the key
(and the file it came from).
"""

from __future__ import annotations

import dataclasses
import math
import os
import tomllib
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, NamedTuple

from etswarm.errors import EtswarmError


def default_control_threads(threads: int) -> int:
    """``control_threads`` for a single interactive run: 2 on a machine of two or more
    cores when ``threads`` is 1, else 1. Results do not depend on it; runs that share the
    machine (sweeps, benchmarks with one job per core) keep ``SimParams``' default 1."""
    return 2 if threads == 1 and (os.cpu_count() or 1) >= 2 else 1


#: (minimum, maximum) allowed for each numeric parameter; None = unbounded on that side.
_RANGES: dict[str, tuple[float | None, float | None]] = {
    "ticks_per_s": (1, 10_000),
    "tx_period": (1, 100_000),
    "comm_range_mm": (0, 10_000),
    "loss": (0, 1),
    "dist_noise_mm": (0, 1_000),
    "body_radius_mm": (0.1, 1_000),
    "speed_mm_s": (0, 1_000),
    "turn_rate_deg_s": (0, 3_600),
    "speed_spread": (0, 0.9),
    "turn_rate_spread": (0, 0.9),
    "speed_noise": (0, 1),
    "heading_noise_deg": (0, 180),
    "leg_angle_deg": (0, 180),
    "inbox_capacity": (1, 4096),
    "arena_mm": (0, 1e9),
    "push_slop_mm": (0, 100),
    "max_push_passes": (1, 10_000),
    "still_push_share": (0, 1),
    "threads": (1, 256),
    "control_threads": (1, 256),
    "message_delay_ticks": (0, 1),
}


class KernelConfig(NamedTuple):
    """The parameters in the form the compiled phases read them (SI-ish units: mm, s, rad)."""

    dt: float
    tx_period: int
    comm_range: float
    loss: float
    dist_noise: float
    radius: float
    speed_noise: float
    heading_noise: float
    leg_angle: float
    arena: float
    max_passes: int
    slop: float
    still_share: float
    msg_delay: int
    portable: bool


@dataclass(frozen=True)
class SimParams:
    """Everything the world physics and radio need. Units in the names.

    ``speed_spread`` and ``turn_rate_spread`` are relative standard deviations of the
    per-robot calibration (speed_i = speed_mm_s * (1 + spread * N(0,1)), clipped to
    [0.1, 1.9] x nominal). ``speed_noise`` is the relative std of a per-tick speed jitter
    and ``heading_noise_deg`` the std of a per-tick heading jitter while a robot moves.
    ``arena_mm`` > 0 puts walls around the square [0, arena_mm]^2; 0 means no walls.
    ``push_slop_mm``: overlaps up to this depth are left alone (resolving them would
    ripple tiny pushes through every cluster of touching robots); deeper ones are pushed
    apart until the bodies touch. ``max_push_passes``: collision passes per tick; what is
    left is resolved in the next tick. With the defaults bodies never overlap by more than
    about 0.3 mm (tested: 0.5 mm in dense random walks).
    ``still_push_share``: when a moving robot pushes one whose motors are off, the share of
    the overlap the still robot takes (the mover takes the rest). A Kilobot standing on its
    three legs grips the table while a vibrating one slides, so values below 0.5 model that
    grip. The default 0.05 (a still robot yields only a little) keeps a searching robot
    from shoving placed robots off their sites; 0.5 is Kilombo's symmetric push. Two moving
    or two still robots always share an overlap equally.
    ``threads``: threads the tick phases run on. 1 (the default) is the single-threaded
    simulator; more runs radio, motion and collisions on that many threads (at most the
    machine's CPUs are used) with the same physics but counter-based random draws and a
    different order of resolving overlaps (see :mod:`etswarm.sim.parallel`): results
    are deterministic and the same for every value > 1, but differ from threads = 1.
    ``control_threads``: with threads = 1, threads the controller's per-robot work runs on
    when the controller offers its step split (``part_step`` and ``rest_step``, as the ET
    controller does); radio, motion and collisions stay on one thread with the same random
    draws, so results are byte-identical to ``control_threads`` 1. Each call of the loop
    runs on this many threads or on one, whichever has lately been faster.
    ``message_delay_ticks``: ticks between a broadcast and the control tick that reads it.
    0: a message sent at tick t (the sender's outgoing message after tick t - 1, its
    distance from the positions after tick t - 1's motion) is read at tick t. 1: it is
    read at tick t + 1, 32 ms later, as a robot's loop handles a message received
    during its previous iteration. With 1 the split loop (``control_threads``) delivers
    a tick's messages on one thread while the others run the controller, and the results
    do not depend on the thread count either. Not with ``threads`` > 1.
    ``portable_math``: compute sines, cosines, arctangents, logarithms and normal draws
    with :mod:`etswarm.sim.fpmath`, which gives the same bits on every machine (the
    default since session 53), instead of the platform's maths library, whose code (and
    last bits) glibc picks by CPU. With it a seed gives the same run on any machine;
    ``False`` gives the runs of sessions up to 52 on the machine they ran on.
    """

    ticks_per_s: int = 31
    tx_period: int = 15
    comm_range_mm: float = 70.0
    loss: float = 0.0
    dist_noise_mm: float = 0.0
    body_radius_mm: float = 16.5
    speed_mm_s: float = 7.0
    turn_rate_deg_s: float = 13.0
    speed_spread: float = 0.0
    turn_rate_spread: float = 0.0
    speed_noise: float = 0.0
    heading_noise_deg: float = 0.0
    leg_angle_deg: float = 125.5
    inbox_capacity: int = 32
    arena_mm: float = 0.0
    push_slop_mm: float = 0.1
    max_push_passes: int = 4
    still_push_share: float = 0.05
    threads: int = 1
    control_threads: int = 1
    message_delay_ticks: int = 0
    portable_math: bool = True
    source: str = field(default="", compare=False, repr=False)

    def __post_init__(self) -> None:
        where = f" in {self.source}" if self.source else ""
        for f in fields(self):
            bad = f"sim parameter {f.name}{where}:"
            if f.name == "source":
                continue
            value = getattr(self, f.name)
            if f.name == "portable_math":
                if not isinstance(value, bool):
                    raise EtswarmError(f"{bad} expected true or false, got {value!r}")
                continue
            want_int = f.type in (int, "int")
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise EtswarmError(f"{bad} expected a number, got {value!r}")
            if want_int and not float(value).is_integer():
                raise EtswarmError(f"{bad} expected an integer, got {value!r}")
            if not math.isfinite(value):
                raise EtswarmError(f"{bad} must be finite, got {value!r}")
            lo, hi = _RANGES[f.name]
            if (lo is not None and value < lo) or (hi is not None and value > hi):
                raise EtswarmError(f"{bad} {value!r} is outside [{lo}, {hi}]")
            object.__setattr__(self, f.name, int(value) if want_int else float(value))
        if self.message_delay_ticks and self.threads > 1:
            raise EtswarmError(f"sim parameters{where}: message_delay_ticks 1 needs threads 1 "
                               f"(got threads {self.threads}); use control_threads")

    @property
    def dt(self) -> float:
        """Seconds per tick."""
        return 1.0 / self.ticks_per_s

    @property
    def walls(self) -> bool:
        """True when the arena has walls."""
        return self.arena_mm > 0

    def kernel_config(self) -> KernelConfig:
        """The values the compiled kernel reads, converted to rad and seconds."""
        return KernelConfig(
            dt=1.0 / self.ticks_per_s,
            tx_period=self.tx_period,
            comm_range=self.comm_range_mm,
            loss=self.loss,
            dist_noise=self.dist_noise_mm,
            radius=self.body_radius_mm,
            speed_noise=self.speed_noise,
            heading_noise=math.radians(self.heading_noise_deg),
            leg_angle=math.radians(self.leg_angle_deg),
            arena=self.arena_mm,
            max_passes=self.max_push_passes,
            slop=self.push_slop_mm,
            still_share=self.still_push_share,
            msg_delay=self.message_delay_ticks,
            portable=self.portable_math,
        )

    def with_overrides(self, **overrides: Any) -> SimParams:
        """A copy with some values replaced; ``None`` values are ignored (CLI defaults)."""
        given = {k: v for k, v in overrides.items() if v is not None}
        names = {f.name for f in fields(self)} - {"source"}
        for key in given:
            if key not in names:
                known = ", ".join(sorted(names))
                raise EtswarmError(f"unknown sim parameter {key!r} (known: {known})")
        return dataclasses.replace(self, **given)

    def to_dict(self) -> dict[str, Any]:
        """The parameters as a plain dict (for headers and final-state JSON); ``threads``
        and ``message_delay_ticks`` only when they are not at their defaults (they change
        results, but files of earlier runs stay as they were), ``portable_math`` always
        (files before session 53 lack it: their runs used the platform's maths),
        ``control_threads`` never (it changes only the speed)."""
        return {f.name: getattr(self, f.name) for f in fields(self)
                if f.name not in ("source", "control_threads")
                and not (f.name == "threads" and self.threads == 1)
                and not (f.name == "message_delay_ticks" and self.message_delay_ticks == 0)}

    @classmethod
    def from_mapping(cls, values: dict[str, Any], source: str = "") -> SimParams:
        """Build from a dict (e.g. a TOML table); unknown keys are an error."""
        names = {f.name for f in fields(cls)} - {"source"}
        where = f" in {source}" if source else ""
        for key in values:
            if key not in names:
                raise EtswarmError(f"unknown sim parameter {key!r}{where}")
        return cls(**values, source=source)

    @classmethod
    def from_toml(cls, path: str | Path) -> SimParams:
        """Read a TOML file: keys at top level, or in a ``[sim]`` table (others ignored)."""
        path = Path(path)
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise EtswarmError(f"config file {path} not found") from None
        except tomllib.TOMLDecodeError as err:
            raise EtswarmError(f"config file {path}: invalid TOML ({err})") from None
        if "sim" in data and isinstance(data["sim"], dict):
            # Other tables belong to other parts (e.g. [et]); loose keys are a mistake.
            extra = [k for k, v in data.items() if k != "sim" and not isinstance(v, dict)]
            if extra:
                raise EtswarmError(f"unknown sim parameter {extra[0]!r} in {path}")
            data = data["sim"]
        return cls.from_mapping(data, source=str(path))
