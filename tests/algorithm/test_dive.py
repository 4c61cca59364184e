"""``dive_mm``: in the first formation a searcher long at the shape edge-follows nearer,
into notches the growth pinched narrower than 2 d, where the last free sites sat."""

from __future__ import annotations

import pytest

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig

from .traced import NATIVE_MATHS, SESSION_19_WIDENING

#: The settings these runs were traced with (session 12): with the wider consistency
#: tolerance of session 13 the same seeds form without diving too.
# the settings these runs were traced with (before the pinched-mouth default, the lookahead,
# held-site gossip, site offsets, lost searchers' homing and session 20's faster widening)
TRACED = {
    "consistency_widen_max": 1.0, "fill_lookahead": "off", "held_gossip_every": 0,
    "site_offsets": "off", "lost_homing": "off", **SESSION_19_WIDENING,
}


def formation(shape: str, seed: int, **et: float) -> dict:
    params = ETParams(**{**TRACED, **et})
    config = RunConfig(shape=shape, seed=seed, max_time_s=4 * 3600, et=params)
    summary = ETRun(config, sim_params=NATIVE_MATHS).run()
    assert summary["duplicate_tags"] == []
    return summary


@pytest.mark.parametrize(("shape", "seed"), [("disc", 0), ("heart", 24)])
def test_diving_searchers_fill_the_last_sites(shape: str, seed: int) -> None:
    # Both stall for the 4 h without diving (pinched and narrow last sites).
    level = formation(shape, seed, dive_mm=0.0)
    assert not level["formed"]
    summary = formation(shape, seed)
    assert summary["formed"] and summary["jaccard"] == 1.0
    assert summary["states"]["Stable"] == summary["robots"]
