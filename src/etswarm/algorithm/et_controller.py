"""The ET controller packaged for the simulator: kernel, robot memory and the gene.

``ETController`` owns the arrays of every robot's private memory (see ``memory``) and the
gene grids, and exposes them as the ``mem`` tuple the compiled ``et_step`` receives. The
host side of regeneration lives here too: a Leader's request for ``scale(bitmap, n)``
is answered by storing the scaled gene in a target slot (the robots' on-board computation,
memoised).
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.controller import et_part, et_rest, et_step, slot_signature
from etswarm.algorithm.layout import Layout
from etswarm.algorithm.memory import (
    HOLE_FLAG,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_EPOCH,
    R_FLOOR_SINCE,
    R_HAS_TAG,
    R_HELD_EPOCH,
    R_NEWSLOT,
    R_NN,
    R_QMIN_SINCE,
    R_REQUEST,
    R_SINCE,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    R_TSLOT,
    R_WALK,
    SLOT_FIELDS,
    SLOT_SHAPE,
    SLOT_SIG,
    SLOT_WX,
    SLOT_WY,
    allocate,
)
from etswarm.algorithm.messages import status_nibble
from etswarm.algorithm.params import (
    C_FIRST_PLUNGE,
    C_HOLE_WATCH,
    C_RIM_WAVE,
    C_WAVE,
    C_WAY_PLUNGE,
    F_PORTABLE_MATH,
    NOMINAL_MOTION,
    ETParams,
)
from etswarm.algorithm.states import PLACED_STATES, State
from etswarm.algorithm.wave import HOPS_SHIFT, nn_of, rim_hops, seed_hops
from etswarm.shapes.lattice import depths, enclosed_cells, neighbour_counts, sort_cells

#: Target slots allocated at first (more are added when regenerations need them).
INITIAL_SLOTS = 8


class ETController:
    """The ET controller in the simulator's fast-path form: ``step`` (also split into
    ``part_step`` and ``rest_step``) and ``mem``.

    Holds every robot's private memory and the gene grids of the targets (slot 0: the
    original shape; later slots: scaled shapes asked for by Leaders). The grids span the
    original's tags with a margin of one shape size on every side, so a scaled shape can
    be placed anywhere around the original frame.
    """

    step = staticmethod(et_step)
    #: The step split for the simulator's threaded loop (``SimParams.threads > 1``): the
    #: per-robot work on every thread (:func:`~etswarm.algorithm.controller.et_part`), and
    #: a rest on one thread that has nothing left to do.
    part_step = staticmethod(et_part)
    rest_step = staticmethod(et_rest)

    def __init__(
        self,
        n_robots: int,
        target: np.ndarray,
        et: ETParams,
        ticks_per_s: int,
        nominal_motion: tuple[float, float, float, float] = NOMINAL_MOTION,
        portable_math: bool = True,
    ):
        """``nominal_motion``: the robot model the searchers' odometry assumes (see
        ``ETParams.pack``); ``portable_math``: their odometry and homing use
        ``sim.fpmath`` (``SimParams.portable_math``)."""
        self.ri, self.nb, self.nb_dist = allocate(n_robots)
        # Per robot, the tick until which it sleeps unless it hears something new (0: awake;
        # see ``controller.et_part``). A host that edits a robot's memory must wake it.
        self.idle = np.zeros(n_robots, dtype=np.int64)
        self.stop = np.zeros(1, dtype=np.int64)
        self.et = et
        self.ticks_per_s = ticks_per_s
        target = np.asarray(target, dtype=np.int64)
        lo = target.min(axis=0)
        hi = target.max(axis=0)
        span = hi - lo + 1
        self.x0 = int(lo[0] - span[0] - 1)
        self.y0 = int(lo[1] - span[1] - 1)
        self.grid_shape = (int(3 * span[0] + 2), int(3 * span[1] + 2))
        self.gene_flag = np.zeros((INITIAL_SLOTS, *self.grid_shape), dtype=np.uint8)
        self.gene_nn = np.zeros((INITIAL_SLOTS, *self.grid_shape), dtype=np.int16)
        self.slot_info = np.zeros((INITIAL_SLOTS, SLOT_FIELDS), dtype=np.int64)
        self.slot_cells: list[np.ndarray] = []
        self.ci, self.cf = et.pack(
            ticks_per_s, self.x0, self.y0, diameter_hops=int(span.sum()),
            nominal_motion=nominal_motion, shape_depth=int(depths(target).max(initial=0)),
            shape_cells=len(target),
        )
        self.cf[F_PORTABLE_MATH] = 1.0 if portable_math else 0.0
        # The hole watch costs every placed robot a look round each evaluation: it runs
        # only once a target with a hole has been stored (``add_target``).
        self.hole_watch_ticks = int(self.ci[C_HOLE_WATCH])
        self.ci[C_HOLE_WATCH] = 0
        # Each robot's bitmap of the tags it collected on a census walk (only Leaders use
        # it; a placeholder when the census is by spanning tree).
        walk_grid = self.grid_shape if et.census == "walk" else (1, 1)
        self.walk_seen = np.zeros((n_robots, *walk_grid), dtype=np.uint8)
        # Each searcher's memory of the sites it heard held (see ``site_memory``): a window
        # of the original's extent plus one site round it (scaled targets are smaller).
        held_grid = (int(span[0] + 2), int(span[1] + 2)) if et.hole_memory == "on" else (1, 1)
        self.held = np.zeros((n_robots, *held_grid), dtype=np.uint8)
        self.add_target(target, release_limit=max(0, len(target) - 3), tx=0, ty=0)

    # -- targets -----------------------------------------------------------------------
    def fits(self, cells: np.ndarray) -> bool:
        """True when every tag of ``cells`` lies inside the gene grids."""
        gx = cells[:, 0] - self.x0
        gy = cells[:, 1] - self.y0
        return bool(
            np.all((gx >= 0) & (gy >= 0) & (gx < self.grid_shape[0]) & (gy < self.grid_shape[1]))
        )

    def add_target(
        self, cells: np.ndarray, release_limit: int, tx: int, ty: int, turn: int = 0
    ) -> int:
        """Store the gene of ``cells`` ((P, 2) tags: scale(bitmap, n) turned ``turn`` times
        and translated by (tx, ty)) in a new slot; return the slot."""
        slot = len(self.slot_cells)
        if slot == self.slot_info.shape[0]:
            grow = self.slot_info.shape[0]
            self.gene_flag = np.concatenate([self.gene_flag, np.zeros_like(self.gene_flag)])
            self.gene_nn = np.concatenate([self.gene_nn, np.zeros_like(self.gene_nn)])
            self.slot_info = np.concatenate(
                [self.slot_info, np.zeros((grow, SLOT_FIELDS), dtype=np.int64)]
            )
        cells = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
        window = (0, 0)
        if len(cells):
            lo = cells.min(axis=0) - 1
            window = (int(lo[0]), int(lo[1]))
            gx = cells[:, 0] - self.x0
            gy = cells[:, 1] - self.y0
            self.gene_flag[slot, gx, gy] = 1
            if self.et.hole_flag == "on":
                holes = enclosed_cells(cells)
                self.gene_flag[slot, holes[:, 0] - self.x0, holes[:, 1] - self.y0] = HOLE_FLAG
                if len(holes):
                    self.ci[C_HOLE_WATCH] = self.hole_watch_ticks
            self.gene_nn[slot, gx, gy] = neighbour_counts(cells)
        self.slot_info[slot] = (len(cells), release_limit, tx, ty, 1, *window, slot, turn, 0)
        # what each robot of the target works out from the announcement it heard
        self.slot_info[slot, SLOT_SIG] = status_nibble(slot_signature(slot, self.slot_info))
        key = sort_cells(cells)
        for other, other_cells in enumerate(self.slot_cells):
            if np.array_equal(sort_cells(other_cells), key):
                self.slot_info[slot, SLOT_SHAPE] = self.slot_info[other, SLOT_SHAPE]
                break
        self.slot_cells.append(cells)
        return slot

    @property
    def target(self) -> np.ndarray:
        """(P, 2) tags of the original target (slot 0)."""
        return self.slot_cells[0]

    @property
    def mem(self) -> tuple:
        return (
            self.stop,
            self.ri,
            self.nb,
            self.nb_dist,
            self.gene_flag,
            self.gene_nn,
            self.slot_info,
            self.ci,
            self.cf,
            self.walk_seen,
            self.held,
            self.idle,
        )

    def seed(self, layout: Layout) -> None:
        """Initialise the seeds (paper: one Active TS 1, two Inactive TS 2)."""
        ri = self.ri
        ri[:, R_FLOOR_SINCE] = -(10**9)
        ri[:, R_QMIN_SINCE] = 0
        for k, (rid, (x, y)) in enumerate(zip(layout.seed_ids, layout.seed_tags, strict=True)):
            ri[rid, R_STATE] = State.ACTIVE if k == 0 else State.INACTIVE
            ri[rid, R_TS] = 1 if k == 0 else 2
            ri[rid, R_TAG_X] = x
            ri[rid, R_TAG_Y] = y
            ri[rid, R_NN] = nn_of(self.gene_nn[0, x - self.x0, y - self.y0])
            ri[rid, R_HAS_TAG] = 1
            ri[rid, R_SINCE] = 0
        self.idle[:] = 0
        cells = self.slot_cells[0]
        if len(enclosed_cells(cells)):
            # A ring's two fronts meet wherever they meet; waiting for the sites nearer
            # the seeds formed O less often (103 of 200 runs against 118): the hole watch
            # rules there. Plunging into a ring's inner rim formed O 26 of 60 times
            # against 31. The rim wave (``rim_wave_s``) grows the ring from its hole out.
            self.ci[C_WAVE] = self.ci[C_RIM_WAVE]
            self.ci[C_FIRST_PLUNGE] = 0
        else:
            self.ci[C_RIM_WAVE] = 0
            self.ci[C_WAY_PLUNGE] = 0
        if self.ci[C_WAVE] > 0:
            hops = (
                rim_hops(cells) if self.ci[C_RIM_WAVE] > 0
                else seed_hops(cells, np.asarray(layout.seed_tags))
            )
            self.gene_nn[0, cells[:, 0] - self.x0, cells[:, 1] - self.y0] += (
                hops << HOPS_SHIFT
            ).astype(np.int16)

    # -- what robots report ----------------------------------------------------------------
    @property
    def states(self) -> np.ndarray:
        """(N,) int64 state codes."""
        return self.ri[:, R_STATE]

    @property
    def tags(self) -> np.ndarray:
        """(N, 2) int64 tags (meaningful where the robot is placed)."""
        return self.ri[:, [R_TAG_X, R_TAG_Y]]

    @property
    def holds_site(self) -> np.ndarray:
        """(N,) bool: the robot stands on the site of its tag. That is a robot in a placed
        state (``PLACED_STATES``) that took or kept a site (``R_HAS_TAG``): a searcher an
        election flood pulls into Danger keeps its candidate in its tag fields, but holds
        no site."""
        placed = np.isin(self.ri[:, R_STATE], [int(s) for s in PLACED_STATES])
        return placed & (self.ri[:, R_HAS_TAG] == 1)

    def pending_requests(self) -> np.ndarray:
        """IDs of Leaders waiting for their scaled target (R_REQUEST == 1)."""
        return np.flatnonzero(self.ri[:, R_REQUEST] == 1)

    def known_tags(self, i: int, since_tick: int) -> set[tuple[int, int]]:
        """Tags robot ``i`` knows to be held: its own, those of the placed robots in its
        table heard since ``since_tick``, and those it collected on a census walk."""
        known = {(int(self.ri[i, R_TAG_X]), int(self.ri[i, R_TAG_Y]))}
        if self.walk_seen.shape[1:] == self.grid_shape and self.ri[i, R_WALK] != 0:
            gx, gy = np.nonzero(self.walk_seen[i])
            known.update(zip((gx + self.x0).tolist(), (gy + self.y0).tolist(), strict=True))
        for row in self.nb[i]:
            if row[NB_ID] >= 0 and row[NB_STATE] >= State.INACTIVE and row[NB_LAST] >= since_tick:
                known.add((int(row[NB_TX]), int(row[NB_TY])))
        return known

    def remembered_tags(self, i: int) -> set[tuple[int, int]]:
        """Tags robot ``i``'s memory of held sites (``site_memory``) holds for the target it
        works for (empty if its memory is of another epoch)."""
        if self.ri[i, R_HELD_EPOCH] != self.ri[i, R_EPOCH] + 1:
            return set()
        slot = int(self.ri[i, R_TSLOT])
        ox, oy = int(self.slot_info[slot, SLOT_WX]), int(self.slot_info[slot, SLOT_WY])
        gx, gy = np.nonzero(self.held[i])
        return set(zip((gx + ox).tolist(), (gy + oy).tolist(), strict=True))

    def answer(
        self, leader: int, cells: np.ndarray, n: int, tx: int, ty: int, turn: int = 0
    ) -> int:
        """Give Leader ``leader`` its scaled target (``cells`` already turned ``turn`` times
        and translated)."""
        from etswarm.algorithm.regeneration import TURN_CODE, find_slot

        code = n + TURN_CODE * turn
        slot = find_slot(self.slot_info, code, tx, ty) if len(self.slot_cells) > 1 else -1
        if slot < 0:
            slot = self.add_target(cells, release_limit=len(cells), tx=tx, ty=ty, turn=turn)
        self.ri[leader, R_NEWSLOT] = slot
        self.ri[leader, R_REQUEST] = 2
        self.idle[leader] = 0  # its memory changed (a Leader never sleeps; to be sure)
        return slot
