"""Growth in waves from the seeds (``wave``): hop counts, the capture test, and a disc
whose rim no longer closes round free sites."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.kernel_util import hex_distance
from etswarm.algorithm.layout import plan_layout
from etswarm.algorithm.memory import R_NN
from etswarm.algorithm.params import C_WAVE, ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.algorithm.wave import HOPS_SHIFT, behind_wave, nn_of, seed_hops
from etswarm.measures.formation import duplicate_tags, min_pair_distance
from etswarm.shapes.lattice import neighbour_counts

from .test_site_memory import ORIGIN, hexagon_gene, memory_of, ring
from .traced import NATIVE_MATHS, SESSION_47_FORMATION

SEEDS = np.array([[0, 0], [1, 0], [0, 1]])


def hexagon_cells(radius: int) -> np.ndarray:
    """(P, 2) tags within ``radius`` steps of (0, 0)."""
    return np.array([s for r in range(radius + 1) for s in ring(r)])


def test_hops_count_steps_from_the_nearest_seed_within_the_shape() -> None:
    cells = hexagon_cells(3)
    hops = dict(zip(map(tuple, cells.tolist()), seed_hops(cells, SEEDS).tolist(), strict=True))
    assert hops[(0, 0)] == hops[(1, 0)] == hops[(0, 1)] == 0
    # In a convex shape the count is the lattice distance to the nearest seed.
    for (x, y), h in hops.items():
        assert h == min(hex_distance(x - sx, y - sy) for sx, sy in SEEDS.tolist())
    assert hops[(-3, 0)] == 3
    # Around a notch the count follows the shape, not the straight line: a bar two rows
    # thick bent round, whose far end is one step from the seeds across the gap.
    bent = np.array([[x, 0] for x in range(5)] + [[4, 1], [4, 2]] + [[x, 2] for x in range(4)]
                    + [[x, 1] for x in range(0, 1)])
    hops_bent = dict(zip(map(tuple, bent.tolist()), seed_hops(bent, SEEDS[:1]).tolist(),
                         strict=True))
    assert hops_bent[(4, 0)] == 4
    assert hops_bent[(0, 2)] == 2  # through (0, 1)
    # A cell the seeds cannot reach gets the largest count plus one.
    apart = np.vstack([cells, [[9, 9]]])
    assert seed_hops(apart, SEEDS)[-1] == seed_hops(cells, SEEDS).max() + 1


def gene_with_hops() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The hexagon gene of ``test_site_memory`` with NN and hops from ``SEEDS`` packed as
    ``ETController.seed`` packs them."""
    gene, ci = hexagon_gene()
    cells = np.argwhere(gene == 1) + ORIGIN
    packed = np.zeros(gene.shape, dtype=np.int16)
    packed[cells[:, 0] - ORIGIN, cells[:, 1] - ORIGIN] = neighbour_counts(cells) + (
        seed_hops(cells, SEEDS) << HOPS_SHIFT
    )
    return gene, packed, ci


def test_a_site_waits_for_its_neighbours_nearer_the_seeds() -> None:
    gene, packed, ci = gene_with_hops()
    # (3, 0) is 2 steps from the seeds, (2, 0) 1 step. With the seeds, (2, 1) and (3, 1)
    # held, (3, 0) could be located from (3, 1) and (4, 1)'s side, but (2, 0) is free.
    held = [(0, 0), (1, 0), (0, 1), (2, 1), (3, 1)]
    assert behind_wave(3, 0, gene, packed, ci, memory_of(held), ORIGIN, ORIGIN)
    assert not behind_wave(3, 0, gene, packed, ci, memory_of([*held, (2, 0)]), ORIGIN, ORIGIN)
    # Free neighbours as near the seeds or farther never hold a site back: (-1, 0) is
    # 1 step out, beside the free (-1, -1), also 1 step out.
    assert not behind_wave(-1, 0, gene, packed, ci, memory_of(held), ORIGIN, ORIGIN)


def test_the_packed_gene_keeps_nn() -> None:
    cells = hexagon_cells(4)
    et = ETParams(wave_s=1200.0)
    ctl = ETController(len(cells), cells, et, ticks_per_s=31)
    layout = plan_layout(cells, len(cells), rng=np.random.default_rng(0))
    ctl.seed(layout)
    gx = cells[:, 0] - ctl.x0
    gy = cells[:, 1] - ctl.y0
    packed = ctl.gene_nn[0, gx, gy]
    assert np.array_equal(nn_of(packed), neighbour_counts(cells))
    assert np.array_equal(packed >> HOPS_SHIFT, seed_hops(cells, layout.seed_tags))
    nn = dict(zip(map(tuple, cells.tolist()), neighbour_counts(cells).tolist(), strict=True))
    for rid, tag in zip(layout.seed_ids, layout.seed_tags.tolist(), strict=True):
        assert ctl.ri[rid, R_NN] == nn[tuple(tag)]


def test_a_disc_whose_rim_closed_round_free_sites_forms_with_the_wave() -> None:
    # disc seed 213 (traced before the first-formation plunge) without the wave ends 4 h
    # with free sites walled in (Jaccard 0.945); with it the disc fills from the seeds
    # outwards and forms.
    def run(wave_s: float) -> ETRun:
        r = ETRun(RunConfig(shape="disc", seed=213, max_time_s=14400,
                            et=ETParams(wave_s=wave_s, **SESSION_47_FORMATION)),
                  sim_params=NATIVE_MATHS)
        r.run()
        return r

    assert not run(0.0).summary()["formed"]
    with_wave = run(1200.0)
    summary = with_wave.summary()
    assert summary["formed"], summary["states"]
    assert summary["jaccard"] == 1.0
    placed = with_wave.controller.states >= State.INACTIVE
    assert duplicate_tags(with_wave.controller.tags, placed) == []
    assert min_pair_distance(with_wave.world.pos, with_wave.world.present) > 2 * 16.5 - 1.0


def test_the_wave_is_on_by_default_but_not_for_thin_or_holed_shapes() -> None:
    on = {shape: ETRun(RunConfig(shape=shape)).controller.ci[C_WAVE] > 0
          for shape in ("disc", "starfish", "dumbbell", "plus", "T", "H", "triangle", "O")}
    assert on == {"disc": True, "starfish": True, "dumbbell": True, "plus": True,
                  "T": False, "H": False, "triangle": False, "O": False}
    no_wave = ETRun(RunConfig(shape="disc", et=ETParams(wave_s=0.0)))
    assert no_wave.controller.ci[C_WAVE] == 0
