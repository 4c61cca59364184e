"""Links torn apart: holders of neighbouring tags that stand far apart."""

from __future__ import annotations

import numpy as np

from etswarm.measures.formation import STRETCHED_FACTOR, stretched_links
from etswarm.shapes.lattice import are_adjacent, tags_to_xy

D = 40.0
TAGS = np.array([(x, y) for x in range(-2, 3) for y in range(-2, 3)], dtype=np.int64)
HOLDS = np.ones(len(TAGS), dtype=bool)


def adjacent_pairs(tags: np.ndarray) -> int:
    """Neighbouring pairs among ``tags`` (K, 2), counted the slow way."""
    rows = [tuple(int(v) for v in t) for t in tags]
    return sum(are_adjacent(a, b) for k, a in enumerate(rows) for b in rows[k + 1:])


def test_a_sound_lattice_has_none_and_a_stretched_one_has_every_link() -> None:
    pos = tags_to_xy(TAGS, D) + np.array([300.0, -80.0])
    assert stretched_links(pos, TAGS, HOLDS, D) == 0
    # every distance grows by 1.6x: each of the lattice's links is now too long
    assert stretched_links(1.6 * pos, TAGS, HOLDS, D) == adjacent_pairs(TAGS) > 0


def test_a_row_moved_away_tears_exactly_its_links_to_the_rest() -> None:
    pos = tags_to_xy(TAGS, D)
    top = TAGS[:, 1] == 2
    pos[top] += (0.0, 30.0)  # 34.6 + 30 mm from the row below: past 1.5 d
    below = TAGS[TAGS[:, 1] == 1]
    torn = sum(
        are_adjacent(tuple(a), tuple(b)) for a in TAGS[top].tolist() for b in below.tolist()
    )
    assert torn > 0
    assert stretched_links(pos, TAGS, HOLDS, D) == torn


def test_only_holders_count_and_a_lone_one_has_no_links() -> None:
    pos = tags_to_xy(TAGS, D)
    pos[0] += (0.0, -200.0)  # far from every neighbour ...
    holds = HOLDS.copy()
    holds[0] = False  # ... but it holds nothing
    assert stretched_links(pos, TAGS, holds, D) == 0
    one = np.zeros(len(TAGS), dtype=bool)
    one[3] = True
    assert stretched_links(pos, TAGS, one, D) == 0


def test_the_factor_is_a_strict_bound() -> None:
    tags = np.array([(0, 0), (1, 0)], dtype=np.int64)
    both = np.ones(2, dtype=bool)
    at_bound = np.array([(0.0, 0.0), (STRETCHED_FACTOR * D, 0.0)])
    assert stretched_links(at_bound, tags, both, D) == 0
    beyond = at_bound + np.array([(0.0, 0.0), (0.5, 0.0)])
    assert stretched_links(beyond, tags, both, D) == 1


def test_the_run_summary_names_torn_groups_only() -> None:
    from etswarm.cli.run_outputs import torn_lines

    comps = [
        {"stretched_links": 0, "placement_error_mm": 4.2},
        {"stretched_links": 3, "placement_error_mm": 17.5},
        {"placement_error_mm": None},  # a summary written before the measure existed
        {"stretched_links": 1, "placement_error_mm": 9.0},
    ]
    assert torn_lines(comps) == [
        "group 1: 3 links between robots of neighbouring sites stretched past 1.5 spacings "
        "(placement error 17.5 mm)",
        "group 3: 1 link between robots of neighbouring sites stretched past 1.5 spacings "
        "(placement error 9.0 mm)",
    ]
