"""Seeded randomness: one integer seed, independent named child streams.

Every random draw in etswarm comes from a ``numpy.random.Generator`` obtained here,
never from global state. A stream is identified by (seed, name); the name is hashed
with CRC-32 so the mapping is the same on every machine and Python version.
"""

from __future__ import annotations

import zlib

import numpy as np

#: Names of the streams the simulator and the algorithm use.
STREAM_NAMES = ("motion", "radio", "placement", "controller", "damage")


def stream(seed: int, name: str) -> np.random.Generator:
    """Return the generator for stream ``name`` of run ``seed``.

    Same (seed, name) -> same sequence; different names -> independent sequences.
    """
    if seed < 0:
        raise ValueError(f"seed must be >= 0, got {seed}")
    key = zlib.crc32(name.encode("utf-8"))
    return np.random.Generator(np.random.PCG64(np.random.SeedSequence([int(seed), key])))


def streams(seed: int, names: tuple[str, ...] = STREAM_NAMES) -> dict[str, np.random.Generator]:
    """Return ``{name: generator}`` for every name in ``names``."""
    return {name: stream(seed, name) for name in names}
