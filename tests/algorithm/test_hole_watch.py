"""The hole's edge watches for searchers inside the hole, and a searcher does not wall the
hole off while one is seen there (``hole_watch``)."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.hole_watch import (
    MAX_AGE_S,
    encode_watch,
    file_watch,
    knows_sighting,
    note_sighting,
    sends_watch,
    watch_blocks,
)
from etswarm.algorithm.memory import (
    R_EPOCH,
    R_TAG_X,
    R_TAG_Y,
    R_WATCH_ID0,
    R_WATCH_ID1,
    R_WATCH_T0,
    R_WATCH_T1,
    allocate,
)
from etswarm.algorithm.messages import EPOCH_SHIFT, KIND_MASK, MSG_WATCH, get_u16
from etswarm.algorithm.params import C_HOLE_WATCH, ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.site_memory import walls_a_hole

from .test_site_memory import ORIGIN, memory_of, ring, ring_gene

TPS = 31


def sightings(ri: np.ndarray, i: int) -> dict[int, int]:
    """Robot i's kept sightings: searcher ID -> tick."""
    kept = {}
    for f in range(2):
        sid = int(ri[i, R_WATCH_ID0 + 2 * f])
        if sid >= 0:
            kept[sid] = int(ri[i, R_WATCH_T0 + 2 * f])
    return kept


def test_two_sightings_are_kept_the_newest_per_searcher() -> None:
    ri, _, _ = allocate(1)
    assert sightings(ri, 0) == {}
    note_sighting(0, 7, 100, ri)
    note_sighting(0, 9, 120, ri)
    note_sighting(0, 7, 90, ri)  # older news of a searcher kept already: ignored
    assert sightings(ri, 0) == {7: 100, 9: 120}
    note_sighting(0, 7, 130, ri)
    assert sightings(ri, 0) == {7: 130, 9: 120}
    note_sighting(0, 4, 125, ri)  # a third searcher takes the older field
    assert sightings(ri, 0) == {7: 130, 4: 125}
    note_sighting(0, 5, 110, ri)  # older than both: dropped
    assert sightings(ri, 0) == {7: 130, 4: 125}


def test_a_sighting_goes_on_one_second_older_and_of_the_same_epoch_only() -> None:
    ri, _, _ = allocate(3)
    ci, _ = ETParams().pack(TPS, 0, 0)
    tick = 100 * TPS
    ri[:, R_EPOCH] = 2
    note_sighting(0, 2, tick - 5 * TPS, ri)  # robot 2 was in the hole 5 s ago
    note_sighting(0, 300, tick - 3 * TPS - 4, ri)
    out_type = np.zeros(3, dtype=np.uint8)
    out_data = np.zeros((3, 9), dtype=np.uint8)
    encode_watch(0, tick, ri, ci, out_type, out_data)
    assert out_type[0] & KIND_MASK == MSG_WATCH
    assert out_type[0] >> EPOCH_SHIFT == 2
    sent = {get_u16(out_data[0], 2 + 3 * f): int(out_data[0, 4 + 3 * f]) for f in range(2)}
    assert sent == {2: 5, 300: 3}  # whole seconds, rounded down
    in_type = np.zeros((3, 1), dtype=np.uint8)
    in_data = np.zeros((3, 1, 9), dtype=np.uint8)
    for receiver in (1, 2):
        in_type[receiver, 0] = out_type[0]
        in_data[receiver, 0] = out_data[0]
    file_watch(1, 0, tick, ri, in_type, in_data, ci)
    assert sightings(ri, 1) == {2: tick - 6 * TPS, 300: tick - 4 * TPS}
    # Robot 2 does not take news of itself; a robot of another epoch takes nothing.
    file_watch(2, 0, tick, ri, in_type, in_data, ci)
    assert sightings(ri, 2) == {300: tick - 4 * TPS}
    ri[1, R_WATCH_ID0 : R_WATCH_T1 + 1] = [-1, -(1 << 40), -1, -(1 << 40)]
    ri[1, R_EPOCH] = 3
    file_watch(1, 0, tick, ri, in_type, in_data, ci)
    assert sightings(ri, 1) == {}


def test_an_empty_or_stale_field_is_sent_as_none() -> None:
    ri, _, _ = allocate(2)
    ci, _ = ETParams().pack(TPS, 0, 0)
    tick = 1000 * TPS
    note_sighting(0, 1, tick - 600 * TPS, ri)  # older than a message can say
    out_type = np.zeros(2, dtype=np.uint8)
    out_data = np.zeros((2, 9), dtype=np.uint8)
    encode_watch(0, tick, ri, ci, out_type, out_data)
    assert out_data[0, 4] == MAX_AGE_S and out_data[0, 7] == MAX_AGE_S
    in_type = out_type[:, None].copy()
    in_data = out_data[:, None, :].copy()
    in_type[1], in_data[1] = in_type[0], in_data[0]
    file_watch(1, 0, tick, ri, in_type, in_data, ci)
    assert sightings(ri, 1) == {}


