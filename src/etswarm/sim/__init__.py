"""etswarm.sim: the Kilobot world simulator.

Public API::

    from etswarm.sim import SimParams, World, Simulator, RandomWalk, random_world
    params = SimParams(arena_mm=1600)
    world = random_world(1000, params, seed=1)
    sim = Simulator(world, RandomWalk(world.n), params, seed=1)
    sim.run_ticks(31 * 60)
"""

from etswarm.sim.controllers import CONTROLLERS, RandomWalk
from etswarm.sim.params import SimParams
from etswarm.sim.placement import arena_side_for, place_uniform, random_world
from etswarm.sim.simulator import ControlView, Simulator
from etswarm.sim.world import FORWARD, LEFT, PAYLOAD_BYTES, RIGHT, STOP, World

__all__ = [
    "CONTROLLERS",
    "FORWARD",
    "LEFT",
    "PAYLOAD_BYTES",
    "RIGHT",
    "STOP",
    "ControlView",
    "RandomWalk",
    "SimParams",
    "Simulator",
    "World",
    "arena_side_for",
    "place_uniform",
    "random_world",
]
