"""Growth in waves from the seeds (``wave``): hop counts, the capture test, and a disc
whose rim no longer closes round free sites."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.kernel_util import hex_distance
from etswarm.algorithm.layout import plan_layout
from etswarm.algorithm.memory import HOLE_FLAG, R_NN
from etswarm.algorithm.params import C_RIM_WAVE, C_WAVE, ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.algorithm.wave import HOPS_SHIFT, behind_wave, nn_of, rim_hops, seed_hops
from etswarm.measures.formation import duplicate_tags, min_pair_distance
from etswarm.shapes.lattice import hole_edge_cells, neighbour_counts

from .test_site_memory import ORIGIN, SIZE, hexagon_gene, memory_of, ring
from .traced import NATIVE_MATHS, SESSION_47_FORMATION, SESSION_68_QUEUE

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


def test_the_wave_is_on_by_default_but_not_for_thin_shapes_and_from_the_rim_for_holed_ones(
) -> None:
    controllers = {shape: ETRun(RunConfig(shape=shape)).controller
                   for shape in ("disc", "starfish", "dumbbell", "plus", "T", "H", "triangle", "O")}
    on = {shape: ctl.ci[C_WAVE] > 0 for shape, ctl in controllers.items()}
    assert on == {"disc": True, "starfish": True, "dumbbell": True, "plus": True,
                  "T": False, "H": False, "triangle": False, "O": True}
    rim = {shape for shape, ctl in controllers.items() if ctl.ci[C_RIM_WAVE] > 0}
    assert rim == {"O"}
    no_wave = ETRun(RunConfig(shape="disc", et=ETParams(wave_s=0.0)))
    assert no_wave.controller.ci[C_WAVE] == 0


def ring_of_three_rows() -> np.ndarray:
    """(P, 2) tags one to three steps from (0, 0): a ring three rows thick round a hole of
    one site."""
    return np.array([s for r in (1, 2, 3) for s in ring(r)])


def test_rim_hops_count_steps_from_the_edge_of_the_hole() -> None:
    cells = ring_of_three_rows()
    assert {tuple(t) for t in hole_edge_cells(cells).tolist()} == set(ring(1))
    assert len(hole_edge_cells(hexagon_cells(3))) == 0  # no hole, no edge
    hops = rim_hops(cells)
    assert hops.tolist() == [hex_distance(x, y) - 1 for x, y in cells.tolist()]
    # The edge of the hole is where the count starts, whatever the shape around it:
    # the library's O has rows of three and of two, and every cell counts 0 to 2.
    o_cells = ETRun(RunConfig(shape="O")).target
    assert sorted(set(rim_hops(o_cells).tolist())) == [0, 1, 2]


def ring_gene_with_rim_hops() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``ring_of_three_rows`` as a gene (its hole flagged), NN and rim hops packed as
    ``ETController.seed`` packs them, and constants with the rim wave on."""
    cells = ring_of_three_rows()
    gene = np.zeros((SIZE, SIZE), dtype=np.uint8)
    gene[cells[:, 0] - ORIGIN, cells[:, 1] - ORIGIN] = 1
    gene[-ORIGIN, -ORIGIN] = HOLE_FLAG
    packed = np.zeros(gene.shape, dtype=np.int16)
    packed[cells[:, 0] - ORIGIN, cells[:, 1] - ORIGIN] = neighbour_counts(cells) + (
        rim_hops(cells) << HOPS_SHIFT
    )
    ci, _ = ETParams(rim_wave_s=1200.0).pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    return gene, packed, ci


