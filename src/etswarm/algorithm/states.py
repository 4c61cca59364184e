"""The eight ET robot states (paper, Table 1) and their numeric codes.

The code of a robot's state is what the ET controller writes to ``World.led``; the
renderer, the recorder and the measures read it from there.
"""

from __future__ import annotations

from enum import IntEnum


class State(IntEnum):
    """ET state codes (uint8 in arrays)."""

    QUEUED = 0
    SEARCH = 1
    INACTIVE = 2
    ACTIVE = 3
    QUASI = 4
    STABLE = 5
    DANGER = 6
    LEADER = 7


#: Display names, indexed by code.
STATE_NAMES: tuple[str, ...] = tuple(s.name.capitalize() for s in State)

#: States in which a robot may hold a lattice tag: every robot in Inactive to Stable does;
#: one in Danger or Leader does if it held one when the election reached it
#: (``ETController.holds_site``).
PLACED_STATES: frozenset[State] = frozenset(
    {State.INACTIVE, State.ACTIVE, State.QUASI, State.STABLE, State.DANGER, State.LEADER}
)
