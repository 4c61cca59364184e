"""Damage specifications: ``KIND REGION [at=TIME]`` strings and their parsed form.

Kinds (DESIGN §4): ``split`` cuts the swarm by a line and moves one side out of radio
range; ``remove`` makes robots vanish; ``kill`` stops robots and silences them, leaving
them as obstacles.

Regions, in lattice spacings in the world frame (origin: the gene's (0, 0) site; x along
the lattice X direction, y up):

- ``x=V`` / ``y=V`` (split only): the line x = V or y = V; the side with larger x (y)
  moves away.
- ``x<V``, ``x>V``, ``y<V``, ``y>V``: a half-plane.
- In both, ``V`` may be ``mid``: the middle of the present robots' extent along that
  axis when the damage happens (``split x=mid`` cuts the shape through its middle).
- ``disc=CX,CY,R``: a disc.
- ``band=x,LO,HI`` / ``band=y,LO,HI``: the strip LO <= x (or y) <= HI.
- ``random=F``: a random fraction F of the robots (damage random stream).
- ``ids=A,B,...``: robot IDs.

Times: ``at=formed`` (default: when the current targets are all formed), ``at=formed+S``
(S seconds later), ``at=S`` (S simulated seconds from the start).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from etswarm.errors import EtswarmError

KINDS = ("split", "remove", "kill")
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)"


@dataclass(frozen=True)
class DamageSpec:
    """A parsed damage: what, where, when.

    Attributes:
        kind: "split", "remove" or "kill".
        region: "line", "half", "disc", "band", "random" or "ids".
        axis: "x" or "y" for line, half and band regions, else "".
        op: "<" or ">" for half-planes, "=" for lines, else "".
        values: the numbers of the region (spacings; a fraction for random; IDs for ids).
        at_formed: True when the time counts from formation.
        at_s: seconds (from the start, or after formation when ``at_formed``).
        text: the specification as given.
        mid: for line and half regions, the value is the middle of the present robots'
            extent at damage time (``values`` then holds 0.0).
    """

    kind: str
    region: str
    axis: str
    op: str
    values: tuple[float, ...]
    at_formed: bool
    at_s: float
    text: str
    mid: bool = False


def _numbers(text: str, spec: str, count: int | None = None) -> tuple[float, ...]:
    parts = [p for p in text.split(",") if p != ""]
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        raise EtswarmError(f"--damage {spec!r}: {text!r} is not a list of numbers") from None
    if count is not None and len(values) != count:
        raise EtswarmError(f"--damage {spec!r}: expected {count} numbers, got {len(values)}")
    return values


def _parse_time(text: str, spec: str) -> tuple[bool, float]:
    if not text.startswith("at="):
        raise EtswarmError(f"--damage {spec!r}: expected at=TIME, got {text!r}")
    value = text[3:]
    if value == "formed":
        return True, 0.0
    m = re.fullmatch(rf"formed\+({_NUMBER})", value)
    if m:
        return True, float(m.group(1))
    if re.fullmatch(_NUMBER, value):
        if float(value) < 0:
            raise EtswarmError(f"--damage {spec!r}: time must be >= 0 s, got {value}")
        return False, float(value)
    raise EtswarmError(
        f"--damage {spec!r}: time {value!r} is not 'formed', 'formed+SECONDS' or SECONDS"
    )


def parse_damage(spec: str) -> DamageSpec:
    """Parse ``KIND REGION [at=TIME]``; raise EtswarmError naming what is wrong."""
    words = spec.split()
    if len(words) not in (2, 3):
        raise EtswarmError(
            f"--damage {spec!r}: expected 'KIND REGION [at=TIME]', e.g. 'split x=0' or "
            "'remove random=0.2 at=formed+60'"
        )
    kind, region_text = words[0], words[1]
    if kind not in KINDS:
        raise EtswarmError(f"--damage {spec!r}: kind must be one of {', '.join(KINDS)}")
    at_formed, at_s = _parse_time(words[2], spec) if len(words) == 3 else (True, 0.0)
    m = re.fullmatch(rf"([xy])([<>=])({_NUMBER}|mid)", region_text)
    if m:
        axis, op = m.group(1), m.group(2)
        mid = m.group(3) == "mid"
        value = 0.0 if mid else float(m.group(3))
        if op == "=" and kind != "split":
            raise EtswarmError(f"--damage {spec!r}: a line x=V/y=V is for split; use x<V or x>V")
        if op != "=" and kind == "split":
            raise EtswarmError(
                f"--damage {spec!r}: split takes a line, x=V or y=V (V a number or mid)"
            )
        region = "line" if op == "=" else "half"
        return DamageSpec(kind, region, axis, op, (value,), at_formed, at_s, spec, mid)
    if kind == "split":
        raise EtswarmError(f"--damage {spec!r}: split takes a line, x=V or y=V (V a number or mid)")
    key, sep, rest = region_text.partition("=")
    if not sep:
        raise EtswarmError(f"--damage {spec!r}: region {region_text!r} is not NAME=VALUES")
    if key == "disc":
        cx, cy, r = _numbers(rest, spec, 3)
        if r <= 0:
            raise EtswarmError(f"--damage {spec!r}: disc radius must be > 0")
        return DamageSpec(kind, "disc", "", "", (cx, cy, r), at_formed, at_s, spec)
    if key == "band":
        axis, _, nums = rest.partition(",")
        if axis not in ("x", "y"):
            raise EtswarmError(f"--damage {spec!r}: band takes x,LO,HI or y,LO,HI")
        lo, hi = _numbers(nums, spec, 2)
        if lo > hi:
            raise EtswarmError(f"--damage {spec!r}: band LO must not exceed HI")
        return DamageSpec(kind, "band", axis, "", (lo, hi), at_formed, at_s, spec)
    if key == "random":
        (fraction,) = _numbers(rest, spec, 1)
        if not 0 < fraction < 1:
            raise EtswarmError(f"--damage {spec!r}: random fraction must be in (0, 1)")
        return DamageSpec(kind, "random", "", "", (fraction,), at_formed, at_s, spec)
    if key == "ids":
        ids = _numbers(rest, spec)
        if not ids or any(v < 0 or v != int(v) for v in ids):
            raise EtswarmError(f"--damage {spec!r}: ids must be non-negative integers")
        return DamageSpec(kind, "ids", "", "", ids, at_formed, at_s, spec)
    raise EtswarmError(
        f"--damage {spec!r}: unknown region {key!r}; use x<V, y>V, x=V, disc=, band=, "
        "random= or ids="
    )