def test_sightings_count_for_hole_watch_s() -> None:
    ri, _, _ = allocate(1)
    ci, _ = ETParams(hole_watch_s=60.0).pack(TPS, 0, 0)
    assert ci[C_HOLE_WATCH] == 60 * TPS
    note_sighting(0, 5, 0, ri)
    assert knows_sighting(0, 59 * TPS, ri, ci, -1)
    assert not knows_sighting(0, 59 * TPS, ri, ci, 5)  # only itself seen there
    assert not knows_sighting(0, 61 * TPS, ri, ci, -1)
    off, _ = ETParams(hole_watch_s=0.0).pack(TPS, 0, 0)
    assert off[C_HOLE_WATCH] == 0
    assert not knows_sighting(0, 1, ri, off, -1)
    no_flag, _ = ETParams(hole_flag="off").pack(TPS, 0, 0)
    assert no_flag[C_HOLE_WATCH] == 0  # without the hole flag no robot knows a hole


def o_memory(free: list[tuple[int, int]]) -> np.ndarray:
    """The ``ring_gene`` O (ring 3 to 5 round a hole of radius 2) remembered held but
    for ``free``."""
    shape_sites = [s for r in (3, 4, 5) for s in ring(r)]
    return memory_of([s for s in shape_sites if s not in free])


def test_the_last_site_of_the_holes_edge_walls_the_hole_off() -> None:
    gene, _ = ring_gene()
    ci, _ = ETParams().pack(TPS, gene_x0=ORIGIN, gene_y0=ORIGIN)
    window = o_memory([(3, 1)])
    before = window.copy()
    assert walls_a_hole(3, 1, window, ORIGIN, ORIGIN, gene, ci)
    assert np.array_equal(window, before)
    # With a second way into the hole left, (3, 1) may go: the hole stays open.
    window = o_memory([(3, 1), (-3, -1), (-4, -1), (-5, -1)])
    assert not walls_a_hole(3, 1, window, ORIGIN, ORIGIN, gene, ci)
    # A site off the hole's edge, or one held already, walls nothing off itself.
    assert not walls_a_hole(5, 1, o_memory([(3, 1), (5, 1)]), ORIGIN, ORIGIN, gene, ci)
    assert not walls_a_hole(3, 1, o_memory([]), ORIGIN, ORIGIN, gene, ci)


def test_a_searcher_keeps_the_hole_open_while_another_is_seen_inside() -> None:
    gene, _ = ring_gene()
    ci, _ = ETParams().pack(TPS, gene_x0=ORIGIN, gene_y0=ORIGIN)
    ri, _, _ = allocate(2)
    window = o_memory([(3, 1)])
    tick = 10 * TPS

    def blocks(i: int) -> bool:
        return bool(watch_blocks(i, tick, 3, 1, ri, window, ORIGIN, ORIGIN, gene, ci))

    assert not blocks(0)  # no sighting: the ring closes
    note_sighting(0, 1, tick - TPS, ri)
    assert blocks(0)  # robot 1 was in the hole a second ago
    note_sighting(1, 1, tick - TPS, ri)
    assert not blocks(1)  # robot 1 itself, the only one seen inside, takes the last site


def test_only_an_edge_robot_with_fresh_news_sends_a_watch() -> None:
    gene, _ = ring_gene()
    ci, _ = ETParams().pack(TPS, gene_x0=ORIGIN, gene_y0=ORIGIN)
    ri, _, _ = allocate(2)
    ri[0, R_TAG_X], ri[0, R_TAG_Y] = 3, 0  # on the hole's edge
    ri[1, R_TAG_X], ri[1, R_TAG_Y] = 5, 0  # on the outer edge
    for i in (0, 1):
        note_sighting(i, 9, 0, ri)
    periods = range(0, 60 * TPS - 15, 15)
    sent = [t // 15 for t in periods if sends_watch(0, t, ri, gene, ci)]
    assert sent and all(p % 3 == 2 for p in sent)
    assert len(sent) == len([t for t in periods if (t // 15) % 3 == 2])
    assert not any(sends_watch(1, t, ri, gene, ci) for t in periods)
    assert not sends_watch(0, 61 * TPS + 30, ri, gene, ci)  # the news is stale
    assert ri[0, R_WATCH_ID1] == -1 and ri[0, R_WATCH_T1] < 0


def test_the_watch_runs_only_for_targets_with_a_hole() -> None:
    plain = ETRun(RunConfig(shape="T", seed=0, max_time_s=1.0)).controller
    assert plain.ci[C_HOLE_WATCH] == 0 and plain.hole_watch_ticks == 60 * plain.ticks_per_s
    ring_shape = ETRun(RunConfig(shape="O", seed=0, max_time_s=1.0)).controller
    assert ring_shape.ci[C_HOLE_WATCH] == 60 * ring_shape.ticks_per_s
    off = ETRun(RunConfig(shape="O", seed=0, max_time_s=1.0, et=ETParams(hole_watch_s=0)))
    assert off.controller.ci[C_HOLE_WATCH] == 0
