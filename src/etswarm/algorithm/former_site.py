"""Where a searcher released after damage stands: near the site it held before.

When a regenerated target leaves out a placed robot's site, the robot gives the site up
and waits Queued where it stands (``regeneration.adopt_target``). It still knows its old tag
(``R_FORMER_X``, ``R_FORMER_Y``), in the lattice frame of the new target, since the
Leader lays the new shape over the same tags. When the robot is released it starts its
odometry there (``homing.reset_odometry``), so it knows roughly how far it has gone since.

That settles what distances alone cannot. Two placed robots on adjacent sites, each read
at d, put a robot on one of their two common neighbour sites; which one, a searcher
judges from the side it came round the pair on (``localise.find_site``). A searcher
released right beside the pair came round nothing: traced on `T` `kill random=0.1` seed
64 (session 55), robots 21 and 27 were left out on the crossbar's lower row, released
where they stood, and within 100 s took the sites above the row's upper neighbours, 69
mm away across the pair, so the crossbar's right half grew on as a mirror image of the
lattice and the shape could not close.

So while its odometric path is shorter than ``FORMER_PATH_MM`` a searcher takes no site
whose position lies farther from its former site's than its odometric distance from
where it started plus ``ETParams.former_site_slack_mm`` (the robot's offset from its
site, the window a capture allows, odometry's error and shoves it missed).
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.homing import ODO_PER_MM
from etswarm.algorithm.kernel_util import lattice_distance
from etswarm.algorithm.memory import (
    NO_SITE,
    R_FORMER_X,
    R_FORMER_Y,
    R_ODO_PATH,
    R_ODO_X,
    R_ODO_Y,
)
from etswarm.algorithm.params import F_FORMER_SLACK, F_SPACING

#: Beyond this odometric path (mm) the estimate has drifted too far to say anything:
#: a tenth of it in heading and speed errors is already a site's spacing.
FORMER_PATH_MM = 400.0
#: ``former_reach``'s answer when the test does not apply (mm).
ANY_REACH = 1e18


@njit(inline="always")
def note_former_site(i, ri, x, y):  # type: ignore[no-untyped-def]
    """Robot i gives up site (x, y) and waits where it stands (``NO_SITE``: it held none,
    or it is not where it held one)."""
    ri[i, R_FORMER_X] = x
    ri[i, R_FORMER_Y] = y


@njit(inline="always")
def former_reach(i, ri, cf):  # type: ignore[no-untyped-def]
    """How far (mm) from its former site's position a site searcher i takes may lie:
    its odometric distance from where it started searching plus the slack, or
    ``ANY_REACH`` when it has no former site, its path is too long to trust or the test
    is off."""
    if cf[F_FORMER_SLACK] <= 0.0 or ri[i, R_FORMER_X] == NO_SITE:
        return ANY_REACH
    if ri[i, R_ODO_PATH] > FORMER_PATH_MM * ODO_PER_MM:
        return ANY_REACH
    gone = math.sqrt(float(ri[i, R_ODO_X]) ** 2 + float(ri[i, R_ODO_Y]) ** 2) / ODO_PER_MM
    return gone + cf[F_FORMER_SLACK]


@njit(inline="always")
def out_of_reach(i, ri, cx, cy, reach, cf):  # type: ignore[no-untyped-def]
    """Site (cx, cy) lies farther than ``reach`` (mm, ``former_reach``) from the position
    of searcher i's former site."""
    if reach >= ANY_REACH:
        return False
    spacings = lattice_distance(cx, cy, ri[i, R_FORMER_X], ri[i, R_FORMER_Y])
    return cf[F_SPACING] * spacings > reach
