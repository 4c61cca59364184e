"""A moving robot pushing a still one: the still one yields only its share of the overlap."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.sim import FORWARD, SimParams, Simulator, World


class Silent:
    """Slow-path controller that leaves the motors as the test set them."""

    def step(self, view) -> None:
        pass


@pytest.mark.parametrize("share", [0.05, 0.5])
def test_still_robot_takes_its_share_of_a_push(share: float) -> None:
    params = SimParams(still_push_share=share)
    # robot 0 drives straight at robot 1 (touching distance 33 mm) for 5 s
    world = World.from_positions([[0.0, 0.0], [34.0, 0.0]], [0.0, 0.0], params)
    world.motor[:] = [FORWARD, 0]
    sim = Simulator(world, Silent(), params)
    sim.run_ticks(31 * 5)
    pushed = world.pos[1, 0] - 34.0
    driven = 7.0 * 5 - 1.0  # how far the mover tried to go past first contact (mm)
    assert pushed > 0  # a pushed robot moves
    assert pushed == pytest.approx(driven * share, abs=0.3)
    # each tick the mover gives back (1 - share) of its step: the pair advances together
    assert world.pos[0, 0] == pytest.approx(1.0 + driven * share, abs=0.3)
    gap = np.hypot(*(world.pos[1] - world.pos[0]))
    assert gap >= 33.0 - 0.5  # no overlap beyond the tolerance


def test_bad_share_is_rejected() -> None:
    from etswarm.errors import EtswarmError

    with pytest.raises(EtswarmError, match="still_push_share"):
        SimParams(still_push_share=1.5)
