"""The lookahead on a searcher's memory: a capture that leaves a pocket nobody can fill
is refused, an ordinary one is not, and a shape that is stuck already refuses nothing."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.fill_order import finishes, locatable, strands_a_site
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig

from .traced import NATIVE_MATHS, SESSION_19_WIDENING

#: Gene grid and memory window: tags -3..7 in both axes.
ORIGIN = -3
SIZE = 11
#: The free sites of the pocket traced on heart seed 4: a triangle (2, 0), (3, 0), (3, 1)
#: and (4, 0), which has a single held neighbour.
POCKET = [(2, 0), (3, 0), (3, 1), (4, 0)]
#: The capture that closes the pocket's second way out.
CLOSING = (2, -1)


def notched_shape():  # type: ignore[no-untyped-def]
    """A block of shape sites with a notch cut out below and right of (4, 0), as at the
    cleft of the heart: (3, -1), (4, -1), (5, 0) and (5, 1) lie outside the shape."""
    gene = np.zeros((SIZE, SIZE), dtype=np.uint8)
    for x in range(-2, 7):
        for y in range(-2, 6):
            outside = (y <= -1 and x >= 3) or (x >= 5 and y <= 1)
            gene[x - ORIGIN, y - ORIGIN] = 0 if outside else 1
    ci, _ = ETParams().pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    return gene, ci


def memory_with_free(gene, free):  # type: ignore[no-untyped-def]
    """A memory that holds every shape site except ``free``."""
    held = gene.copy()
    for x, y in free:
        held[x - ORIGIN, y - ORIGIN] = 0
    return held


def test_the_capture_that_closes_the_pocket_is_refused() -> None:
    gene, ci = notched_shape()
    held = memory_with_free(gene, [*POCKET, CLOSING])
    assert finishes(held.copy(), ORIGIN, ORIGIN, gene, ci, *CLOSING)
    assert strands_a_site(CLOSING[0], CLOSING[1], held, ORIGIN, ORIGIN, gene, ci)
    # the memory itself is left as it was
    assert held[CLOSING[0] - ORIGIN, CLOSING[1] - ORIGIN] == 0


def test_the_deepest_site_of_the_pocket_may_be_taken_first() -> None:
    gene, ci = notched_shape()
    held = memory_with_free(gene, [*POCKET, CLOSING])
    assert locatable(3, 1, held, ORIGIN, ORIGIN)
    assert not strands_a_site(3, 1, held, ORIGIN, ORIGIN, gene, ci)


def test_a_shape_that_is_stuck_already_refuses_nothing() -> None:
    gene, ci = notched_shape()
    held = memory_with_free(gene, POCKET)
    assert not finishes(held.copy(), ORIGIN, ORIGIN, gene, ci, *CLOSING)
    for x, y in POCKET:
        assert not strands_a_site(x, y, held, ORIGIN, ORIGIN, gene, ci)


def test_heart_seed_9_forms_only_with_the_lookahead() -> None:
    """Heart seed 9 stalls for 4 h without the lookahead (13 shapes, seeds 0-29: 351
    formed with it, 346 without)."""
    outcomes = {}
    for lookahead in ("off", "on"):
        config = RunConfig(
            shape="heart", seed=9, max_time_s=4 * 3600.0,
            # as traced
            et=ETParams(
                fill_lookahead=lookahead, held_gossip_every=0, site_offsets="off",
                lost_homing="off", **SESSION_19_WIDENING,
            ),
        )
        run = ETRun(config, sim_params=NATIVE_MATHS)
        summary = run.run()
        assert summary["duplicate_tags"] == []
        outcomes[lookahead] = summary["formed"]
    assert outcomes == {"off": False, "on": True}