def test_a_ring_site_waits_only_for_a_nearer_site_that_could_be_located() -> None:
    gene, packed, ci = ring_gene_with_rim_hops()
    assert ci[C_RIM_WAVE] == 1200 * 31
    # (2, 0), in the middle row, has one neighbour on the hole's edge: (1, 0). Held (1, 1)
    # and (2, 1) locate (1, 0): a searcher should take it first.
    locating = [(1, 1), (2, 1)]
    assert behind_wave(2, 0, gene, packed, ci, memory_of(locating), ORIGIN, ORIGIN)
    assert not behind_wave(2, 0, gene, packed, ci, memory_of([*locating, (1, 0)]),
                           ORIGIN, ORIGIN)
    # With (1, 1) alone, (1, 0) cannot be located until a site beside it is held, which
    # may be (2, 0) itself: the rim wave lets (2, 0) go, the wave from the seeds would not.
    alone = memory_of([(1, 1)])
    assert not behind_wave(2, 0, gene, packed, ci, alone, ORIGIN, ORIGIN)
    plain = ci.copy()
    plain[C_RIM_WAVE] = 0
    assert behind_wave(2, 0, gene, packed, plain, alone, ORIGIN, ORIGIN)
    # A site on the hole's edge waits for nothing.
    assert not behind_wave(1, 0, gene, packed, ci, memory_of([]), ORIGIN, ORIGIN)


def test_the_rim_wave_runs_only_for_targets_with_a_hole() -> None:
    et = ETParams(rim_wave_s=600.0)
    ring_run = ETRun(RunConfig(shape="O", et=et)).controller
    assert ring_run.ci[C_WAVE] == ring_run.ci[C_RIM_WAVE] == 600 * ring_run.ticks_per_s
    cells = ring_run.slot_cells[0]
    packed = ring_run.gene_nn[0, cells[:, 0] - ring_run.x0, cells[:, 1] - ring_run.y0]
    assert np.array_equal(packed >> HOPS_SHIFT, rim_hops(cells))
    assert np.array_equal(nn_of(packed), neighbour_counts(cells))
    disc = ETRun(RunConfig(shape="disc", et=et)).controller
    assert disc.ci[C_RIM_WAVE] == 0 and disc.ci[C_WAVE] == 1200 * disc.ticks_per_s
    off = ETRun(RunConfig(shape="O", et=ETParams(rim_wave_s=0.0))).controller
    assert off.ci[C_WAVE] == off.ci[C_RIM_WAVE] == 0


def test_o_closes_its_ring_from_the_hole_out_where_a_way_across_it_stalled() -> None:
    # O seed 9 without the rim wave ends 4 h on a way of three free sites across the ring,
    # (2, 3), (3, 4) and (4, 5): each capture would shut a free site off from the searchers.
    # With it the ring's inner rows lead, its last free sites open to the outside, and it
    # forms (session 65; session 68's rules for such a way are off here).
    def run(rim_wave_s: float) -> ETRun:
        r = ETRun(RunConfig(shape="O", seed=9, max_time_s=14400,
                            et=ETParams(rim_wave_s=rim_wave_s, inside_bit="off",
                                        way_end="off", way_plunge="off",
                                        **SESSION_68_QUEUE)))
        r.run()
        return r

    stalled = run(0.0).summary()
    assert not stalled["formed"]
    assert sorted(stalled["components"][0]["free_tags"]) == [[2, 3], [3, 4], [4, 5]]
    with_rim = run(1200.0)
    summary = with_rim.summary()
    assert summary["formed"], summary["components"]
    assert summary["jaccard"] == 1.0 and summary["duplicate_tags"] == []
    assert min_pair_distance(with_rim.world.pos, with_rim.world.present) > 2 * 16.5 - 1.0


def test_no_wave_on_the_command_line_turns_the_rim_wave_off_too(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    from click.testing import CliRunner

    from etswarm.cli import run_command, run_outputs

    seen = []
    monkeypatch.setattr(run_outputs, "drive",
                        lambda et_run, **_: seen.append(et_run.controller.ci.copy()) or {})
    for flag in ("--wave", "--no-wave"):
        result = CliRunner().invoke(run_command.run, ["O", "--max-time", "1", "--json", flag])
        assert result.exit_code == 0, result.output
    on, off = seen
    assert on[C_RIM_WAVE] > 0 and on[C_WAVE] == on[C_RIM_WAVE]
    assert off[C_RIM_WAVE] == 0 and off[C_WAVE] == 0
