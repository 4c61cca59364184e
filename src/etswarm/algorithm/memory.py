"""Per-robot memory of the ET controller: column layouts and allocation.

A robot's memory is one row of ``ri`` (int64 fields) plus its neighbour table, one
``(M, NB_FIELDS)`` block of ``nb`` and ``(M,)`` of ``nb_dist``. These are the robot's own
memory only; the controller never reads another robot's row.

``mem`` passed to the simulator is the tuple
``(stop, ri, nb, nb_dist, gene_flag, gene_nn, slot_info, ci, cf, walk_seen, held, idle)``:

- ``stop``       (1,) int64: nonzero asks the simulator to end the chunk (host work needed)
- ``ri``         (N, R_FIELDS) int64: the fields ``R_*`` below
- ``nb``         (N, M, NB_FIELDS) int64: neighbour table, fields ``NB_*``; NB_ID -1 = empty.
  Stored field by field (a transposed view of an (N, NB_FIELDS, M) array): a robot's M
  values of one field lie together, so a scan of the table over a few fields (finding a
  sender, the Queued robots' rule) reads a few cache lines instead of one per row
- ``nb_dist``    (N, M) float64: last distance estimate to that neighbour, mm
- ``gene_flag``  (S, GX, GY) uint8 and ``gene_nn`` (S, GX, GY) int16: the genes of up to S
  targets (slot 0: the original shape; later slots: scaled shapes made by regeneration) as
  dense grids indexed by (X - ci[C_GENE_X0], Y - ci[C_GENE_Y0]); flag 1 on the shape,
  ``HOLE_FLAG`` on a hole of it (``lattice.enclosed_cells``: the middle of an ``O``,
  which the paper proposes to flag in the gene), 0 outside; NN in the low bits of
  ``gene_nn`` (``wave.nn_of``), and in slot 0 with the wave on, the steps from the seed
  triangle above them (``wave.HOPS_SHIFT``)
- ``slot_info``  (S, SLOT_FIELDS) int64: per target slot its cell count, release limit,
  translation and turn; a robot that hears of a scaled target (its code n + 8192 * turn,
  tx, ty; ``regeneration.target_code``) finds its slot here (the slots memoise ``scale``,
  which every robot could compute on board from n alone)
- ``ci``, ``cf``: packed constants (see ``params``)
- ``walk_seen``  (N, GX, GY) uint8: per robot, the tags it collected walking round its
  remnant as Leader (census ``walk``; grid as the genes'); (N, 1, 1) when census ``tree``
- ``held``       (N, WX, WY) uint8: per searching robot, the sites it has heard held (see
  ``site_memory``; a window of the original shape's extent plus one site on every side)
- ``idle``       (N,) int64: per robot, the tick until which it sleeps unless it hears
  something new (0: awake; Queued robots whose next evaluations could change nothing,
  see ``controller.et_part``); the host zeroes a robot's entry when it edits its memory
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.states import State

#: ``gene_flag`` value of a site outside the shape that the shape encloses (a hole): no
#: robot takes it, and free space there leads nowhere once the shape round it is closed.
HOLE_FLAG = 2

# Per-robot integer fields.
R_STATE = 0
R_TAG_X = 1
R_TAG_Y = 2
R_NN = 3  # neighbours the gene wants at this tag
R_TS = 4  # timestep (order of arrival)
R_SINCE = 5  # tick of the last state change
R_QMIN = 6  # lowest Queued ID this robot hears (itself included)
R_QMIN_SINCE = 7  # tick R_QMIN last changed
R_FLOOR = 8  # ID of the last robot released, as far as this robot knows (-1: none)
R_FLOOR_SINCE = 9  # tick this robot last heard of a release
R_RELEASED = 10  # robots released so far, as far as this robot knows
R_SUB = 11  # search sub-state (SUB_*)
R_SUB_SINCE = 12
R_CAND_X = 13  # site being settled on
R_CAND_Y = 14
R_COOLDOWN = 15  # tick until which site candidates are ignored
R_YIELD_SINCE = 16  # tick yielding began (-1: not yielding)
R_COUNT = 17  # placed lattice neighbours heard (last evaluation)
R_BELOW_SINCE = 18  # tick the count fell below NN while Stable (-1: not below)
R_QUASI_UNTIL = 19
R_EPOCH = 20  # target epoch (bumped by regeneration)
# A searcher tracks the distance trend of two robots, each in four consecutive fields
# (ID or -1, tick of the last reading used, that reading in 1/16 mm, trend: -1 closing
# in, +1 drawing away, 0 unknown): the stationary robot it steers by, and the nearest
# lower-ID searcher it may yield to.
R_REF_ID = 21
R_REF_TREND = 24
R_YLD_ID = 25
R_YLD_TREND = 28
R_MASK = 29  # bit k set: a robot holds the neighbour site in direction k (last evaluation)
# Regeneration (paper Algorithm 2).
R_TSLOT = 30  # slot of the current target's gene (see ``slot_info``)
R_HAS_TAG = 31  # 1 while the robot holds a tag (kept through the election)
R_PHASE = 32  # PHASE_*
R_LEADER = 33  # lowest ID heard in the election
R_HOP = 34  # hops from that robot (spanning tree depth)
R_PARENT = 35  # neighbour one hop nearer to it (-1: none)
R_SUBCOUNT = 36  # robots in this robot's subtree (census by convergecast)
R_ELECT_SINCE = 37  # tick the election began here
R_BEST_SINCE = 38  # tick (leader, hop) last changed
R_COUNT_SINCE = 39  # tick the subtree count last changed
R_REQUEST = 40  # leader's request to compute the scaled gene: 0 none, 1 asked, 2 answered
R_CENSUS = 41  # robots counted by the census (leader)
R_NEWSLOT = 42  # answer: slot of the scaled target
R_ADOPTED_AT = 43  # tick the current target was adopted (it is relayed for a while)
R_PEND_EPOCH = 44  # newest target announcement heard: epoch (-1: none), code, tx, ty
R_PEND_N = 45  # the target's code: n + 8192 * turn (``regeneration.target_code``)
R_PEND_TX = 46
R_PEND_TY = 47
# Census by periphery walk (``census_walk``).
R_CANDIDATE = 48  # 1: stands for Leader itself (census walk: only robots that saw damage)
R_WALK = 49  # WALK_* phase of the Leader's walk round the remnant
R_WALK_SINCE = 50  # tick the walk began
R_WALK_SUB_SINCE = 51  # tick the current walk phase began
R_WALK_GONE = 52  # 1 once the walker has been well away from its own site
R_WALK_END = 53  # tick the census was concluded (walk or tree)
R_WALK_RESULT = 54  # WALK_RESULT_*: how the walk ended
R_WALK_SEEN = 55  # tick this robot last heard a walking Leader (it then also sends its tag)
R_WALK_TAGS = 56  # distinct tags the walker collected
R_WALK_DIRS = 57  # bit k: a robot held the walker's neighbour site in direction k
R_WALK_HEARD = 58  # tick the walker last heard any robot
R_WALK_DOOR = 59  # 1: the walker is settling on the doorstep of its site, not on it
R_LOST_SINCE = 60  # 1 + tick a searcher last lost every stationary robot (0: not lost)
R_ORBIT = 61  # a searcher's direction round the group: 0 clockwise, 1 anticlockwise
R_ON_SHAPE = 62  # 1 once a searcher steered by a placed robot since it last turned round
R_CREEP_UNTIL = 63  # a searcher near a free site creeps (stop-and-go) until this tick
R_SHAPE_SINCE = 64  # 1 + tick a searcher first heard a placed robot (0: not yet)
R_TOWARD_SINCE = 65  # a searcher has pivoted towards the group (never away) since this tick
R_HELD_EPOCH = 66  # 1 + the target epoch the searcher's memory of held sites is for (0: none)
R_SHAPE_HOPS = 67  # a Queued robot's hops to the target's placed robots (regenerated remnants)
R_SILENT_N = 68  # how many silent sites the robot knows of (``silent``)
R_SILENT_NEXT = 69  # the next of them to send
R_SILENT_ADDED = 70  # tick it last learnt of a new one
R_SILENT0 = 71  # the first of SILENT_MAX fields: silent sites' tags (``silent.pack_tag``)
SILENT_MAX = 8
# The side of a pair a searcher passes on (``localise.find_site``) follows from which of the
# two it came from: the reference it steered by before the current one, kept only if it
# steered by it while moving for a while (at the midpoint of a pair the nearest robot
# flickers between the two, so the current reference alone says nothing).
R_FROM_ID = R_SILENT0 + SILENT_MAX  # the reference before the current one (-1: none)
R_REF_MOVED = R_FROM_ID + 1  # ticks the searcher moved since its current reference took over
# A searcher trapped where the group's edge folds in (between the repository and the shape)
# steers by the same few robots for ever; it turns round (``search.follow_reference``).
R_RECENT0 = R_REF_MOVED + 1  # the first of RECENT_REFS fields: its last distinct references
RECENT_REFS = 4
R_NEW_REF_MOVED = R_RECENT0 + RECENT_REFS  # ticks moved since a reference not among them
R_SETTLE_TRIES = R_NEW_REF_MOVED + 1  # settle periods a searcher has stood on its candidate
R_HOLD_UNTIL = R_SETTLE_TRIES + 1  # a Queued robot releases no robot before this tick
# Hovering (option ``regrowth_hover_s``): the free site a creeping searcher keeps finding
# near it with the creep window, and since when (1 + tick; 0: none).
R_HOVER_X = R_HOLD_UNTIL + 1
R_HOVER_Y = R_HOVER_X + 1
R_HOVER_SINCE = R_HOVER_Y + 1
#: The last tick at which the robot's motors were on: it has stood where it is since the
#: tick after (``controller.ingest`` averages readings taken since then).
R_MOVED_TICK = R_HOVER_SINCE + 1
#: A Queued robot of a regenerated target has heard a searcher within ``release_clear_s``
#: at every evaluation since this tick + 1 (0: it did not at its last one).
R_CROWDED_SINCE = R_MOVED_TICK + 1
#: An electing robot's settled subtree count (``regeneration.settle_count``): the count
#: it last kept for a quarter of the quiet time, since when (R_SETTLED_SINCE), and 1 +
#: the tick since which the count has differed from it (R_COUNT_OFF; 0: equal).
R_SETTLED_COUNT = R_CROWDED_SINCE + 1
R_SETTLED_SINCE = R_SETTLED_COUNT + 1
R_COUNT_OFF = R_SETTLED_SINCE + 1
#: A Queued robot's rank in the first formation's repository: the most Queued robots of
#: lower ID it has learnt stand behind it in a chain (``release``, never lowered), and
#: the highest rank it heard a searcher carry (the rank that robot had when it left).
R_QRANK = R_COUNT_OFF + 1
R_FLOOR_RANK = R_QRANK + 1
#: The tick a Queued robot last learnt of a release: a higher released count or a
#: searcher of a higher rank than any before (searchers carry the count of their release
#: time only, so past a break in the queue the count stands still while releases go on).
R_RANK_NEWS = R_FLOOR_RANK + 1
#: While electing: the extent of the remnant's tags heard of so far (``extent``), as the
#: least and greatest X, Y and X - Y (six fields), and the tick it last grew.
R_EXT0 = R_RANK_NEWS + 1
EXTENT_FIELDS = 6
R_EXT_GREW = R_EXT0 + EXTENT_FIELDS
#: A placed robot's estimate of where it stands from its site's centre (``offsets``), in
#: units of ``offsets.FINE_PER_MM`` along the gene frame's x and y; 1 while it still
#: refines that estimate (from taking its site until it is Stable); the tick of the
#: newest reading it refined by.
R_OFF_X = R_EXT_GREW + 1
R_OFF_Y = R_OFF_X + 1
R_OFF_REFINE = R_OFF_Y + 1
R_OFF_TICK = R_OFF_REFINE + 1
#: A searcher's odometry (``homing``): its pose as it reckons it from its own motor
#: commands, in a frame of its own (position x, y and heading), and home, where it last
#: heard a stationary robot (x, y); the length of its path so far, and that length when
#: it last lost the group.
R_ODO_X = R_OFF_TICK + 1
R_ODO_Y = R_ODO_X + 1
R_ODO_H = R_ODO_Y + 1
R_HOME_X = R_ODO_H + 1
R_HOME_Y = R_HOME_X + 1
R_ODO_PATH = R_HOME_Y + 1
R_LOST_PATH = R_ODO_PATH + 1
#: A placed robot's neighbour directions (bits as ``R_MASK``) whose holder it heard itself
#: at its last evaluation with every neighbour accounted for (the others it knew of only
#: through their neighbours' reports).
R_SEEN_FULL = R_LOST_PATH + 1
#: Sites a searcher refused since it left the repository because it stood too far into
#: a free neighbour site (``pinch``).
R_PINCH_REFUSED = R_SEEN_FULL + 1
#: Tick + 1 since which a placed robot has heard another remnant's robot beside it
#: without a break (0: not now; ``merge``).
R_CONTACT_SINCE = R_PINCH_REFUSED + 1
#: What a robot was before it joined an election (its state, and R_SINCE then), to go
#: back to when the election was a false alarm (``regeneration.resume``).
R_PRE_STATE = R_CONTACT_SINCE + 1
R_PRE_SINCE = R_PRE_STATE + 1
#: Neighbour sites of the gene (bits as ``R_MASK``) that a Stable robot starting an
#: election did not know held; after a false alarm they are excused: they count as held
#: until the robot next adopts a new target.
R_MISSING = R_PRE_SINCE + 1
R_EXCUSED = R_MISSING + 1
#: Tick + 1 at which the robot resumed after a false alarm (0: it has not since it last
#: adopted a target); for a quiet time after it, it starts no election.
R_RESUMED_AT = R_EXCUSED + 1
#: The epoch whose target the robot's present growth began with: its epoch when it
#: adopted a new target, kept when it resumed after a false alarm. 0 while it still works
#: on the first formation, whatever elections were false alarms (``first_growth``).
R_GROWTH = R_RESUMED_AT + 1
#: Tick + 1 since which an Active (or Quasi) robot has missed only neighbour sites its
#: memory of held sites knows held (0: not now; ``placed.remembered_dirs``).
R_REMEMBERED_SINCE = R_GROWTH + 1
#: A Stable robot that hears no placed robot: 1 + the tick since which (0: it hears
#: one; ``rejoin``). A searcher that left its site so (``R_LEFT`` 1) counts that site
#: (``R_LEFT_X``, ``R_LEFT_Y``) free whatever its memory of held sites says.
R_CUT_OFF_SINCE = R_REMEMBERED_SINCE + 1
R_LEFT = R_CUT_OFF_SINCE + 1
R_LEFT_X = R_LEFT + 1
R_LEFT_Y = R_LEFT_X + 1
#: Two sightings of searchers inside a hole (``hole_watch``): the searcher's ID (-1:
#: none) and the tick, on this robot's clock, it was heard there.
R_WATCH_ID0 = R_LEFT_Y + 1
R_WATCH_T0 = R_WATCH_ID0 + 1
R_WATCH_ID1 = R_WATCH_T0 + 1
R_WATCH_T1 = R_WATCH_ID1 + 1
#: A searcher of a regenerated target that could not confirm its site edge-follows at
#: ``search.PLUNGE_AIM_MM`` until this tick (``ETParams.regrowth_plunge_s``).
R_PLUNGE_UNTIL = R_WATCH_T1 + 1
#: A lost searcher that had to turn away from another shape's robot edge-follows that
#: shape's robots until this tick (``ETParams.lost_escape_s``).
R_ESCAPE_UNTIL = R_PLUNGE_UNTIL + 1
#: The site a placed robot held when a regenerated target left it out, so that it waits
#: Queued where it stood; the searcher it becomes knows, by odometry, how far it has gone
#: from it (``former_site``). ``NO_SITE`` for none.
R_FORMER_X = R_ESCAPE_UNTIL + 1
R_FORMER_Y = R_FORMER_X + 1
#: The lowest candidate an electing robot has heard in this election (``R_LEADER`` falls
#: back when entries age; this does not): an announcement of the epoch it elects for by
#: any other Leader is a sibling remnant's (``regeneration.from_sibling``).
R_ELECT_MIN = R_FORMER_Y + 1
#: 1 while a searcher's readings place it in a hole of its target (``hole_watch``).
R_INSIDE = R_ELECT_MIN + 1
#: A searcher's walk along the first formation's repository (``repository_gap``): its
#: phase, the lowest and highest queue ranks it followed and the odometric points where
#: it heard them, the tick it last heard a placed robot, and the tick its leap began.
R_GAP_PHASE = R_INSIDE + 1
R_GAP_LO = R_GAP_PHASE + 1
R_GAP_LO_X = R_GAP_LO + 1
R_GAP_LO_Y = R_GAP_LO_X + 1
R_GAP_TOP = R_GAP_LO_Y + 1
R_GAP_TOP_X = R_GAP_TOP + 1
R_GAP_TOP_Y = R_GAP_TOP_X + 1
R_GAP_SINCE = R_GAP_TOP_Y + 1
R_LEAP_SINCE = R_GAP_SINCE + 1
#: 1 while a searcher's plunge (``R_PLUNGE_UNTIL``) began in a notch's mouth, 0 when it
#: began at a site it could not confirm.
R_PLUNGE_MOUTH = R_LEAP_SINCE + 1
R_FIELDS = R_PLUNGE_MOUTH + 1

#: No site (a tag field that holds none: ``R_FORMER_X``, ``localise.find_site``'s left site).
NO_SITE = -(1 << 40)

PHASE_NORMAL = 0
PHASE_ELECTING = 1

SUB_FOLLOW = 0
SUB_SETTLE = 1

# Neighbour-table fields.
NB_ID = 0
NB_STATE = 1
NB_PREV = 2  # the state before the last change (-1: none seen)
NB_LAST = 3  # tick last heard
NB_TX = 4
NB_TY = 5
NB_TS = 6
NB_QRANK = NB_TS  # a Queued or searching robot's queue rank (bytes 3-4 of its status)
NB_RELEASED = 7  # a Queued or searching robot's count of robots released
NB_MASK = 8  # a placed robot's neighbour-occupancy bits
NB_EEPOCH = 9  # election: epoch being elected for (-1: no election message heard)
NB_ELEADER = 10  # election: lowest ID it has heard
NB_EHOP = 11  # election: its hops from that robot
NB_EPARENT = 12  # election: its parent
NB_ESUB = 13  # election: its subtree count
NB_ELAST = 14  # tick of its last election message
NB_EPOCH = 15  # the target epoch the robot works for (from its status message's type)
NB_HOPS = 16  # a Queued robot's hops to the target's placed robots (``release``)
NB_ANCHORED = 17  # byte 6 of a Queued or searching robot's status (see ``messages``)
NB_READINGS = 18  # readings averaged into nb_dist (both robots still since the first)
NB_OX = 19  # a placed robot's offset from its site's centre (``offsets``), x and y
NB_OY = 20
#: A placed robot found working for another target of the receiver's own epoch (a sibling
#: remnant's): its epoch + 1 when its held-sites message carried another target's
#: signature in that epoch (``controller.file_held``); 0 when not known so.
NB_OTHER = 21
NB_FIELDS = 22

SLOT_N = 0  # cells of the target
SLOT_LIMIT = 1  # robots the repository releases for it
SLOT_TX = 2  # translation of scale(bitmap, n) (tags)
SLOT_TY = 3
SLOT_USED = 4  # 1 when the slot holds a target
SLOT_WX = 5  # origin of the searchers' memory window (see ``site_memory``): least tag - 1
SLOT_WY = 6
SLOT_SHAPE = 7  # the first slot holding the same cells (the same target, wherever found)
SLOT_TURN = 8  # 60° turns of scale(bitmap, n) before the translation (``lattice.turn_cells``)
SLOT_SIG = 9  # ``messages.status_nibble`` of the target's signature (its n and placement)
SLOT_FIELDS = 10

#: Neighbour-table slots per robot (a lattice site has 6 neighbours and 6 at ~1.73 d).
NB_SLOTS = 16


def allocate(n_robots: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return zeroed ``(ri, nb, nb_dist)`` for ``n_robots`` robots, all Queued.

    Shapes: ri (N, R_FIELDS) int64, nb (N, NB_SLOTS, NB_FIELDS) int64 with NB_ID = -1
    (a view with the fields outermost per robot, see the module docstring), nb_dist
    (N, NB_SLOTS) float64.
    """
    ri = np.zeros((n_robots, R_FIELDS), dtype=np.int64)
    ri[:, R_STATE] = State.QUEUED
    ri[:, R_QMIN] = np.arange(n_robots)
    ri[:, R_FLOOR] = -1
    ri[:, R_YIELD_SINCE] = -1
    ri[:, R_BELOW_SINCE] = -1
    ri[:, R_REF_ID] = -1
    ri[:, R_FROM_ID] = -1
    ri[:, R_RECENT0 : R_RECENT0 + RECENT_REFS] = -1
    ri[:, R_YLD_ID] = -1
    ri[:, R_PARENT] = -1
    ri[:, R_PEND_EPOCH] = -1
    ri[:, R_CANDIDATE] = 1
    ri[:, R_WALK_SEEN] = -(1 << 40)
    ri[:, R_WATCH_ID0] = -1
    ri[:, R_WATCH_ID1] = -1
    ri[:, R_WATCH_T0] = -(1 << 40)
    ri[:, R_WATCH_T1] = -(1 << 40)
    ri[:, R_FORMER_X] = NO_SITE
    ri[:, R_FORMER_Y] = NO_SITE
    nb = np.zeros((n_robots, NB_FIELDS, NB_SLOTS), dtype=np.int64).transpose(0, 2, 1)
    nb[:, :, NB_ID] = -1
    nb[:, :, NB_PREV] = -1
    nb[:, :, NB_EEPOCH] = -1
    nb_dist = np.zeros((n_robots, NB_SLOTS), dtype=np.float64)
    return ri, nb, nb_dist
