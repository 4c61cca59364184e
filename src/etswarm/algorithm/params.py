"""Parameters of the ET controller, in user units, and their packing for numba.

All times are simulated seconds (converted to ticks at 31 ticks/s); all lengths are mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from etswarm.errors import EtswarmError

# Column indices of the packed integer constants (``ci``) and float constants (``cf``).
C_TICKS_NB_FRESH = 0  # a neighbour counts if heard within this many ticks
C_TICKS_DANGER = 1  # Stable -> Danger after the count stays below NN this long
C_TICKS_QUASI = 2  # Quasi back-off time
C_TICKS_RELEASE = 3  # minimum interval between two releases from the repository
C_TICKS_QUIET = 4  # a Queued robot must be the lowest ID this long before leaving
C_TICKS_SETTLE = 5  # a searching robot stands still this long before taking a site
C_TICKS_COOLDOWN = 6  # after a rejected site, ignore candidates this long
C_TICKS_YIELD_MAX = 7  # give up yielding to another searcher after this long
C_TICKS_MOVE_FRESH = 8  # distance readings used for steering must be this recent
C_GENE_X0 = 9  # tag X of gene grid column 0
C_GENE_Y0 = 10  # tag Y of gene grid row 0
C_EVAL_EVERY = 11  # placed robots re-evaluate their state every this many ticks
C_TICKS_CLEAR = 12  # a Queued robot leaves only after hearing no searcher this long
C_TICKS_REGEN_QUIET = 13  # election/census quiet time before a robot declares itself Leader
C_CENSUS_WALK = 14  # 1: the Leader counts by walking round the remnant; 0: spanning tree
C_TICKS_WALK_MAX = 15  # the census walk gives up after this long
C_ORBIT_BOUNCE = 16  # 1: a searcher turns back where the shape ends and the repository begins
C_CREEP = 17  # 1: a searcher near a free site moves stop-and-go
C_SECOND_RING = 18  # 1: two references sqrt(3) d apart also locate a site (between them)
C_HOLE_MEMORY = 19  # 1: the hole test uses the searcher's memory of held sites
C_POCKET = 20  # POCKET_*: when a searcher long at the shape may take a site from all round
C_RELEASE_FAR = 21  # 1: a regenerated remnant releases its Queued robots farthest first
C_QUEUE_STRIDE = 22  # 1: along the repository a searcher near its aim drives straight on
C_SILENT_SITES = 23  # 1: electing robots note and flood the sites that fell silent
C_LOST_BEACON = 24  # 1: a lost searcher follows a searcher that hears a stationary robot
C_SETTLE_RETRIES = 25  # a settled searcher that cannot confirm its site stays this many times
C_TICKS_HOLD = 26  # a Queued robot that hears a yielding searcher holds releases this long
C_LOST_YIELD = 27  # 1: a lost searcher yields to lower-ID searchers as on the edge
C_REGROW_RETRIES = 28  # settle retries of a searcher working for a regenerated target
C_TICKS_HOVER = 29  # after damage, a searcher near one free site this long centres its window on d
C_STILL_READINGS = 30  # a still robot averages up to this many readings of a still neighbour
C_TICKS_CROWDED = 31  # after damage, a Queued robot crowded by searchers this long leaves anyway
C_FILL_LOOKAHEAD = 32  # 1: a capture must not leave the shape unfinishable (``fill_order``)
C_GOSSIP_EVERY = 33  # placed robots send a chunk of their held-site memory every this many periods
C_TICKS_RANK_WAIT = 34  # a Queued robot waits for its queue rank at most this long (0: off)
C_EXTENT = 35  # 1: electing robots flood the remnant's extent for the scaled shape's placement
C_OFFSETS = 36  # 1: placed robots estimate and send their offset from their site (``offsets``)
C_LOST_HOMING = 37  # LOST_HOMING_* code: how a lost searcher looks for the group (``homing``)
C_REPORT_PATIENCE = 38  # 1: a Stable robot waits longer for neighbours it only knew by report
C_PINCH_REFUSALS = 39  # a searcher refuses at most this many sites that would pinch a free one
C_REGROW_PINCH_REFUSALS = 40  # the same while it searches for a regenerated target
C_REGROW_OFFSETS = 41  # REGROW_OFFSETS_*: what a robot kept on its site does with its offset
C_AVOID_FOREIGN = 42  # 1: searchers ignore placed robots off their target (obstacles only)
C_MERGE = 43  # 1: placed robots touching another remnant's shape start a joint election
C_FALSE_ALARM = 44  # 1: an election whose census keeps the current target is a false alarm
C_TICKS_REMEMBERED = 45  # an Active robot missing only sites remembered held this long excuses them
C_REGROW_UNPINCH = 46  # a kept robot this many mm into a free site of the new target leaves it
C_RIGHT_OF_WAY = 47  # a searcher keeps clear of lower-ID searchers only: RIGHT_OF_WAY_*
C_TICKS_CLEAR_FIRST = 48  # C_TICKS_CLEAR in the first formation (a thin shape's own)
C_TICKS_REJOIN = 49  # a Stable robot cut off this long, Stable only by excused sites, searches
C_HOLE_WATCH = 50  # ticks a searcher seen in a hole keeps others from walling it off (0: off)
C_TICKS_PER_S = 51  # control ticks per simulated second
C_WAVE = 52  # ticks at the shape a searcher keeps to the wave from the seeds (0: off)
C_TICKS_PLUNGE = 53  # after damage, a searcher that cannot take its site plunges this long (0: off)
C_FIRST_PLUNGE = 54  # first formation: ticks at the shape before a searcher may plunge (0: never)
C_TICKS_LOST_ESCAPE = 55  # a lost searcher blocked by a foreign robot follows it this long
C_SIGNED_FOREIGN = 56  # 1: a robot that gossips another target of its epoch is foreign
C_OFFSET_LEAVE = 57  # an Active robot whose refined offset reaches this (mm) leaves its site
C_MOUTH_PLUNGE = 58  # 1: after damage, a searcher long at the shape in a notch's mouth plunges
C_TICKS_FROM_RETURN = 59  # a switch back to the robot a searcher came from needs this much moving
C_MERGE_PARKED = 60  # 1: a placed robot counts a parked robot beside it as contact (``merge``)
C_PARKED_OBSTACLE = 61  # 1: a searcher takes a parked robot for an obstacle, not the repository
C_LONE_KEPT = 62  # 1: a kept robot with no kept neighbour site in the new target searches again
C_CAME_ORDER = 63  # which of a pair a searcher passed first, by the order it met them (mode)
C_SIBLING_TARGET = 64  # which announcements of its epoch an electing robot ignores (mode)
C_STATUS_SIG = 65  # a status carries its target's signature (4 bits, ``messages``): mode
C_RIM_WAVE = 66  # ticks at the shape a searcher keeps to the rim wave round a hole (0: off)
C_INSIDE_BIT = 67  # 1: a searcher that places itself in a hole says so in its status
C_HOLE_TAKER = 68  # 1: a hole's last free edge site may be walled in with one searcher inside
C_WAY_END = 69  # 1: a ring's last way may be closed at the hole's end, leaving a notch
C_WAY_PLUNGE = 70  # 1: in a ring's first formation a searcher in a notch's mouth plunges
C_TICKS_GAP = 71  # a searcher at the dead end of a broken queue leaps after this long (0: off)
C_TICKS_LEAP = 72  # ... and gives the leap up after this long
C_TICKS_LATE_PLUNGE = 73  # first formation: plunge in a mouth after this long at the shape (0: off)
N_CI = 74

#: Values of ``ci[C_RIGHT_OF_WAY]``: never, always, or in the first formation alone (a
#: thin shape's, ``thin_right_of_way``).
RIGHT_OF_WAY_NEVER = 0
RIGHT_OF_WAY_ALWAYS = 1
RIGHT_OF_WAY_FIRST_GROWTH = 2

F_SPACING = 0  # lattice spacing d
F_PAIR_TOL = 1  # two references within this of d trigger a site candidate
F_CONSIST_TOL = 2  # every heard placed robot must match the candidate within this
F_YIELD_DIST = 3  # yield to a lower-ID searcher nearer than this
F_FOLLOW_OFFSET = 4  # edge-following aims at d + this (clearance for the bodies)
F_CLOSING = 5  # assumed worst-case closing speed between readings, mm per tick
F_CLEARANCE = 6  # a searcher turns away from any other robot nearer than this
F_BALANCE_TOL = 7  # the two references' distances may differ by at most this
F_WALK_COLLECT = 8  # the census walker records the tags of robots heard nearer than this
F_PAIR_AIM = 9  # the pair window is centred this far from d (negative: nearer)
F_WIDEN_MAX = 10  # a searcher long at the shape widens its tolerances up to this factor
F_AIM_RELAX = 11  # ticks at the shape over which the pair window's centre moves back to d
F_CONSIST_WIDEN = 12  # a widened pocket candidate's consistency tolerance grows up to this
F_SETTLE_SCALE = 13  # a settled searcher confirms its site with windows this many times wider
F_WIDEN_TICKS = 14  # ticks at the shape over which a searcher's tolerances widen to widen_max
F_DIVE = 15  # after damage, a searcher long at the shape edge-follows up to this much nearer (mm)
F_DIVE_FIRST = 16  # in the first formation, the same once a searcher has been widen_s at the shape
F_OFFSET_TRUST = 17  # share of a placed robot's offset a searcher's expected readings follow
# The robot's nominal motion, which its odometry assumes (``homing``).
F_ODO_STEP = 18  # forward travel per tick, mm
F_ODO_TURN = 19  # pivot per tick, rad
F_ODO_LEG = 20  # angle of the pivot legs from the heading, rad
F_ODO_RADIUS = 21  # body radius (legs on the rim), mm
F_CAPTURE_PINCH = 22  # a searcher takes no site from this far (mm) into a free neighbour site
F_REGROW_WIDEN_TICKS = 23  # F_WIDEN_TICKS while a searcher works for a regenerated target
F_TWO_WIDEN_TICKS = 24  # after this long at the shape a two-neighbour site gets the wide window
F_CAPTURE_MOUTH = 25  # no capture reading the robot across a free site nearer than this
F_REGROW_TWO_WIDEN_TICKS = 26  # F_TWO_WIDEN_TICKS while a searcher works for a regenerated target
F_CAPTURE_OFFSET = 27  # no capture from this far (mm) or more off the site's centre
F_REGROW_CAPTURE_OFFSET = 28  # F_CAPTURE_OFFSET while a searcher works for a regenerated target
F_PINCH_PATIENCE = 29  # ticks at the shape after which a searcher refuses no more pinching sites
F_PORTABLE_MATH = 30  # 1.0: odometry and homing use ``sim.fpmath`` (``SimParams.portable_math``)
F_FORMER_SLACK = 31  # a searcher near its former site: the slack (mm) on its odometric reach
F_MIRROR_MARGIN = 32  # mm: a third robot rules a mirror out only fitting the site this much better
F_REGROW_FOLD_SKIP = 33  # mm: after damage a robot this far from a site, off its mirror, is mute
F_REGROW_PLUNGE_AIM = 34  # mm: after damage a plunging searcher keeps this near placed robots
F_LATE_PLUNGE_AIM = 35  # mm: F_REGROW_PLUNGE_AIM for a first formation's late plunges
N_CF = 36

#: The DESIGN section 2 robot: 7 mm/s, 13 deg/s, legs at 125.5 deg, radius 16.5 mm.
NOMINAL_MOTION = (7.0, 13.0, 125.5, 16.5)

#: Census methods (``ETParams.census``): the paper's periphery walk, or a spanning tree.
CENSUS_METHODS = ("tree", "walk")
#: How searchers go round the group (``ETParams.orbit``): always clockwise (the paper), or
#: back and forth round the shape, turning back where it meets the repository.
ORBIT_MODES = ("bounce", "clockwise")
#: What a robot that keeps its site through a regeneration does with its offset
#: (``ETParams.regrowth_offsets``), in the order of their codes in ``ci``.
REGROWTH_OFFSETS = ("keep", "reset", "zero")
#: Where a Leader places the scaled shape (``ETParams.placement``).
PLACEMENTS = ("extent", "local")
#: What a searcher does with placed robots off its target (``ETParams.foreign_robots``).
FOREIGN_MODES = ("avoid", "follow")
#: Which seed triangle a Leader's placement may use (``ETParams.placement_seeds``).
PLACEMENT_SEEDS = ("leader", "any", "silent")
#: Whether a Leader's placement minds cells off the shape its remnant held
#: (``ETParams.placement_off_shape``).
PLACEMENT_OFF_SHAPE = ("any", "fewest", "weigh")
#: How a lost searcher looks for the group (``ETParams.lost_homing``), in the order of
#: their codes in ``ci``.
LOST_HOMING_MODES = ("off", "on", "ahead")
LOST_HOMING_ON = 1
LOST_HOMING_AHEAD = 2
#: What an election whose census keeps the current target does (``ETParams.false_alarm``).
FALSE_ALARM_MODES = ("resume", "regrow")
#: When a searcher long at the shape may take a site from the robots round it
#: (``ETParams.pocket``), in the order of their codes in ``ci``.
POCKET_MODES = ("off", "on", "regrowth", "located")
POCKET_ON = 1
POCKET_REGROWTH = 2
POCKET_LOCATED = 3
#: ``ETParams.came_order`` modes, in the order of their codes in ``ci`` (``met_order``).
CAME_ORDER_MODES = ("off", "on", "regrowth")
CAME_ORDER_ON = 1
CAME_ORDER_REGROWTH = 2
#: ``ETParams.sibling_target`` modes, in the order of their codes in ``ci``: which
#: announcements of the target it elects for an electing robot takes as its own.
SIBLING_TARGET_MODES = ("adopt", "ignore", "strict")
SIBLING_ADOPT = 0
SIBLING_STRICT = 2
#: ``ETParams.status_signature`` modes, in the order of their codes in ``ci``.
STATUS_SIGNATURE_MODES = ("off", "on", "placed")
STATUS_SIG_ON = 1
#: The allowed values of each ETParams field that takes one of a few names.
CHOICES: dict[str, tuple[str, ...]] = {
    "census": CENSUS_METHODS,
    "regrowth_offsets": REGROWTH_OFFSETS,
    "placement": PLACEMENTS,
    "placement_seeds": PLACEMENT_SEEDS,
    "placement_off_shape": PLACEMENT_OFF_SHAPE,
    "placement_turns": ("off", "on"),
    "foreign_robots": FOREIGN_MODES,
    "release_order": ("far", "id"),
    "orbit": ORBIT_MODES,
    "false_alarm": FALSE_ALARM_MODES,
    "lost_homing": LOST_HOMING_MODES,
    "pocket": POCKET_MODES,
    "came_order": CAME_ORDER_MODES,
    "sibling_target": SIBLING_TARGET_MODES,
    "status_signature": STATUS_SIGNATURE_MODES,
}


#: Parameters that may be zero (all others must be positive).
NON_NEGATIVE: frozenset[str] = frozenset(
    {
        "pair_aim_relax_s", "settle_retries", "regrowth_settle_retries", "release_hold_s",
        "regrowth_hover_s", "regrowth_crowded_s", "regrowth_dive_mm",
        "dive_mm", "held_gossip_every", "queue_rank_wait_s", "capture_pinch_mm",
        "pinch_patience_s", "thin_depth", "thin_settle_retries",
        "capture_pinch_refusals", "regrowth_pinch_refusals", "two_neighbour_widen_s",
        "regrowth_two_neighbour_widen_s", "capture_mouth_mm", "capture_offset_mm",
        "regrowth_capture_offset_mm", "remembered_neighbours_s", "regrowth_unpinch_mm",
        "isolated_rejoin_s", "hole_watch_s", "wave_s", "rim_wave_s", "regrowth_plunge_s",
        "first_plunge_after_s", "lost_escape_s", "offset_leave_mm", "former_site_slack_mm",
        "from_return_s", "mirror_margin_mm", "regrowth_fold_skip_mm", "repository_gap_s",
        "late_plunge_s",
    }
)
#: Parameters that may take any sign.
SIGNED = frozenset({"pair_aim_mm", "follow_offset_mm"})


@dataclass(frozen=True)
class ETParams:
    """Tunable constants of the ET controller (defaults suit DESIGN §2 robots)."""

    spacing_mm: float = 40.0
    neighbour_timeout_s: float = 2.5
    danger_timeout_s: float = 8.0
    quasi_s: float = 4.0
    release_interval_s: float = 30.0
    release_quiet_s: float = 4.0
    release_clear_s: float = 15.0
    settle_s: float = 1.5
    rejected_cooldown_s: float = 3.0
    yield_max_s: float = 30.0
    steer_fresh_s: float = 3.0
    pair_tol_mm: float = 4.0
    #: Offset of the pair window's centre from d. A searcher orbits at d from the nearest
    #: placed robot and enters the window from outside, so it tends to stop on the far
    #: side of a site; a negative offset moves the window in to meet it.
    pair_aim_mm: float = -2.0
    #: The window's centre moves back from ``pair_aim_mm`` to d over a searcher's first
    #: this many seconds at the shape; 0 keeps it at ``pair_aim_mm``. 600 forms thin
    #: shapes about twice as fast, compact ones less often (docs/algorithm.md).
    pair_aim_relax_s: float = 0.0
    #: A searcher at the shape for ``widen_s`` has widened its pair and balance tolerances
    #: to this factor (at pockets of three or more placed neighbours); 1 never widens.
    widen_max: float = 3.0
    #: ... over this long (simulated seconds at the shape), linearly. With 400 (and four
    #: pinch refusals) 758 of 780 first formations formed (13 shapes, seeds 30-89)
    #: against 753 with 1200 (and two), and median formation times fell by 5-25 %: the
    #: last sites of a shape are often only in reach of a widened window, and the last
    #: searcher went round for 20 min before it could take them (docs/algorithm.md).
    widen_s: float = 400.0
    #: ... and this long while it searches for a regenerated target (after damage): with
    #: 400 there too, 306 of 352 damage runs re-formed against 311 (18 cases, seeds 0-19),
    #: and one run held a tag twice.
    regrowth_widen_s: float = 1200.0
    consistency_tol_mm: float = 16.0
    #: A third placed robot whose reading is more than ``consistency_tol_mm`` off what the
    #: mirror site of a pair predicts rules that site out only when its reading also fits
    #: the candidate site better by at least this much (mm). Before (0), it ruled the mirror
    #: out by the tolerance alone, while the candidate may be off by the widened one: on
    #: dumbbell split y=mid seed 33 (session 57) the robot on (0, 0) read 54 mm where both
    #: sites predict 69-71 mm, so a searcher took the site on the far side of the pair, 78 mm
    #: from where it stood.
    mirror_margin_mm: float = 8.0
    #: After damage, a placed robot whose tag puts it more than this far (mm) from a pair's
    #: candidate site is out of radio range of it on the lattice: a searcher there hears it
    #: only where the lattice has folded. When its reading does not fit the pair's other
    #: site either (within ``consistency_tol_mm``), it is left out of the candidate's
    #: consistency check; one that fits the other site still vetoes. (In first formations
    #: every robot heard is checked: there the rule lost as many runs as it gained.) On ``H``
    #: ``split x=mid`` seed 106 the scaled H's two legs had bent towards each other, and
    #: robot (-1, 2) read 56 mm where the last free site (2, 2) predicts 120: no searcher
    #: took the site for 7 h. 0: every robot heard is checked (before session 66).
    regrowth_fold_skip_mm: float = 100.0
    #: At a pocket (see ``widen_max``) the consistency tolerance widens with the pair
    #: window, up to this factor: where the lattice has pinched a site's mouth narrower
    #: than a body, a searcher can only stop at the mouth, farther from the robot inside
    #: than the site is, and robots two steps away may read 20 mm nearer than 2 d where
    #: growth has compressed the lattice (starfish seed 12). 1 never widens it. 2 formed
    #: 346 of 390 first formations (13 shapes, seeds 0-29) against 336 with 1.
    consistency_widen_max: float = 2.0
    #: A searcher that stopped on a candidate site confirms it after ``settle_s`` with the
    #: pair and balance windows this many times wider: the capture window (d + pair_aim
    #: +- pair_tol) is narrow so that a moving robot stops near the site, and a robot that
    #: did stop 1-2 mm beyond its edge failed the confirmation on one noisy reading in two.
    settle_tol_scale: float = 1.0
    #: ... and when it still cannot confirm it, but the site is still near (the creep
    #: window), it stands for another ``settle_s`` with fresh readings, this many times.
    settle_retries: int = 0
    #: The first formation of a thin shape, one whose every cell is at most this many
    #: steps from the shape's outside (``lattice.depths``; strokes up to three cells wide
    #: for 2), uses ``thin_settle_retries`` and ``thin_release_clear_s`` instead of
    #: ``settle_retries`` and ``release_clear_s``. Each robot derives the shape's depth
    #: from the gene it carries. Retries and quicker releases place thin shapes' robots
    #: sooner, and a thin shape closes no ring of captures round a free middle, where
    #: the errors of captures taken at the window's edge add up (compact shapes formed
    #: less often with them). With 2 (and ``thin_right_of_way``), first formations of
    #: `T` took a median 43.8 min against 62.5 (seeds 200-319) and the six thin shapes
    #: formed 715 of 720 runs; after damage their 12 cases re-formed 286 of 320 runs
    #: against 284 of 317 (docs/algorithm.md, "Session 37"). 0: no shape is thin.
    thin_depth: int = 2
    #: ... and of at most this many cells: on bigH (321 cells, strokes 3 wide, from the
    #: cluster, 12 h) the thin settings formed 6 of 20 runs, with two tags held twice and
    #: 19 elections that lost nobody (15 of 20 without their right of way, 14 without any
    #: of them in session 31). They help shapes of 15-50 cells, and an `E` of 90 and one
    #: of 120 (strokes 2 wide, 20 seeds: 20 and 18 formed against 19 and 12). 150 is also
    #: the longest queue ``layout`` lays out without a note.
    thin_max_cells: int = 150
    thin_settle_retries: int = 3
    thin_release_clear_s: float = 10.0
    #: ... and there its searchers have right of way (``right_of_way``) too: with the two
    #: above, `T` formed in a median 42.8 min against 50.3 without it (59 of 60, seeds
    #: 200-259), and the six thin shapes 359 of 360 runs with no tag held twice. Compact
    #: shapes, which it cost runs, and every regrowth keep ``right_of_way``. "off": only
    #: ``right_of_way`` decides.
    thin_right_of_way: str = "on"
    #: ... and as many times while it searches for a regenerated target (after damage).
    #: A remnant's lattice is the first formation's, often distorted, and its last sites
    #: were lost to one noisy reading on confirming (traced on `H` split x=mid seed 1);
    #: with one retry 81 of 126 middle-split runs re-formed against 72 of 130, while in
    #: first formations one retry formed 208 of 260 against 214 (docs/algorithm.md).
    regrowth_settle_retries: int = 1
    #: Hovering after damage: a searcher of a regenerated target that has crept near the
    #: same free site for this long (the creep window keeps finding it) centres its pair
    #: window on d instead of d + ``pair_aim_mm`` until it moves on: a remnant's last
    #: sites often have their pair of neighbours a few mm too far apart for the inward
    #: window. Over 18 damage cases (10 seeds) 97 of 170 runs re-formed against 96, with
    #: shorter median re-formation in 17 (`L` split x 11 min against 14, arrow y 11 against
    #: 16, `H` x 26 against 40); in first formations it cost compact shapes (hexagon 5 of
    #: 10 against 9), so it applies after damage only (docs/algorithm.md). 0: never.
    regrowth_hover_s: float = 5.0
    #: After damage, a Queued robot that has heard a searcher within ``release_clear_s``
    #: at every evaluation for this long stops waiting for the searchers to clear: its
    #: remnant's Queued robots stand packed round the shape, and a searcher that hears no
    #: placed robot can be walled in among them, heard by all of them for ever (traced on
    #: `T` split y=mid seed 6: six Queued robots round one searcher for 2.6 h, seven sites
    #: free). 0: always wait (the first formation's rule).
    regrowth_crowded_s: float = 300.0
    #: A robot that stands still keeps the mean of up to this many readings of each
    #: neighbour that stands still too (Queued or placed), taken since either last moved,
    #: as its distance to that neighbour; beyond that many, each new reading weighs 1/this.
    #: Readings carry N(0, 2 mm) noise each, and a searcher confirming a site on single
    #: readings failed on one in the tail. 1: every reading stands alone (the paper).
    still_readings: int = 1
    follow_offset_mm: float = 0.0
    #: After damage, a searcher edge-follows placed robots at d + ``follow_offset_mm`` -
    #: this x (its time at the shape / ``widen_s``, at most 1): where growth has pinched a
    #: notch narrower than 2 d, a robot orbiting at d from the nearest robot passes outside
    #: the free site at its bottom for ever (traced on `arrow` split y=mid seed 5: 20-23
    #: mm from it on every lap for 2.5 h). In first formations diving cost compact shapes
    #: (dumbbell 4 of 10 formed with 5 mm, starfish 0), so it applies after damage only.
    #: Over 18 damage cases (seeds 0-19): 226 of 322 runs re-formed with 3 mm, 221 with 5,
    #: 189 with 0; 8 mm (89 of 170 on seeds 0-9) brings bodies into contact. 0: never nearer.
    regrowth_dive_mm: float = 3.0
    #: In the first formation, a searcher that has been ``widen_s`` at the shape edge-follows
    #: nearer too, by up to this much over the next ``widen_s`` (diving from its arrival,
    #: as after damage, lost starfish: 4 of 20 formed against 13). Over seeds 0-19 of the 13
    #: shapes 227 of 260 formed against 214, seeds 20-29 109 of 130 against 98, with
    #: shorter median formation times on thin shapes. 0: never nearer.
    dive_mm: float = 3.0
    #: After damage, a searcher that has been ``regrowth_widen_s`` at the shape and stopped
    #: on a site it could not confirm edge-follows at ``regrowth_plunge_aim_mm``
    #: instead of d - ``regrowth_dive_mm`` for this long: a notch's mouth pinched to
    #: 71 mm kept a searcher at 37 mm from every robot 18 mm outside its last site for
    #: 1.5 h (starfish split y=mid seed 1). Over the 18 damage cases, seeds 0-39: 630 of
    #: 704 runs re-formed against 626 with 0 (never). 0: no plunge, after damage or in
    #: the first formation.
    regrowth_plunge_s: float = 20.0
    #: ... at this distance (mm) from the placed robots, under its 33 mm body, so that it
    #: presses on them: where a searcher pressing past has shoved a robot into a notch's
    #: mouth, under a body's width from the robot across it, the plunge's push parts them
    #: a little each time. Traced on `L` `kill random=0.1` seed 109 (session 70): robots 8
    #: and 13 stood 63 mm apart across the free (0, -3); searcher 28 plunged into the
    #: mouth 20 times at 35 mm, which parted them by 4.5 mm in 2.8 h, and took the site
    #: 5.1 h after the damage; at 31 mm the remnant re-forms 41 min after it. The issue-5
    #: suite (seeds 0-39, 60-79 and 100-119) re-formed 1410 of 1432 runs against 1397 (17
    #: gained, 4 lost). First formations plunge at ``search.PLUNGE_AIM_MM`` (35 mm: a body
    #: and 2 mm), as every plunge did before session 70.
    regrowth_plunge_aim_mm: float = 31.0
    #: In the first formation a searcher plunges too (for ``regrowth_plunge_s``) once it
    #: has been this long at the shape (twice ``widen_s``: its dive is complete). Starfish
    #: formed 132 of 140 runs (seeds 0-79, 200-259) against 127; the regeneration suite
    #: (seeds 0-39, whose first formations change too) re-formed 650 of 720 runs against
    #: 630. Off for targets with holes, as the wave is (``O``: 26 of 60 against 31).
    #: 0: never in the first formation.
    first_plunge_after_s: float = 800.0
    closing_speed_mm_s: float = 5.0
    #: A searcher turns away from another searcher, a Queued robot or a placed robot of
    #: another shape (a sibling remnant's) read nearer than this (mm), and from a placed
    #: robot of its own shape nearer than this before it dives. The bodies touch at 33 mm.
    #: 38 until session 58: with 34 the issue-5 suite (seeds 0-59) re-formed 1042 of 1074
    #: runs against 1014 of 1072 (in the gap between sibling remnants a searcher kept
    #: turning away from the sibling's robots before it came within reach of its own),
    #: and first formations (13 shapes, seeds 200-259) formed 774 of 780 against 775,
    #: faster (median T 42.2 min against 44.2, starfish 132 against 146).
    clearance_mm: float = 34.0
    balance_tol_mm: float = 8.0
    yield_distance_mm: float = 60.0
    eval_every_ticks: int = 4
    #: Per hop of the shape's diameter: the election waits this long without change.
    election_quiet_per_hop_s: float = 1.5
    election_quiet_min_s: float = 20.0
    #: How the Leader counts its remnant: "tree" (convergecast) or "walk" (the paper's walk
    #: round the periphery, counting the bitmap's 1s inside the tags it collected).
    census: str = "tree"
    census_walk_timeout_s: float = 1200.0
    census_collect_mm: float = 60.0
    #: "clockwise": searchers edge-follow the whole group clockwise, repository included
    #: (the paper). "bounce": a searcher that leaves the shape along the repository turns
    #: round and goes back the other way, so it sweeps the shape's edge and never walks the
    #: repository again.
    orbit: str = "clockwise"
    #: A searcher near a free site stops and goes, so it sees the site with fresh readings
    #: ("on"), or passes at full speed as in the paper ("off").
    creep: str = "on"
    #: Localise also from two placed robots of the second ring (sqrt(3) d apart, the site
    #: between them) ("on"), or only from lattice neighbours as in the paper ("off").
    second_ring: str = "on"
    #: Before taking a site, check the whole shape for a hole it would close, from the
    #: searcher's memory of every site it has heard held since it began searching ("on"),
    #: or only the sites within three steps, from the robots it hears now ("off").
    hole_memory: str = "on"
    #: Flag the shape's holes (the middle of an ``O``) in the gene, as the paper proposes
    #: for enclosed unfilled areas ("on"): with the hole memory, a capture must not wall a
    #: hole off from the outside while a site on its edge is free. "off": a hole counts as
    #: the outside, as in the paper's runs, and rings close with edge sites left free.
    hole_flag: str = "on"
    #: With the hole memory, also refuse a capture after which the rest of the shape can
    #: no longer be filled in any order the greedy playout finds, though it could before
    #: ("on", see ``fill_order``), or look only one step ahead ("off").
    fill_lookahead: str = "on"
    #: A searcher that has been at the shape for 10 minutes may also take a free site from
    #: the placed robots all round it where the lattice has stretched (see ``pocket``):
    #: "on" in both phases; "regrowth" only while it searches for a regenerated target;
    #: "located" the same, with the site chosen by a least-squares fix of where it stands
    #: among them instead of by its farthest reading; "off": only from two references at
    #: d (the paper). "on" is not the default: in the first formation of starfish it led
    #: to shared tags (3 runs in 20, session 8).
    pocket: str = "off"
    #: Which Queued robot of a regenerated remnant leaves first: the one farthest (in
    #: hops) from the scaled shape's robots ("far"), so the repository stays connected to
    #: the shape, or the lowest ID, as at the start ("id", the paper). See ``release``.
    release_order: str = "far"
    #: Back-pressure: a Queued robot that hears a searcher yielding to another (traffic
    #: is jammed) holds the release for this long and passes the hold on along the
    #: repository (byte 6 of its status: seconds left, less one per hop), so no robot
    #: leaves while searchers queue up at the shape. 0: no hold (releases are paced by
    #: ``release_interval_s`` and ``release_clear_s`` alone).
    release_hold_s: float = 0.0
    #: In the first formation, along the repository (no placed robot heard yet) a searcher
    #: near its aim drives straight on instead of pivoting ("on"), or pivots to and fro as
    #: along the shape ("off", the paper's edge-following). After a regeneration the
    #: Queued robots stand packed round the shape and every searcher edge-follows.
    queue_stride: str = "on"
    #: While electing, robots note and flood where placed neighbours fell silent, and the
    #: Leader keeps the scaled target off those sites ("on", see ``silent``), or places it
    #: from the robots it hears alone ("off").
    silent_sites: str = "on"
    #: A lost searcher (no stationary robot heard) follows a searcher that hears one
    #: ("on"), or only drives its widening spiral ("off"). Off by default: over 20 seeds of
    #: 13 shapes 209 of 260 formed with it against 214 (docs/algorithm.md, "lost").
    lost_beacon: str = "off"
    #: A lost searcher yields to a lower-ID searcher nearby as it does on the group's edge
    #: ("on"), or only keeps clear of it ("off").
    lost_yield: str = "on"
    #: A searcher keeps the clearance from lower-ID searchers only ("on"): higher IDs
    #: yield to it and stop where it must pass, and in the pocket between the queue's head
    #: and the shape a searcher that kept clear of them pivoted on the spot for minutes
    #: while they waited for it (traced on `T` seeds 212 and 226). Off by default: over 13
    #: shapes (seeds 200-259) 753 of 780 formed against 769, with 38 elections that lost
    #: nobody against 1, as searchers shove placed robots apart (docs/algorithm.md).
    #: "off": it keeps clear of every searcher (but see ``thin_right_of_way``).
    right_of_way: str = "off"
    #: Placed robots keep the searchers' memory of held sites too and pass it on: every
    #: this many transmit periods a Stable robot (the growth front four times less often)
    #: sends one 40-site chunk of it instead of its status (``site_memory``, message kind
    #: 5), and every robot of its epoch and target that hears it adds the chunk to its
    #: own; needs ``hole_memory`` on. A searcher then knows sites held far out of its
    #: earshot and does not take them a second time where the lattice has bent: on
    #: bigdisc 10 tags held twice over six runs instead of 117. First formations of the
    #: 13 benchmark shapes formed as often with 12 as without, and regrowth after damage
    #: within noise (docs/algorithm.md, "Passing on the memory"). 0: off.
    held_gossip_every: int = 12
    #: First formation: a Queued robot that is the lowest ID it hears leaves only once a
    #: searcher that stood just behind it in the repository (the next lower queue rank)
    #: has passed it, or when no release has been heard of for this long. Searchers
    #: shove the repository's robots apart, and a long queue breaks near the shape; the
    #: piece beyond the break, between it and the shape, then took its lowest ID for the
    #: queue's end and left robot by robot, and every searcher coming along the queue was
    #: lost in the gap (``release``). 0: the paper's rule, the lowest ID heard leaves.
    queue_rank_wait_s: float = 600.0
    #: Where the Leader puts the scaled shape (always on its own site and two of its
    #: neighbours', the new seeds): over as much of the remnant as it can ("extent": while
    #: electing, robots flood the least and greatest tag the remnant holds along the
    #: lattice's three axes, and the Leader picks the placement with the most cells inside
    #: that hexagon, see ``extent``), or keeping as many of the sites it hears held as it
    #: can ("local": the robots round the Leader only, so a Leader on the remnant's edge
    #: put most of the shape beside the remnant and sent nearly every robot back to the
    #: repository). "extent" needs ``held_gossip_every`` > 0; without gossip the Leader
    #: places as with "local".
    placement: str = "extent"
    #: Which seeds the scaled shape grows from: "leader" (the paper): the Leader and two
    #: of its neighbours whenever some placement holds them, any other seed triangle of
    #: held sites only when none does; "any": another triangle wins when its placement
    #: covers fewer enclosed silent sites, or far more of the remnant
    #: (``placement.LEAVE_LEADER_SHARE``); "silent": "any" when the Leader knows of sites
    #: inside its remnant that fell silent (robots died there), else "leader". After
    #: ``kill`` the dead robots hem the Leader in, and a shape kept on it can miss most of
    #: the remnant (traced on `T` `kill random=0.1` seed 15: 4 of 37 robots kept against
    #: 25 possible). With "silent" the 18 damage cases re-formed 329 of 356 runs against
    #: 325 (seeds 0-19) and 308 of 350 against 307 (seeds 20-39), no case worse.
    placement_seeds: str = "silent"
    #: "weigh": a Leader's placement counts each cell on a site off the target its
    #: remnant was building (in its notches or past its edges, where the torn sites that
    #: stall regrowths lie) against it as one remnant site left out. "fewest": such cells
    #: only break ties between placements that cover as much of the remnant. "any": they
    #: count like any other cell (session 31's rule). Over the 18 damage cases (seeds
    #: 0-39) 636 of 706 runs re-formed with "weigh", 635 with "fewest", 624 with "any";
    #: on six hard cases of fresh seeds 40-59, 103 of 120 against 97 with "fewest"
    #: (session 32).
    placement_off_shape: str = "weigh"
    #: Whether a Leader may also turn the scaled shape in 60° steps ("on"): it takes the
    #: turn whose best translation ranks first, a turned one only when it covers more of
    #: the remnant (``placement.choose_placement``). The scaled starfish laid over half a
    #: starfish in its first orientation puts an arm into an old notch; turned, fewer do.
    #: Measured in session 34 (18 damage cases on seeds 0-19, 20-39 and 60-79, six hard
    #: cases on seeds 40-59): 1066 of 1184 runs re-formed against 1063, starfish
    #: `split y` 54 of 77 against 44 (seeds 0-79), `T` kill on seeds 40-59 13 of 20
    #: against 20. So it is off by default: the shape keeps the original's orientation
    #: (the paper).
    placement_turns: str = "off"
    #: "on": a robot that takes a site estimates how far off its centre it stands and
    #: sends that offset; searchers aim at sites' true centres from where the placed
    #: robots really stand (``offsets``). "off": every placed robot is taken to stand on
    #: its site's centre (the paper's localisation), and placement errors add up.
    site_offsets: str = "on"
    #: With ``site_offsets`` on, a searcher expects to read a placed robot this share of
    #: the way from the lattice distance (0) to the distance from where that robot really
    #: stands (1), when that is farther; never nearer than the lattice distance. Over 13
    #: shapes (seeds 30-49) 0.5 formed 241 of 260 against 235 with 1 (docs/algorithm.md).
    offset_trust: float = 0.5
    #: "on": a lost searcher, once its pivot on the spot has not found the group, circles
    #: the place where it last heard a stationary robot on a widening spiral, steering by
    #: its odometry (``homing``). "off": it drives a fixed widening spiral of commands,
    #: whose centre every turn away from another robot moves. "ahead": as "on", but a
    #: searcher of the first formation that got lost before it ever heard a placed robot
    #: (on its way along the repository) moves the spiral's centre on from that place,
    #: away from where it left the repository: the robots it heard there have since left
    #: and the shape lies on along the way it was going (``homing.AHEAD_SHARE``).
    lost_homing: str = "on"
    #: A lost searcher that had to turn away from a placed robot of another shape (an
    #: obstacle, ``foreign_robots``) edge-follows that shape's robots for this long (s),
    #: steering by them alone, before it steers for its spiral round home again. Its
    #: turns are pivots about a leg, which bring the body back where it started: when the
    #: spiral's course led into a sibling remnant, it turned away, turned back to the
    #: course and met the same robots, for hours (dumbbell split y=mid seed 12, session
    #: 50). Going round the sibling, it passes the gap towards its own remnant. 0: off.
    lost_escape_s: float = 120.0
    #: First formation: a searcher that has followed the repository round a dead end (the
    #: Queued robots' queue ranks climbed, then fell, by ``repository_gap.RANK_STEP``)
    #: with no placed robot heard for this long (s) leaps the gap: the Queued robots it
    #: walked round become obstacles, and it circles as a lost searcher, its spiral's
    #: centre moving on the way the ranks climbed, until it hears the shape or the queue
    #: beyond the gap (``repository_gap``). Searchers shove a long queue apart, and the
    #: piece beyond a gap wider than radio range was cut off from the shape for good
    #: (starfish seeds 229, 238). Seeds 0-319: starfish formed 305 of 320 runs against
    #: 302 (8 gained, 5 lost), `O` 286 against 284 (docs/algorithm.md, "Session 69").
    #: Queue layout only (``RunConfig.layout``): the ranks of a packed cluster climb and
    #: fall all round it. 0: off; they go round their piece of the queue.
    repository_gap_s: float = 300.0
    #: ... and a leap that has found nothing after this long (s) ends: the searcher
    #: follows the repository again.
    gap_leap_s: float = 1800.0
    #: "on": after damage, a searcher long at the shape (as for ``regrowth_plunge_s``)
    #: that reads the two robots across a free site of its target (``search.in_mouth``)
    #: plunges, as after a failed confirmation; "off": only after one. Traced on `H`
    #: split y=mid seed 47 (session 56): a searcher passed a notch's 70 mm mouth every
    #: 440 s for 10 000 s, 20 mm short of its site, and never stopped to confirm it.
    mouth_plunge: str = "on"
    #: A searcher that steers by robot B after the robot A it came from, and then by A
    #: again, takes B for the robot it came from only after steering by B for this long
    #: while moving (s); before, 2 s sufficed, as for any reference. Settling midway
    #: between a pair, the nearest of the two flips with every reading: on dumbbell split
    #: y=mid seed 28 (session 57) a searcher that had passed 42 and steered by 28 for 4 s
    #: flipped back to 42 as it stopped, so 28 became the robot it came from and it took
    #: the site on the far side of the pair, mirrored, where it stood 72 mm off. Going
    #: round a tip robot and back to its neighbour takes much longer. 0: off.
    from_return_s: float = 8.0
    #: "on": a placed robot whose held-sites message carried the signature of another
    #: target of the epoch it works for (a sibling remnant's scaled shape) is foreign to a
    #: searcher whatever its tag. "off": only a robot whose tag is no site of the
    #: searcher's target is (session 23's test). Siblings' targets can share tags: on `H`
    #: split y=mid seed 5 a leg's searcher took robots of the far half for its own shape
    #: and made its home there (session 50).
    signed_foreign: str = "on"
    #: "on": a Stable robot whose count falls short only by neighbours it knew of through
    #: their neighbours' reports (it did not hear them itself at its last complete count)
    #: waits four Danger timeouts before it starts an election; "off": one, whatever it
    #: lacks (the paper). Traced on `T` seed 43: a Stable robot whose neighbour stood
    #: 101 mm away, known by report, elected with no damage when one report dropped.
    report_patience: str = "on"
    #: A searcher confirming a site does not take it when its own position estimate puts
    #: it this far (mm) or more into a free neighbour site of the gene that has another
    #: neighbour held (``pinch``); 0: it takes any site its window confirms. First
    #: formations, 13 shapes, seeds 30-89: 753 of 780 formed against 739 with 0.
    capture_pinch_mm: float = 10.0
    #: ... nor when that estimate puts it this far (mm) or more from the site's centre in
    #: any direction (a capture half a spacing off is most of the way to another site);
    #: 0: no such limit. Both refusals share one count (``capture_pinch_refusals``). In
    #: first formations 18 formed 766 of 780 against 773 (13 shapes, seeds 30-89).
    capture_offset_mm: float = 0.0
    #: ... the same while the searcher works for a regenerated target.
    regrowth_capture_offset_mm: float = 0.0
    #: ... nor when it reads the placed robot across such a free site (two steps away
    #: through it) nearer than this (mm): the two would leave the free site a mouth too
    #: narrow for a body (ideal 2 d = 80 mm; two 33 mm bodies need 66); 0: no such test.
    capture_mouth_mm: float = 68.0
    #: ... and refuses at most this many sites so between leaving the repository and
    #: taking one: where the lattice is stretched every capture may stand far off. 4
    #: since session 20, when windows widen three times faster (``widen_s``).
    capture_pinch_refusals: int = 4
    #: A searcher this long (s) at the shape refuses no more sites for the pinch guard
    #: (``capture_pinch_mm``, ``capture_mouth_mm``) or ``capture_offset_mm``, as if it
    #: had used up its refusals. 0: only the count of refusals ends them.
    pinch_patience_s: float = 0.0
    #: ... and this many while it searches for a regenerated target (after damage).
    regrowth_pinch_refusals: int = 2
    #: What a robot that keeps its site through a regeneration does with its offset:
    #: "keep" it; "reset" it to 0 and refine it again from its neighbours' readings
    #: until it is Stable; "zero": reset it to 0 and stop refining.
    regrowth_offsets: str = "keep"
    #: After damage, an Active robot whose refined offset puts it this far (whole mm) or
    #: farther from its site's centre gives the site up and searches for it again, as a
    #: robot pushed out of range does (``rejoin``): there it blocks a neighbour site, or
    #: its estimate has slid away with its neighbours'. Estimates past 35 mm were found
    #: in 7 of 60 runs after damage, 6 of which did not re-form. 0: never.
    offset_leave_mm: float = 0.0
    #: A robot that a regenerated target leaves out waits Queued on the site it held; the
    #: searcher it becomes takes no site farther from that site's position than its
    #: odometry has taken it plus this (mm), while its odometric path is short enough to
    #: trust (``former_site``). Released beside a pair of placed robots, it otherwise
    #: took the pair's other common neighbour site, the mirror of where it stood (traced on
    #: `T` `kill random=0.1` seed 64, session 55). 0: no such test.
    former_site_slack_mm: float = 30.0
    #: A searcher this long at the shape (s) in the first formation also gets its widened
    #: window at a site where it hears only two placed neighbours (a tip or an edge), not
    #: only at one with three or more; 0: never. First formations, 13 shapes, seeds 30-89:
    #: 1800 formed 773 of 780 against 763 with 0 (docs/algorithm.md, session 27).
    two_neighbour_widen_s: float = 1800.0
    #: ... and after damage, while it searches for a regenerated target. Session 27
    #: measured 1800 worse there (320 of 352 damage runs re-formed against 330 of 356);
    #: with session 54's rules it re-formed 1004 of 1072 runs of the issue-5 suite (seeds
    #: 0-59) against 970 with 0 (docs/algorithm.md, "Session 54").
    regrowth_two_neighbour_widen_s: float = 1800.0
    #: A searcher that hears a placed robot whose tag is not a site of its own target
    #: (a robot of a sibling remnant's shape, cut from the same lattice, or one that has
    #: not yet adopted the new target): "avoid" keeps clear of it as of any obstacle and
    #: neither edge-follows it nor localises from it; "follow" treats it as part of the
    #: shape (before session 23). Traced on `H` `split y=mid` seed 0: the two searchers
    #: of one leg's remnant went round the other leg's finished shape for 2.5 h.
    foreign_robots: str = "avoid"
    #: "on": a placed robot of a regenerated target that hears, for ``merge.MERGE_AFTER_S``
    #: without a break, a placed robot of its epoch standing within ``merge.MERGE_NEAR_MM``
    #: whose tag is no site of its target (a robot of another remnant's shape, grown into
    #: contact with its own) starts an election; both remnants' robots join it and elect
    #: as one (``merge``). "off": remnants that meet stay apart.
    merge_remnants: str = "on"
    #: "on": with ``merge_remnants``, a placed robot also counts as contact a Queued robot
    #: parked beside it: one of a remnant too small to grow, which stays put where the cut
    #: left it (``parked``). A sibling remnant growing over that spot could never take the
    #: site it stands on (traced on `H` `split y=mid` seed 45: a lone robot on the free
    #: (0, 0) of the 11-robot leg for 2.8 h); electing as one, the remnants count it in
    #: and it joins the growth. "off": the parked robot stays where it is.
    merge_parked: str = "on"
    #: "on": a searcher takes a parked Queued robot (``parked``, see ``merge_parked``) for
    #: an obstacle only, as it does a robot of another shape: it does not edge-follow it
    #: as the repository (traced on `T` `remove random=0.2` seed 14: a searcher went round
    #: a lone parked robot 150 mm from its shape for 2.7 h, the last free site empty).
    #: "off": it follows it as any Queued robot.
    parked_obstacle: str = "on"
    #: "resume": a Leader whose census equals the cell count of its current target keeps
    #: that target where it is, and every robot goes back to the state it had before the
    #: election (a false alarm: nothing was lost); a robot that started the election
    #: counts the neighbour sites it missed then as held (``regeneration.resume``).
    #: "regrow": every election regrows the shape from its seeds (the paper).
    false_alarm: str = "resume"
    #: An Active robot that for this long (s) has missed only neighbour sites its memory
    #: of held sites (``site_memory``, kept by gossip) knows held excuses them, as a robot
    #: does after a false alarm, and turns Stable: their holders stand out of its range
    #: where the lattice has torn, and without this it stays Active for good and the
    #: shape never counts as formed (traced on starfish seed 274: every site held, two
    #: robots 73-77 mm from lattice neighbours). Needs ``held_gossip_every`` > 0. 0: it
    #: waits to hear them (the paper).
    remembered_neighbours_s: float = 120.0
    #: A robot on a site of the old target that the new target keeps gives the site up
    #: and searches again when its offset (``site_offsets``) puts it this many mm or more
    #: into a neighbour site of the new target that no robot it hears holds: such a site,
    #: often a notch the old shape left empty, would stay too narrow for a body
    #: (``pinch.pinches_new_target``). Whole mm; 0: every robot on a site of the new
    #: target keeps it (the paper).
    regrowth_unpinch_mm: int = 0
    #: "on": a robot on a site of the old target that the new target keeps gives it up
    #: and searches again when none of the placed robots it heard recently holds a
    #: neighbour site of its own in the new target: a lone kept robot stands where the
    #: old lattice put it, which may be far from where the growth from the new seeds
    #: will reach, and the growth bends to meet it (traced on `T` `kill random=0.1` seed
    #: 36, ``docs/algorithm.md``, "Session 59"). "off": it keeps the site (the paper).
    lone_kept_leave: str = "on"
    #: A Stable robot that has heard no placed robot for this long (s), and counts its
    #: neighbours only by the sites a false alarm excused, was pushed out of their range
    #: (searchers going round a tip shove it a little at every pass): it leaves its site
    #: and searches, and it alone counts that site free, so it can take it again
    #: (``rejoin``). 0: it stays, cut off (H ``split x`` seeds 0 and 6: all robots Stable,
    #: one of them 80 mm from the rest).
    isolated_rejoin_s: float = 120.0
    #: With the hole flag and memory: placed robots on a hole's edge note searchers they
    #: hear inside the hole and pass it on round the edge, and a searcher does not wall a
    #: hole off while it knows another searcher was seen inside within this many seconds
    #: (``hole_watch``). 0: no watch (a ring may close with searchers shut in).
    hole_watch_s: float = 60.0
    #: With the watch: a searcher whose readings of three or more placed robots fit a hole
    #: site best says so in its status (``hole_watch.INSIDE_BIT``), and every robot on the
    #: hole's edge that hears it notes a sighting, also those beside a free site of the
    #: ring, which cannot tell the two sides apart by distance alone. "off": only the
    #: distance test. With the rim wave, "on" formed `O` 184 of 220 runs against 158
    #: (``docs/algorithm.md``, session 65; without it, 57 of 100 against 61, session 64).
    inside_bit: str = "on"
    #: With the watch: a capture that would leave one free site of a hole's edge
    #: reachable only through the hole (two free sites across a ring, the ring's last
    #: way, taken from its middle) is not refused when the searcher knows exactly one
    #: other searcher seen in the hole lately: that one can take the site
    #: (``hole_watch.taker_allows``). "off": refused, as any capture that cuts a free site
    #: off from the outside. With the rim wave and ``inside_bit``, "on" formed `O` 180 of
    #: 220 runs against 184 (session 65), so it is off.
    hole_taker: str = "off"
    #: For a target with holes: a capture of a site on a hole's edge is not refused for
    #: leaving a free neighbour site too narrow to enter when that site and its one free
    #: neighbour make a notch two deep, open to the outside of the shape
    #: (``site_memory.notch_two_deep``), or when its two free neighbours are another
    #: site on the hole's edge and one that is not (``site_memory.way_corridor``: a way
    #: across the ring that stays one). A ring's last way across (edge site, middle,
    #: outer site) is otherwise refused at all three sites. "off": refused. `O`, seeds
    #: 0-319: with ``way_plunge``, 284 of 320 runs formed against 277 (with the notch
    #: alone 281); alone (the notch) 271 against 267.
    way_end: str = "on"
    #: For a target with holes: in the first formation too, a searcher long at the shape
    #: that stands in the mouth of a notch plunges (as ``mouth_plunge`` after damage), so
    #: that it reaches the notch's inner site. "off": only after damage. `O`, seeds
    #: 0-319: 277 of 320 runs formed against 267; with ``way_end`` 284 (docs/algorithm.md,
    #: "Session 68").
    way_plunge: str = "on"
    #: In the first formation of any target, a searcher that has been this long (simulated
    #: seconds) at the shape plunges when it stands in the mouth of a notch, as
    #: ``way_plunge`` lets a ring's searchers do from ``widen_s``: the last searcher of a
    #: starfish that passed 20 mm from its free site every 800 s for hours never stopped
    #: there to confirm it (seed 59). 0: off. With 3600 and ``late_plunge_aim_mm`` 31,
    #: starfish formed 309 of 320 runs on seeds 0-319 against 305 (docs/algorithm.md,
    #: "Session 73").
    late_plunge_s: float = 3600.0
    #: ... and such a plunge, begun in a mouth from ``late_plunge_s`` at the shape, keeps
    #: this near the placed robots (mm): under the 33 mm body, so it presses the mouth's
    #: robots apart, as every plunge after damage does (``regrowth_plunge_aim_mm``). At
    #: 35 (the first formation's other plunges) starfish formed 306 of 320.
    late_plunge_aim_mm: float = 31.0
    #: In the first formation a searcher does not take a site while a neighbour site of
    #: the target nearer the seed triangle (in steps within the shape) is not known held,
    #: for its first this many seconds at the shape (``wave``): a compact shape then
    #: grows outwards from the seeds instead of along its rim round free middles. Off
    #: for targets with holes and for thin shapes (``thin_depth``: `T` took a median 47
    #: min against 43 with it). 0: off, the paper's first site found. 1200 formed disc
    #: 119 of 120 runs against 113 (``docs/algorithm.md``, sessions 44 and 45).
    wave_s: float = 1200.0
    #: For a target with holes, the wave runs out from the holes' edges instead of from
    #: the seeds (``wave.rim_hops``): in the first formation a searcher does not take a
    #: site while a neighbour site nearer a hole could be located and is not known held,
    #: for its first this many seconds at the shape. A ring's rows then close round the
    #: hole first, and its last free sites are a notch open to the outside rather than a
    #: way across the ring that no capture may close. 0: off. 1200 formed `O` 158 of 220
    #: runs against 135 (``docs/algorithm.md``, session 65).
    rim_wave_s: float = 1200.0
    #: Which robot of a pair a searcher passed first, when it came from a robot outside
    #: the pair (it decides the side of the pair the searcher takes a site on): "off",
    #: the one it steers by now (``localise.came_from``); "on", the one of the two it met
    #: first as its reference, when it steered by both (``met_order``); "regrowth", so
    #: only after damage (traced on dumbbell ``split y=mid`` seed 77: a searcher that
    #: had steered by the first of the pair for less than 2 s took the mirror site, and
    #: a mirrored row of the lattice grew from it).
    came_order: str = "regrowth"
    #: An electing robot that hears the announcement of a target for the epoch it elects
    #: for, from a Leader whose ID is higher than the lowest candidate it hears itself:
    #: "ignore", that Leader is not its own election's (min-ID flooding would have beaten
    #: it) but a sibling remnant's of the same damage, and the robot goes on electing;
    #: "strict", it also ignores one by a lower Leader than it has heard in this election
    #: (a sibling whose Leader has the lower ID: `T` `remove random=0.2` seed 85);
    #: "adopt", it takes the target as its own (traced on `T` `remove random=0.2` seed 10:
    #: a searcher of a 3-robot remnant that had elected came within range of the 33-robot
    #: remnant while it still elected, and all 36 robots grew the 3-cell target).
    sibling_target: str = "strict"
    #: Every status carries four bits of its sender's target signature (the high half of
    #: byte 2, ``messages.status_nibble``), so that after damage a robot tells a sibling
    #: remnant's robots (the same epoch, another target) from its own at the first status
    #: it hears: "placed", a sibling's placed robot is foreign to a searcher whatever its
    #: tag (as ``signed_foreign`` makes it only once its rarer held-sites message is
    #: heard), and a Queued robot takes no release count or rank from a sibling's robots.
    #: Traced on dumbbell `split x=mid` seed 80 (session 62): two lost searchers of the
    #: right half reached the left half, made their home among its robots, whose tags are
    #: sites of their own target too, and went round it for four hours. "on": a searcher
    #: also takes a sibling's Queued robot for an obstacle, not for its repository; then
    #: a lost searcher near a sibling has nothing to hold on to, and on `H` `split y`,
    #: whose legs stand side by side, three such runs stopped re-forming (seeds 0-39, 4
    #: lost, none gained). "off": the bits are 0 and unread, as before session 62.
    status_signature: str = "placed"

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in CHOICES:
                if value not in CHOICES[f.name]:
                    raise EtswarmError(
                        f"{f.name} must be one of {CHOICES[f.name]}, got {value!r}"
                    )
            elif f.name in (
                "creep", "second_ring", "hole_memory", "hole_flag", "fill_lookahead",
                "queue_stride",
                "silent_sites", "lost_beacon", "lost_yield", "right_of_way", "thin_right_of_way",
                "site_offsets", "report_patience", "merge_remnants", "signed_foreign",
                "mouth_plunge", "merge_parked", "parked_obstacle", "lone_kept_leave",
                "inside_bit", "hole_taker", "way_end", "way_plunge",
            ):
                if value not in ("on", "off"):
                    raise EtswarmError(f"{f.name} must be 'on' or 'off', got {value!r}")
            elif f.name == "offset_trust":
                if not 0 <= value <= 1:
                    raise EtswarmError(f"ET parameter offset_trust must be in [0, 1], got {value}")
            elif f.name in SIGNED:
                continue
            elif f.name in ("widen_max", "consistency_widen_max", "settle_tol_scale"):
                if not value >= 1:
                    raise EtswarmError(f"ET parameter {f.name} must be >= 1, got {value}")
            elif f.name in NON_NEGATIVE:
                if not value >= 0:
                    raise EtswarmError(f"ET parameter {f.name} must be >= 0, got {value}")
            elif not value > 0:
                raise EtswarmError(f"ET parameter {f.name} must be > 0, got {value}")

    def pack(
        self,
        ticks_per_s: int,
        gene_x0: int,
        gene_y0: int,
        diameter_hops: int = 10,
        nominal_motion: tuple[float, float, float, float] = NOMINAL_MOTION,
        shape_depth: int = 0,
        shape_cells: int = 0,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return ``(ci, cf)``: int64 (N_CI,) and float64 (N_CF,) arrays for the kernel.

        ``nominal_motion`` is the robot model the odometry assumes: forward speed (mm/s),
        turning rate (deg/s), pivot-leg angle (deg) and body radius (mm).

        ``diameter_hops`` bounds the hops across any remnant (the shape's extent); the
        election's quiet time grows with it so a Leader is declared only after the lowest
        ID had time to cross the remnant at the configured loss.

        ``shape_depth`` is the first target's greatest cell depth (``lattice.depths``; 0:
        unknown) and ``shape_cells`` its cell count (0: unknown); a depth of at most
        ``thin_depth`` and at most ``thin_max_cells`` cells give the first formation the
        thin settings, and no wave (``wave_s``).
        """

        def ticks(seconds: float) -> int:
            return max(1, round(seconds * ticks_per_s))

        ci = np.zeros(N_CI, dtype=np.int64)
        ci[C_TICKS_NB_FRESH] = ticks(self.neighbour_timeout_s)
        ci[C_TICKS_DANGER] = ticks(self.danger_timeout_s)
        ci[C_TICKS_QUASI] = ticks(self.quasi_s)
        ci[C_TICKS_RELEASE] = ticks(self.release_interval_s)
        ci[C_TICKS_QUIET] = ticks(self.release_quiet_s)
        ci[C_TICKS_SETTLE] = ticks(self.settle_s)
        ci[C_TICKS_COOLDOWN] = ticks(self.rejected_cooldown_s)
        ci[C_TICKS_YIELD_MAX] = ticks(self.yield_max_s)
        ci[C_TICKS_MOVE_FRESH] = ticks(self.steer_fresh_s)
        ci[C_GENE_X0] = gene_x0
        ci[C_GENE_Y0] = gene_y0
        ci[C_EVAL_EVERY] = self.eval_every_ticks
        thin = 0 < shape_depth <= self.thin_depth and shape_cells <= self.thin_max_cells
        ci[C_TICKS_CLEAR] = ticks(self.release_clear_s)
        ci[C_TICKS_CLEAR_FIRST] = ticks(
            self.thin_release_clear_s if thin else self.release_clear_s
        )
        ci[C_TICKS_REGEN_QUIET] = ticks(
            max(self.election_quiet_min_s, self.election_quiet_per_hop_s * diameter_hops)
        )
        ci[C_CENSUS_WALK] = 1 if self.census == "walk" else 0
        ci[C_TICKS_WALK_MAX] = ticks(self.census_walk_timeout_s)
        ci[C_ORBIT_BOUNCE] = 1 if self.orbit == "bounce" else 0
        ci[C_CREEP] = 1 if self.creep == "on" else 0
        ci[C_SECOND_RING] = 1 if self.second_ring == "on" else 0
        ci[C_HOLE_MEMORY] = 1 if self.hole_memory == "on" else 0
        ci[C_FILL_LOOKAHEAD] = 1 if self.fill_lookahead == "on" else 0
        ci[C_GOSSIP_EVERY] = self.held_gossip_every if self.hole_memory == "on" else 0
        ci[C_TICKS_RANK_WAIT] = ticks(self.queue_rank_wait_s) if self.queue_rank_wait_s > 0 else 0
        ci[C_POCKET] = POCKET_MODES.index(self.pocket)
        # the placement over the extent counts the sites remembered held: gossip keeps them
        ci[C_EXTENT] = 1 if self.placement == "extent" and ci[C_GOSSIP_EVERY] > 0 else 0
        ci[C_OFFSETS] = 1 if self.site_offsets == "on" else 0
        ci[C_LOST_HOMING] = LOST_HOMING_MODES.index(self.lost_homing)
        ci[C_REPORT_PATIENCE] = 1 if self.report_patience == "on" else 0
        ci[C_QUEUE_STRIDE] = 1 if self.queue_stride == "on" else 0
        ci[C_SILENT_SITES] = 1 if self.silent_sites == "on" else 0
        ci[C_LOST_BEACON] = 1 if self.lost_beacon == "on" else 0
        ci[C_LOST_YIELD] = 1 if self.lost_yield == "on" else 0
        ci[C_SIGNED_FOREIGN] = 1 if self.signed_foreign == "on" else 0
        ci[C_MOUTH_PLUNGE] = 1 if self.mouth_plunge == "on" else 0
        ci[C_LONE_KEPT] = 1 if self.lone_kept_leave == "on" else 0
        ci[C_TICKS_FROM_RETURN] = round(self.from_return_s * ticks_per_s)
        if self.right_of_way == "on":
            ci[C_RIGHT_OF_WAY] = RIGHT_OF_WAY_ALWAYS
        elif thin and self.thin_right_of_way == "on":
            ci[C_RIGHT_OF_WAY] = RIGHT_OF_WAY_FIRST_GROWTH
        else:
            ci[C_RIGHT_OF_WAY] = RIGHT_OF_WAY_NEVER
        ci[C_RELEASE_FAR] = 1 if self.release_order == "far" else 0
        ci[C_AVOID_FOREIGN] = 1 if self.foreign_robots == "avoid" else 0
        ci[C_MERGE] = 1 if self.merge_remnants == "on" else 0
        ci[C_MERGE_PARKED] = 1 if self.merge_parked == "on" else 0
        ci[C_PARKED_OBSTACLE] = 1 if self.parked_obstacle == "on" else 0
        ci[C_CAME_ORDER] = CAME_ORDER_MODES.index(self.came_order)
        ci[C_SIBLING_TARGET] = SIBLING_TARGET_MODES.index(self.sibling_target)
        ci[C_STATUS_SIG] = STATUS_SIGNATURE_MODES.index(self.status_signature)
        ci[C_FALSE_ALARM] = 1 if self.false_alarm == "resume" else 0
        ci[C_TICKS_REMEMBERED] = (
            ticks(self.remembered_neighbours_s)
            if self.remembered_neighbours_s > 0 and ci[C_GOSSIP_EVERY] > 0
            else 0
        )
        ci[C_REGROW_UNPINCH] = self.regrowth_unpinch_mm
        ci[C_TICKS_REJOIN] = ticks(self.isolated_rejoin_s) if self.isolated_rejoin_s > 0 else 0
        ci[C_SETTLE_RETRIES] = self.thin_settle_retries if thin else self.settle_retries
        ci[C_REGROW_RETRIES] = self.regrowth_settle_retries
        ci[C_TICKS_HOVER] = round(self.regrowth_hover_s * ticks_per_s)
        ci[C_TICKS_HOLD] = round(self.release_hold_s * ticks_per_s)
        ci[C_STILL_READINGS] = self.still_readings
        ci[C_TICKS_CROWDED] = round(self.regrowth_crowded_s * ticks_per_s)
        holes_known = self.hole_flag == "on" and self.hole_memory == "on"
        watching = self.hole_watch_s > 0 and holes_known
        ci[C_HOLE_WATCH] = ticks(self.hole_watch_s) if watching else 0
        ci[C_INSIDE_BIT] = 1 if watching and self.inside_bit == "on" else 0
        ci[C_HOLE_TAKER] = 1 if watching and self.hole_taker == "on" else 0
        ci[C_WAY_END] = 1 if holes_known and self.way_end == "on" else 0
        ci[C_WAY_PLUNGE] = 1 if self.way_plunge == "on" else 0
        ci[C_TICKS_LATE_PLUNGE] = ticks(self.late_plunge_s) if self.late_plunge_s > 0 else 0
        ci[C_TICKS_PER_S] = ticks_per_s
        # A thin shape closes no ring round a free middle: the wave only slows it.
        ci[C_WAVE] = ticks(self.wave_s) if self.wave_s > 0 and not thin else 0
        ci[C_RIM_WAVE] = ticks(self.rim_wave_s) if self.rim_wave_s > 0 else 0
        ci[C_TICKS_PLUNGE] = ticks(self.regrowth_plunge_s) if self.regrowth_plunge_s > 0 else 0
        ci[C_TICKS_LOST_ESCAPE] = ticks(self.lost_escape_s) if self.lost_escape_s > 0 else 0
        ci[C_TICKS_GAP] = ticks(self.repository_gap_s) if self.repository_gap_s > 0 else 0
        ci[C_TICKS_LEAP] = ticks(self.gap_leap_s)
        first_plunge = self.first_plunge_after_s
        ci[C_FIRST_PLUNGE] = ticks(first_plunge) if first_plunge > 0 else 0
        cf = np.zeros(N_CF, dtype=np.float64)
        cf[F_SPACING] = self.spacing_mm
        cf[F_PAIR_TOL] = self.pair_tol_mm
        cf[F_PAIR_AIM] = self.pair_aim_mm
        cf[F_WIDEN_MAX] = self.widen_max
        cf[F_WIDEN_TICKS] = self.widen_s * ticks_per_s
        cf[F_REGROW_WIDEN_TICKS] = self.regrowth_widen_s * ticks_per_s
        cf[F_TWO_WIDEN_TICKS] = self.two_neighbour_widen_s * ticks_per_s
        cf[F_REGROW_TWO_WIDEN_TICKS] = self.regrowth_two_neighbour_widen_s * ticks_per_s
        cf[F_AIM_RELAX] = self.pair_aim_relax_s * ticks_per_s
        cf[F_CONSIST_TOL] = self.consistency_tol_mm
        cf[F_MIRROR_MARGIN] = self.mirror_margin_mm
        cf[F_REGROW_FOLD_SKIP] = self.regrowth_fold_skip_mm
        cf[F_REGROW_PLUNGE_AIM] = self.regrowth_plunge_aim_mm
        cf[F_LATE_PLUNGE_AIM] = self.late_plunge_aim_mm
        cf[F_CONSIST_WIDEN] = self.consistency_widen_max
        cf[F_SETTLE_SCALE] = self.settle_tol_scale
        cf[F_YIELD_DIST] = self.yield_distance_mm
        cf[F_FOLLOW_OFFSET] = self.follow_offset_mm
        cf[F_CLOSING] = self.closing_speed_mm_s / ticks_per_s
        cf[F_CLEARANCE] = self.clearance_mm
        cf[F_DIVE] = self.regrowth_dive_mm
        cf[F_DIVE_FIRST] = self.dive_mm
        cf[F_BALANCE_TOL] = self.balance_tol_mm
        cf[F_WALK_COLLECT] = self.census_collect_mm
        cf[F_OFFSET_TRUST] = self.offset_trust
        cf[F_CAPTURE_PINCH] = self.capture_pinch_mm
        cf[F_CAPTURE_OFFSET] = self.capture_offset_mm
        cf[F_REGROW_CAPTURE_OFFSET] = self.regrowth_capture_offset_mm
        cf[F_CAPTURE_MOUTH] = self.capture_mouth_mm
        cf[F_PINCH_PATIENCE] = self.pinch_patience_s * ticks_per_s
        cf[F_FORMER_SLACK] = self.former_site_slack_mm
        ci[C_PINCH_REFUSALS] = self.capture_pinch_refusals
        ci[C_REGROW_PINCH_REFUSALS] = self.regrowth_pinch_refusals
        ci[C_REGROW_OFFSETS] = REGROWTH_OFFSETS.index(self.regrowth_offsets)
        ci[C_OFFSET_LEAVE] = round(self.offset_leave_mm)
        speed_mm_s, turn_deg_s, leg_deg, radius_mm = nominal_motion
        cf[F_ODO_STEP] = speed_mm_s / ticks_per_s
        cf[F_ODO_TURN] = math.radians(turn_deg_s) / ticks_per_s
        cf[F_ODO_LEG] = math.radians(leg_deg)
        cf[F_ODO_RADIUS] = radius_mm
        return ci, cf


def parse_et_option(text: str) -> tuple[str, float | int | str]:
    """``NAME=VALUE`` (``--et``) -> (field of ``ETParams``, value of that field's type).

    Raises ``EtswarmError`` naming the option when the name is unknown or the value does
    not parse; ``ETParams`` itself then checks the range.
    """
    name, sep, value = text.partition("=")
    name = name.strip().replace("-", "_")
    value = value.strip()
    kinds = {f.name: type(f.default) for f in fields(ETParams)}
    if not sep or name not in kinds or not value:
        raise EtswarmError(
            f"--et {text!r}: expected NAME=VALUE with NAME one of {', '.join(sorted(kinds))}"
        )
    kind = kinds[name]
    if kind is str:
        return name, value
    try:
        return name, kind(value)
    except ValueError:
        raise EtswarmError(
            f"--et {text!r}: {name} takes a number ({kind.__name__}), got {value!r}"
        ) from None
