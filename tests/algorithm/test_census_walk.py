"""Census by walking round the remnant (census ``walk``): the count from collected tags,
and end to end on a split triangle."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from etswarm.algorithm.api import run_experiment
from etswarm.algorithm.census_walk import opens_outside, walk_count
from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.memory import R_TAG_X, R_TAG_Y
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.cli.run_command import run as run_command
from etswarm.errors import EtswarmError
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS

from .traced import SESSION_34_FORMATION


def hexagon_cells(radius: int) -> list[tuple[int, int]]:
    """Tags within ``radius`` lattice steps of (0, 0) (skewed axes: |x|, |y|, |x-y|)."""
    return [
        (x, y)
        for x in range(-radius, radius + 1)
        for y in range(-radius, radius + 1)
        if max(abs(x), abs(y), abs(x - y)) <= radius
    ]


def grid(cells: list[tuple[int, int]], size: int = 13, origin: int = 6) -> np.ndarray:
    out = np.zeros((size, size), dtype=np.uint8)
    for x, y in cells:
        out[x + origin, y + origin] = 1
    return out


def test_walk_count_counts_the_ones_inside_and_on_the_collected_ring() -> None:
    flags = grid(hexagon_cells(3))  # 37 cells
    ring = [c for c in hexagon_cells(3) if c not in hexagon_cells(2)]
    assert walk_count(grid(ring), flags) == 37


def test_walk_count_overcounts_a_hole_inside_and_ignores_ones_outside() -> None:
    flags = grid(hexagon_cells(3))
    ring = [c for c in hexagon_cells(3) if c not in hexagon_cells(2)]
    # Robots gone from the middle: the walk never sees them, so they are still counted.
    assert walk_count(grid(ring), flags) == len(hexagon_cells(3))
    # A remnant that is only the ring's right part: what lies beyond it is not counted.
    part = [(x, y) for x, y in hexagon_cells(3) if x >= 1]
    boundary = [c for c in part if any((c[0] + dx, c[1] + dy) not in part for dx, dy in
                                       NEIGHBOUR_OFFSETS.tolist())]
    assert walk_count(grid(boundary), flags) == len(part)


def test_walk_count_leaks_through_a_gap_in_the_ring() -> None:
    flags = grid(hexagon_cells(3))
    ring = [c for c in hexagon_cells(3) if c not in hexagon_cells(2) and c != (3, 0)]
    # Without one boundary tag the flood gets in: only the ring's cells are counted.
    assert walk_count(grid(ring), flags) == len(ring)


def test_a_ring_round_a_hole_is_told_from_a_ring_round_the_outside() -> None:
    ring = [c for c in hexagon_cells(3) if c not in hexagon_cells(2)]
    # From (3, 0) on the outer ring, its free neighbour sites (directions 1, 2, 3) are
    # outside: the walk went round the remnant.
    assert opens_outside(grid(ring), 3 + 6, 0 + 6, 0b110001)
    # The six robots round a one-site hole, the walker at (1, 0) among them: its only free
    # neighbour site (the hole, direction 5) is shut in, so that walk went round the hole.
    hole_ring = [(dx, dy) for dx, dy in NEIGHBOUR_OFFSETS.tolist()]
    assert not opens_outside(grid(hole_ring), 1 + 6, 0 + 6, 0b011111)
    assert opens_outside(grid(hole_ring), 1 + 6, 0 + 6, 0b111011)


def test_census_parameter_is_checked_and_reaches_the_kernel() -> None:
    with pytest.raises(EtswarmError):
        ETParams(census="guess")
    config = RunConfig(shape="triangle", census="walk")
    assert config.et.census == "walk"
    assert RunConfig(shape="triangle").census == "tree"
    ctl = ETController(4, np.array([[0, 0], [1, 0], [1, 1]]), config.et, 31)
    assert ctl.walk_seen.shape == (4, *ctl.grid_shape)


def test_census_is_a_run_parameter_and_a_cli_option() -> None:
    assert run_experiment({"shape": "triangle", "census": "walk", "max_time_s": 2})[
        "census"
    ] == "walk"
    assert "census" in run_experiment.parameters  # type: ignore[attr-defined]
    result = CliRunner().invoke(
        run_command, ["triangle", "--census", "walk", "--max-time", "2", "--json"]
    )
    assert result.exit_code == 0, result.output
    assert json.loads(result.output)["census"] == "walk"
    result = CliRunner().invoke(run_command, ["triangle", "--census", "count", "--json"])
    assert result.exit_code != 0


class WatchedRun(ETRun):
    """Records where each Leader stands, relative to its site's neighbours, when it asks
    for its scaled target (the simulator's view; the robots never see it)."""

    def __init__(self, config: RunConfig) -> None:
        super().__init__(config)
        self.leader_offsets: dict[int, list[float]] = {}

    def _answer_requests(self) -> None:
        ctl = self.controller
        d = self.config.et.spacing_mm
        tags = ctl.ri[:, [R_TAG_X, R_TAG_Y]]
        for leader in ctl.pending_requests():
            home = tags[leader]
            group = self._radio_group_of(int(leader))
            errors = []
            for j in group:
                if j != leader and tuple((tags[j] - home).tolist()) in {
                    tuple(o) for o in NEIGHBOUR_OFFSETS.tolist()
                }:
                    dist = float(np.linalg.norm(self.world.pos[j] - self.world.pos[leader]))
                    errors.append(abs(dist - d))
            self.leader_offsets[int(leader)] = errors
        super()._answer_requests()


def test_walk_census_on_a_split_triangle() -> None:
    config = RunConfig(
        # seed 9: both Leaders have two or more lattice neighbours in their remnants
        shape="triangle", seed=9, max_time_s=3 * 3600, damage=("split x=0 at=formed+30",),
        census="walk", et=ETParams(**SESSION_34_FORMATION),
    )
    run = WatchedRun(config)
    summary = run.run()
    assert summary["formed"] and summary["settled"]
    assert summary["census"] == "walk"
    censuses = [e for e in summary["events"] if e["kind"] == "census"]
    leaders = [e for e in summary["events"] if e["kind"] == "leader"]
    # One Leader, one census per remnant; exact counts (no holes); walked back home.
    assert len(censuses) == len(leaders) == 2
    moved = next(e["robots"] for e in summary["events"] if e["kind"] == "damage")
    assert sorted(e["robots"] for e in censuses) == sorted([moved, 15 - moved])
    for e in censuses:
        assert e["method"] == "walk"
        assert e["result"] == "returned"
        assert e["count"] == e["robots"]
        assert e["duration_s"] > 10  # it really went round
    assert summary["max_leaders_per_component"] <= 1
    assert summary["duplicate_tags"] == []
    # The Leader stands on its own site again: at d from the robots of the neighbouring
    # sites, within what localisation allows (the formed shape itself is off by ~5 mm).
    for leader, errors in run.leader_offsets.items():
        assert len(errors) >= 2, leader
        assert max(errors) < 10.0, (leader, errors)
    for comp in summary["components"]:
        assert comp["census_count"] == comp["robots"]
        assert comp["formed"] and comp["jaccard"] == 1.0
