"""Thin shapes' first-formation settings (``thin_depth``): which shapes count as thin, what
the packed constants become, and a thin formation with them on."""

from __future__ import annotations

import pytest

from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.params import (
    C_REGROW_RETRIES,
    C_RIGHT_OF_WAY,
    C_SETTLE_RETRIES,
    C_TICKS_CLEAR,
    C_TICKS_CLEAR_FIRST,
    RIGHT_OF_WAY_ALWAYS,
    RIGHT_OF_WAY_FIRST_GROWTH,
    RIGHT_OF_WAY_NEVER,
    ETParams,
)
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError
from etswarm.shapes.lattice import depths
from etswarm.shapes.shape import load_shape

TPS = 31


@pytest.mark.parametrize(
    ("shape", "depth"), [("T", 2), ("L", 1), ("H", 2), ("starfish", 3), ("disc", 4)]
)
def test_library_shapes_have_the_depths_the_docs_give(shape: str, depth: int) -> None:
    assert int(depths(load_shape(shape).cells).max()) == depth


def test_a_thin_shape_packs_the_thin_settings_for_its_first_formation_only() -> None:
    et = ETParams(thin_depth=2, settle_retries=1, release_clear_s=15.0)
    thin, _ = et.pack(TPS, 0, 0, shape_depth=2)
    assert thin[C_SETTLE_RETRIES] == et.thin_settle_retries == 3
    assert thin[C_TICKS_CLEAR_FIRST] == round(et.thin_release_clear_s * TPS)
    # after damage the usual settings hold
    assert thin[C_TICKS_CLEAR] == round(15.0 * TPS)
    assert thin[C_REGROW_RETRIES] == et.regrowth_settle_retries
    compact, _ = et.pack(TPS, 0, 0, shape_depth=3)
    assert compact[C_SETTLE_RETRIES] == 1
    assert compact[C_TICKS_CLEAR_FIRST] == compact[C_TICKS_CLEAR] == round(15.0 * TPS)
    # off, and an unknown depth, change nothing
    off, _ = ETParams(thin_depth=0, settle_retries=1).pack(TPS, 0, 0, shape_depth=2)
    unknown, _ = et.pack(TPS, 0, 0)
    assert (off == compact).all() and (unknown == compact).all()


def test_right_of_way_is_given_in_a_thin_first_formation_only_unless_asked_for() -> None:
    thin = ETParams(thin_depth=2)
    assert thin.pack(TPS, 0, 0, shape_depth=2)[0][C_RIGHT_OF_WAY] == RIGHT_OF_WAY_FIRST_GROWTH
    assert thin.pack(TPS, 0, 0, shape_depth=3)[0][C_RIGHT_OF_WAY] == RIGHT_OF_WAY_NEVER  # compact
    off = ETParams(thin_depth=0)
    assert off.pack(TPS, 0, 0, shape_depth=2)[0][C_RIGHT_OF_WAY] == RIGHT_OF_WAY_NEVER
    no_way = ETParams(thin_depth=2, thin_right_of_way="off")
    assert no_way.pack(TPS, 0, 0, shape_depth=2)[0][C_RIGHT_OF_WAY] == RIGHT_OF_WAY_NEVER
    always = ETParams(thin_depth=2, right_of_way="on")
    for depth in (2, 3):
        assert always.pack(TPS, 0, 0, shape_depth=depth)[0][C_RIGHT_OF_WAY] == RIGHT_OF_WAY_ALWAYS
    with pytest.raises(EtswarmError, match="thin_right_of_way"):
        ETParams(thin_right_of_way="yes")


def test_the_controller_takes_the_depth_and_size_from_its_target() -> None:
    et = ETParams(thin_depth=2)
    t = ETController(45, load_shape("T").cells, et, TPS)
    starfish = ETController(91, load_shape("starfish").cells, et, TPS)
    big_h = ETController(321, load_shape("bigH").cells, et, TPS)  # thin, but large
    assert int(depths(load_shape("bigH").cells).max()) <= 2
    assert t.ci[C_SETTLE_RETRIES] == 3 and t.ci[C_RIGHT_OF_WAY] == RIGHT_OF_WAY_FIRST_GROWTH
    for compact_or_large in (starfish, big_h):
        assert compact_or_large.ci[C_SETTLE_RETRIES] == ETParams().settle_retries
        assert compact_or_large.ci[C_RIGHT_OF_WAY] == RIGHT_OF_WAY_NEVER


def test_a_thin_shape_larger_than_the_limit_packs_the_usual_settings() -> None:
    et = ETParams(thin_depth=2, thin_max_cells=100)
    assert et.pack(TPS, 0, 0, shape_depth=2, shape_cells=100)[0][C_SETTLE_RETRIES] == 3
    large, _ = et.pack(TPS, 0, 0, shape_depth=2, shape_cells=101)
    off, _ = ETParams(thin_depth=0).pack(TPS, 0, 0, shape_depth=2, shape_cells=101)
    assert (large == off).all()


def test_the_thin_options_are_checked() -> None:
    with pytest.raises(EtswarmError, match="thin_depth"):
        ETParams(thin_depth=-1)
    with pytest.raises(EtswarmError, match="thin_release_clear_s"):
        ETParams(thin_release_clear_s=0.0)


def test_thin_settings_are_the_default() -> None:
    assert ETParams().thin_depth == 2 and ETParams().thin_right_of_way == "on"


def test_a_t_forms_with_the_thin_settings() -> None:
    run = ETRun(RunConfig(shape="T", seed=5, max_time_s=3 * 3600.0,
                          et=ETParams(thin_depth=2)))
    summary = run.run()
    assert summary["formed"], summary["states"]
    assert summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []
    assert summary["states"]["Stable"] == 45
