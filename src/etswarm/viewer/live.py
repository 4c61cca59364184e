"""The protocol the live viewer drives: anything that advances and shows a swarm.

The ET runner, the plain random-walk simulator and a replayed recording each implement
:class:`LiveRun`; :func:`etswarm.viewer.window.run_viewer` knows nothing else about them.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from etswarm.viewer.scene import Scene

Point = tuple[float, float]


@runtime_checkable
class LiveRun(Protocol):
    """A running (or replayed) swarm the viewer can step, show, inspect and damage.

    Attributes:
        finished: True when advancing has no further effect (end of run or recording).
        ticks_per_second: simulated control ticks per simulated second (31 for Kilobots).
    """

    ticks_per_second: int

    @property
    def finished(self) -> bool:
        """True when advancing has no further effect."""
        ...

    def advance(self, ticks: int) -> None:
        """Run ``ticks`` more control ticks (fewer when the run finishes first)."""
        ...

    def scene(self) -> Scene:
        """A drawable snapshot of now."""
        ...

    def robot_info(self, i: int) -> dict[str, object]:
        """What to show about robot index ``i``, as ``{label: value}`` in display order.

        A value that is a list of dicts (e.g. ``"neighbours"``) is shown as a table with
        the dicts' keys as columns; any other value is shown with ``str``.
        """
        ...

    def damage_split(self, p0: Point, p1: Point) -> None:
        """Cut the swarm along the line p0 -> p1 (mm) and move one side out of range."""
        ...

    def damage_remove_rect(self, p0: Point, p1: Point) -> None:
        """Remove every robot inside the axis-aligned rectangle with corners p0, p1 (mm)."""
        ...

    def damage_kill(self, ids: list[int]) -> None:
        """Kill robots ``ids`` (indices): they stop and fall silent but stay as obstacles."""
        ...
