"""Damage specifications: parsing, errors, and applying them to a world."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.damage import apply_damage, parse_damage
from etswarm.errors import EtswarmError
from etswarm.seeding import stream
from etswarm.sim.world import World


def test_parse_kinds_regions_and_times() -> None:
    s = parse_damage("split x=0.5")
    assert (s.kind, s.region, s.axis, s.values, s.at_formed, s.at_s) == (
        "split", "line", "x", (0.5,), True, 0.0
    )
    s = parse_damage("remove disc=1,2,1.5 at=3600")
    assert (s.region, s.values, s.at_formed, s.at_s) == ("disc", (1.0, 2.0, 1.5), False, 3600.0)
    s = parse_damage("kill ids=4,9 at=formed+120")
    assert (s.region, s.values, s.at_formed, s.at_s) == ("ids", (4.0, 9.0), True, 120.0)
    assert parse_damage("remove x<0").op == "<"
    assert parse_damage("remove band=y,-1,1").values == (-1.0, 1.0)
    assert parse_damage("remove random=0.2").values == (0.2,)


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("split", "expected 'KIND REGION"),
        ("smash x=0", "kind must be one of"),
        ("remove x=0", "a line x=V/y=V is for split"),
        ("split x<0", "split takes a line"),
        ("remove disc=1,2", "expected 3 numbers"),
        ("remove random=1.5", "random fraction must be in (0, 1)"),
        ("remove ids=1,-2", "non-negative integers"),
        ("remove x<0 at=soon", "is not 'formed'"),
        ("remove blob=3", "unknown region 'blob'"),
    ],
)
def test_bad_specs_get_one_line_errors(spec: str, message: str) -> None:
    with pytest.raises(EtswarmError) as err:
        parse_damage(spec)
    assert message in str(err.value)
    assert "\n" not in str(err.value)
    assert spec in str(err.value)


def test_apply_split_remove_kill() -> None:
    pos = np.array([[-40.0, 0.0], [0.0, 0.0], [40.0, 0.0], [80.0, 0.0]])
    world = World.from_positions(pos, np.zeros(4))
    moved = apply_damage(parse_damage("split x=0.5"), world, 40.0, stream(0, "damage"))
    assert moved.tolist() == [2, 3]
    assert world.pos[2, 0] > 40.0 + 70.0
    removed = apply_damage(parse_damage("remove x<0"), world, 40.0, stream(0, "damage"))
    assert removed.tolist() == [0] and not world.present[0]
    killed = apply_damage(parse_damage("kill ids=1"), world, 40.0, stream(0, "damage"))
    assert killed.tolist() == [1] and world.present[1] and not world.alive[1]


def test_mid_cuts_through_the_middle_of_the_robots() -> None:
    spec = parse_damage("split y=mid")
    assert (spec.region, spec.axis, spec.mid) == ("line", "y", True)
    assert parse_damage("remove x>mid").mid
    # Robots from x = 1 to 7 spacings: the middle is x = 4, so the three right of it move.
    pos = np.array([[40.0 * k, 0.0] for k in range(1, 8)])
    world = World.from_positions(pos, np.zeros(7))
    moved = apply_damage(parse_damage("split x=mid"), world, 40.0, stream(0, "damage"))
    assert moved.tolist() == [4, 5, 6]
