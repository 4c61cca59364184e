"""A lost searcher blocked by another remnant goes round it (``ETParams.lost_escape_s``).

Traced on dumbbell `split y=mid` seed 12 (session 50): the cut left the bottom half as two
remnants about 70 mm apart. Robot 23 of the right one was not kept by its scaled target,
searched, lost its group in the gap and circled home there. Its spiral's course led into
the left remnant, whose robots are only obstacles to it (``foreign_robots``): it pivoted
away, pivoted back to the course and met them again, from 4800 s to the end of the 4 h run,
and its own remnant stayed one site short. Now it edge-follows the robots that blocked it
for a while, and on its way round them it comes back into earshot of its own remnant.
"""

from __future__ import annotations

import pytest

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError

from .traced import NATIVE_MATHS, SESSION_57_SEARCH


def cut_dumbbell(**options: float) -> dict:
    """Summary of dumbbell `split y=mid` seed 12 over 4 h, with ``options`` set."""
    run = ETRun(RunConfig(shape="dumbbell", seed=12, damage=("split y=mid",),
                          max_time_s=4 * 3600, et=ETParams(**{**SESSION_57_SEARCH, **options})),
                sim_params=NATIVE_MATHS)
    return run.run()


def test_a_searcher_lost_beside_a_sibling_remnant_finds_its_own() -> None:
    summary = cut_dumbbell()
    groups = summary["components"]
    assert sorted(c["robots"] for c in groups) == [15, 17, 29]
    for group in groups:
        assert group["formed"] and group["jaccard"] == 1.0
        assert group["census_count"] == group["robots"]
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1


def test_without_the_escape_the_searcher_stays_at_the_sibling() -> None:
    summary = cut_dumbbell(lost_escape_s=0)
    # The 15-robot remnant ends as 14 robots one site short, and its last searcher alone
    # out of their earshot (at the left remnant).
    short = [c for c in summary["components"] if c["census_count"] == 15]
    assert sorted(c["robots"] for c in short) == [1, 14]
    assert not any(c["formed"] for c in short)
    assert [c["searching"] for c in short if c["robots"] == 1] == [1]


def test_lost_escape_s_may_be_zero_but_not_negative() -> None:
    assert ETParams(lost_escape_s=0).lost_escape_s == 0
    with pytest.raises(EtswarmError, match="lost_escape_s"):
        ETParams(lost_escape_s=-1)
