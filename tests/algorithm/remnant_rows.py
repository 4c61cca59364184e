"""One regeneration run's remnants as rows a test can compare."""

from __future__ import annotations

from etswarm.algorithm.run import ETRun, RunConfig


def remnant_rows(config: RunConfig) -> list[tuple[int, int | None, int, bool]]:
    """Run ``config`` to its end; per remnant of the summary, (robots, census count,
    target cells, formed), largest first. Asserts what no run may end with: a tag held
    twice, or a remnant with two Leaders."""
    summary = ETRun(config).run()
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1
    return sorted(
        ((c["robots"], c["census_count"], c["target_cells"], c["formed"])
         for c in summary["components"]), reverse=True
    )
