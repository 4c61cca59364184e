"""etswarm: a Kilobot swarm simulator running distributed Epigenetic Tracking.

Layout: ``shapes`` (bitmap -> lattice -> gene -> scaled shapes), ``sim`` (the
robot world), ``algorithm`` (the ET controller), ``damage``, ``measures``,
``viewer`` (renderer, window, video), ``experiments`` (sweeps) and ``cli``.
"""

__version__ = "0.1.0"
