"""A searcher long at the shape stops refusing captures for the pinch guard.

Traced on disc seeds 217 and 259 (fresh seeds of session 29): the last three free sites
lay side by side and every capture there would narrow another, so each searcher refused
them until it had used its four refusals, which took it three to four hours at the shape.
Once one took a site, the other two filled within minutes.
"""

from __future__ import annotations

import pytest

from etswarm.algorithm.params import F_PINCH_PATIENCE, ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError

from .traced import NATIVE_MATHS, SESSION_44_FORMATION


@pytest.mark.parametrize("patience_s", [0.0, 3600.0])
def test_disc_seed_259_forms_once_long_searchers_stop_refusing(patience_s: float) -> None:
    run = ETRun(RunConfig(shape="disc", seed=259, max_time_s=4 * 3600,
                          et=ETParams(pinch_patience_s=patience_s, **SESSION_44_FORMATION)),
                sim_params=NATIVE_MATHS)
    summary = run.run()
    assert not summary["duplicate_tags"]
    if patience_s > 0:
        assert summary["formed"] and summary["jaccard"] == 1.0
    else:
        # the refusals held the last sites free past the 4 h limit
        assert not summary["formed"]
        assert summary["components"][0]["free_sites"] >= 2
        assert summary["states"]["Search"] == summary["components"][0]["free_sites"]


def test_the_patience_is_packed_in_ticks_and_checked() -> None:
    _ci, cf = ETParams(pinch_patience_s=100.0).pack(31, 0, 0)
    assert cf[F_PINCH_PATIENCE] == 3100.0
    with pytest.raises(EtswarmError, match="pinch_patience_s must be >= 0"):
        ETParams(pinch_patience_s=-1.0)
