"""etswarm: a Kilobot swarm simulator running distributed Epigenetic Tracking.

Layout: ``shapes`` (bitmap -> lattice -> gene -> scaled shapes), ``sim`` (the
robot world), ``algorithm`` (the ET controller), ``damage``, ``measures``,
``viewer`` (renderer, window, video), ``experiments`` (sweeps) and ``cli``.
"""

from etswarm.compile_cache import use_versioned_cache

__version__ = "0.1.0"

# before any module that compiles with numba's disk cache is imported
use_versioned_cache()
