"""One ET run: a shape, a swarm on the simulator, the ET controller, and its measures.

``ETRun`` sets up the experiment (layout, seeds, robot memory), advances the simulator in
chunks, watches the measures from outside (the robots never see them) and produces the
JSON summary of ``etswarm run --json``.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, replace
from typing import Any

import numpy as np

from etswarm.algorithm.census_walk import RESULT_NAMES
from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.extent import cells_in, extent_of
from etswarm.algorithm.layout import LONG_QUEUE_ROBOTS, REPOSITORY_SPACING_MM, plan_layout
from etswarm.algorithm.memory import (
    PHASE_NORMAL,
    R_CENSUS,
    R_ELECT_SINCE,
    R_EPOCH,
    R_PHASE,
    R_SINCE,
    R_TAG_X,
    R_TAG_Y,
    R_TSLOT,
    R_WALK_END,
    R_WALK_RESULT,
    R_WALK_TAGS,
    SLOT_N,
    SLOT_SHAPE,
    SLOT_TURN,
    SLOT_TX,
    SLOT_TY,
)
from etswarm.algorithm.params import C_TICKS_GAP, ETParams
from etswarm.algorithm.placement import RemnantView, choose_placement, holds_a_pair
from etswarm.algorithm.regeneration import turns_coded
from etswarm.algorithm.silent import enclosed_tags, silent_tags
from etswarm.algorithm.states import STATE_NAMES, State
from etswarm.damage import DamageSpec, apply_damage, parse_damage
from etswarm.errors import EtswarmError
from etswarm.measures.formation import (
    apply_fit,
    components,
    duplicate_tags,
    free_sites,
    is_formed,
    jaccard,
    placement_error_mm,
    rigid_fit,
    shut_in_holes,
    stretched_links,
    way_across,
)
from etswarm.seeding import stream
from etswarm.shapes import load_shape, scale
from etswarm.shapes.lattice import tags_to_xy, turn_cells
from etswarm.sim import Simulator
from etswarm.sim.params import SimParams
from etswarm.sim.world import World

#: Ticks per measurement check while running (10 simulated seconds).
CHECK_EVERY_TICKS = 310
#: A component's report lists at most this many of its free target sites.
FREE_SITES_SHOWN = 20


@dataclass(frozen=True)
class RunConfig:
    """What ``etswarm run`` takes. Times in simulated seconds, lengths in mm."""

    shape: str = "T"
    robots: int | None = None
    seed: int = 0
    loss: float = 0.2
    noise_mm: float = 2.0
    max_time_s: float = 3 * 3600.0
    layout: str = "queue"
    fit: bool = False
    damage: tuple[str, ...] = ()
    et: ETParams = field(default_factory=ETParams)
    #: Census method ("tree" or "walk"); None: the one in ``et``. Given, it replaces
    #: ``et.census``; after construction it always names the method in use.
    census: str | None = None

    def __post_init__(self) -> None:
        if self.census is None:
            object.__setattr__(self, "census", self.et.census)
        elif self.census != self.et.census:
            object.__setattr__(self, "et", replace(self.et, census=self.census))
        if not 0.0 <= self.loss < 1.0:
            raise EtswarmError(f"--loss must be in [0, 1), got {self.loss}")
        if self.noise_mm < 0:
            raise EtswarmError(f"--noise must be >= 0 mm, got {self.noise_mm}")
        if self.max_time_s <= 0:
            raise EtswarmError(f"--max-time must be > 0 s, got {self.max_time_s}")
        if self.seed < 0:
            raise EtswarmError(f"--seed must be >= 0, got {self.seed}")
        if self.robots is not None and self.robots < 3:
            raise EtswarmError(f"--robots must be at least 3 (the seeds), got {self.robots}")
        for spec in self.damage:
            parse_damage(spec)


class ETRun:
    """A configured ET experiment on the simulator."""

    def __init__(self, config: RunConfig, sim_params: SimParams | None = None) -> None:
        self.config = config
        self.shape = load_shape(config.shape)
        cells = self.shape.cells
        n = config.robots if config.robots is not None else len(cells)
        self.notes: list[str] = []
        if n < len(cells):
            if config.fit:
                cells = scale(self.shape, max(3, n))
                self.notes.append(
                    f"{n} robots for {self.shape.n_cells} cells: forming the scaled shape "
                    f"of {len(cells)} cells (--fit)"
                )
            else:
                self.notes.append(
                    f"{n} robots for {self.shape.n_cells} cells: the shape cannot be completed; "
                    "forming what the robots can (use --fit to form a scaled shape)"
                )
        elif n > len(cells):
            self.notes.append(f"{n - len(cells)} extra robots will stay Queued")
        self.target = cells
        base = sim_params or SimParams()
        self.sim_params = SimParams(
            **{**asdict(base), "loss": config.loss, "dist_noise_mm": config.noise_mm}
        )
        self.layout = plan_layout(
            cells,
            n,
            layout=config.layout,
            spacing_mm=config.et.spacing_mm,
            rng=stream(config.seed, "placement"),
            portable=self.sim_params.portable_math,
        )
        if config.layout == "queue" and n - 3 > LONG_QUEUE_ROBOTS:
            queue_m = (n - 3) * REPOSITORY_SPACING_MM / 1000.0
            self.notes.append(
                f"the queue of {n - 3} robots is {queue_m:.1f} m long; searchers lose their way "
                "along a queue that long and large shapes seldom form (--layout cluster "
                "packs the repository beside the shape)"
            )
        self.world = World.from_positions(
            self.layout.pos, self.layout.heading, self.sim_params, config.seed
        )
        sp = self.sim_params
        self.controller = ETController(
            n, cells, config.et, sp.ticks_per_s,
            nominal_motion=(sp.speed_mm_s, sp.turn_rate_deg_s, sp.leg_angle_deg, sp.body_radius_mm),
            portable_math=sp.portable_math,
        )
        if config.layout != "queue":
            # Robots programmed for a packed repository: no queue's line to leap along, and
            # the ranks of a cluster climb and fall all round it (``repository_gap``).
            self.controller.ci[C_TICKS_GAP] = 0
        self.controller.seed(self.layout)
        self.sim = Simulator(self.world, self.controller, self.sim_params, config.seed)
        self.damage_rng = stream(config.seed, "damage")
        self.pending_damage: list[DamageSpec] = [parse_damage(d) for d in config.damage]
        self.events: list[dict[str, Any]] = []
        self.formed_at_s: float | None = None
        self.settled_at_s: float | None = None
        self.last_damage_s: float | None = None
        self.reformed_at: dict[int, float] = {}
        #: Every census so far, in the order the Leaders asked for their targets.
        self.censuses: list[dict[str, Any]] = []
        #: (N,) index into ``censuses`` of the last census that counted each robot (the
        #: robot was in its Leader's radio group then); -1: none yet.
        self.counted_in = np.full(self.world.n, -1, dtype=np.int64)
        self._detected_for: float | None = -1.0
        self._target_sizes: dict[int, int] = {}  # distinct tags per target slot (_check)
        self.wall_s = 0.0
        #: Optional :class:`etswarm.sim.recorder.Recorder`, fed at every measure check.
        self.recorder: Any = None

    # -- clock -------------------------------------------------------------------------
    @property
    def ticks_per_s(self) -> int:
        return self.sim_params.ticks_per_s

    @property
    def sim_time_s(self) -> float:
        return self.world.tick / self.ticks_per_s

    def _event(self, kind: str, **fields: Any) -> None:
        self.events.append({"t_s": round(self.sim_time_s, 3), "kind": kind, **fields})

    def _next_damage_tick(self) -> int | None:
        """Tick at which the next pending damage is due (None: waits for formation)."""
        if not self.pending_damage:
            return None
        spec = self.pending_damage[0]
        if spec.at_formed:
            if self.settled_at_s is None:
                return None
            return round((self.settled_at_s + spec.at_s) * self.ticks_per_s)
        return round(spec.at_s * self.ticks_per_s)

    def advance(self, ticks: int) -> None:
        """Run ``ticks`` ticks: answer Leaders' requests, apply due damage, and check the
        measures every ``CHECK_EVERY_TICKS`` ticks of the world clock (so the run does not
        depend on how a caller splits its calls)."""
        end = self.world.tick + ticks
        t0 = time.perf_counter()
        while self.world.tick < end:
            due = self._next_damage_tick()
            if due is not None and due <= self.world.tick:
                self._apply_next_damage()
                continue
            next_check = (self.world.tick // CHECK_EVERY_TICKS + 1) * CHECK_EVERY_TICKS
            stop_at = min(end, next_check) if due is None else min(end, next_check, due)
            self.sim.run_ticks(stop_at - self.world.tick)
            if self.controller.stop[0]:
                self._answer_requests()
            if self.world.tick == next_check:
                self._check()
        self.wall_s += time.perf_counter() - t0

    def _apply_next_damage(self) -> None:
        spec = self.pending_damage.pop(0)
        self.apply_damage(spec)

    def apply_damage(self, spec: DamageSpec) -> np.ndarray:
        """Apply ``spec`` now (whatever its time); return the IDs affected."""
        ids = apply_damage(spec, self.world, self.config.et.spacing_mm, self.damage_rng)
        self.record_damage(spec.text, len(ids))
        return ids

    def record_damage(self, text: str, robots: int) -> None:
        """Note a damage done to the world (by a spec, or by hand in the viewer)."""
        self.last_damage_s = self.sim_time_s
        self.settled_at_s = None
        self.reformed_at.clear()
        self._event("damage", spec=text, robots=int(robots))

    def _answer_requests(self) -> None:
        """Host side of a Leader's on-board ``scale(bitmap, n)`` and placement choice."""
        ctl = self.controller
        tps = self.ticks_per_s
        for leader in ctl.pending_requests():
            row = ctl.ri[leader]
            n = int(row[R_CENSUS])
            group = self._remnant_of(int(leader))
            cells, tx, ty, turn = self._scaled_placement(int(leader), n)
            old_slot = int(row[R_TSLOT])
            slot = ctl.answer(int(leader), cells, n, tx, ty, turn)
            kept = ctl.slot_info[slot, SLOT_SHAPE] == ctl.slot_info[old_slot, SLOT_SHAPE]
            # The robot's clock: election began, Leader declared, census concluded.
            elected_s = int(row[R_SINCE]) / tps
            done_s = int(row[R_WALK_END]) / tps
            self._event_at(elected_s, "leader", robot=int(leader))
            census = {
                "leader": int(leader),
                "count": n,
                "robots": len(group),
                "method": self.config.census,
                "result": RESULT_NAMES[int(row[R_WALK_RESULT])],
                "duration_s": round(done_s - elected_s, 3),
                "since_election_s": round(done_s - int(row[R_ELECT_SINCE]) / tps, 3),
            }
            if self.config.census == "walk":
                census["tags"] = int(row[R_WALK_TAGS])
            self.counted_in[group] = len(self.censuses)
            self.censuses.append(census)
            self._event("census", **census, slot=slot)
            if kept and self.config.et.false_alarm == "resume":
                self._event("target_kept", leader=int(leader), slot=slot)
        ctl.stop[0] = 0

    def _event_at(self, t_s: float, kind: str, **fields: Any) -> None:
        """Record an event that happened at ``t_s`` (in time order among the events)."""
        event = {"t_s": round(t_s, 3), "kind": kind, **fields}
        at = len(self.events)
        while at > 0 and self.events[at - 1]["t_s"] > event["t_s"]:
            at -= 1
        self.events.insert(at, event)

    def _scaled_placement(self, leader: int, n: int) -> tuple[np.ndarray, int, int, int]:
        """scale(bitmap, n), turned and translated as the Leader chooses on board
        (``placement.choose_placement``; (cells, tx, ty, turn)): on a seed triangle, the
        Leader's own if it can, over as much of the remnant as it knows of, and off the
        sites that fell silent (a dead robot may stand there, see ``silent``). Empty when
        n < 3, or when it keeps no two robots that are lattice neighbours: too small to
        seed. With ``false_alarm`` "resume", a census n equal to the
        cell count of the Leader's current target keeps that target, its turn and its
        translation (a false alarm)."""
        if n < 3:
            return np.zeros((0, 2), dtype=np.int64), 0, 0, 0
        ctl = self.controller
        slot = int(ctl.ri[leader, R_TSLOT])
        if self.config.et.false_alarm == "resume" and n == int(ctl.slot_info[slot, SLOT_N]):
            # As many robots as the target it has: nothing was lost, keep it where it is.
            # (More robots than that elect as before: a remnant with spare robots may have
            # lost some of its sites, and the spares would not be released for them.)
            tx, ty = int(ctl.slot_info[slot, SLOT_TX]), int(ctl.slot_info[slot, SLOT_TY])
            return ctl.slot_cells[slot], tx, ty, int(ctl.slot_info[slot, SLOT_TURN])
        cells = scale(self.shape, min(n, self.shape.n_cells))
        lx, ly = (int(v) for v in ctl.ri[leader, [R_TAG_X, R_TAG_Y]])
        # Robots heard since the election began are the remnant's; older entries left.
        known = ctl.known_tags(leader, int(ctl.ri[leader, R_ELECT_SINCE]))
        silent = silent_tags(ctl.ri, leader) - known
        # silent sites with live robots round them: robots killed or removed inside the
        # remnant (a dead one still stands there), not cut off along a split's edge
        old_cells = np.asarray(ctl.slot_cells[int(ctl.ri[leader, R_TSLOT])]).reshape(-1, 2)
        old_shape = {(int(x), int(y)) for x, y in old_cells.tolist()}
        enclosed = enclosed_tags(ctl.ri, leader, old_shape) - known
        # The remnant's hexagon of tags, flooded while electing (``extent``), and the sites
        # in it the Leader remembers held (``site_memory``), less the sites it learnt fell
        # silent: nobody of the remnant holds those. Only with held-site gossip: without
        # it only searchers keep a memory, of what they heard on their way, and the
        # hexagon alone misleads where the remnant does not fill it (bigdisc seed 0, an
        # election with no damage and the shape half built: it shifted the whole shape
        # by two sites), so nothing is flooded then (``ETParams.pack``). None: the local
        # placement.
        extent = extent_of(ctl.ri, leader)
        remnant: set[tuple[int, int]] = set()
        if extent is not None:
            remembered = sorted((ctl.remembered_tags(leader) | known) - silent)
            inside = cells_in(np.array(remembered).reshape(-1, 2), extent)
            remnant = {t for t, keep in zip(remembered, inside, strict=True) if keep}
        off_shape = self.config.et.placement_off_shape
        view = RemnantView(known, remnant, silent, enclosed, extent, ctl.fits,
                           frozenset(old_shape) if off_shape != "any" else frozenset(),
                           off_shape == "weigh")
        et = self.config.et
        # A shape too large for a turn in its target code is never turned.
        turns = et.placement_turns == "on" and bool(turns_coded(ctl.slot_info))
        chosen = choose_placement(cells, (lx, ly), view, et.placement_seeds, turns)
        if chosen is None:
            return cells, 0, 0, 0
        turn, tx, ty = chosen
        placed = turn_cells(cells, turn) + np.array([tx, ty])
        kept = {(int(x), int(y)) for x, y in placed.tolist()} & (known | remnant | {(lx, ly)})
        if not holds_a_pair(kept):
            # No two robots it keeps are neighbours (T split x=0 seed 4: three robots a
            # second-ring step apart, about 70 mm): a searcher cannot locate a site from one
            # robot, so nothing would grow. Too small to seed, as with n < 3.
            return np.zeros((0, 2), dtype=np.int64), 0, 0, 0
        return placed, tx, ty, turn

    def _radio_group_of(self, robot: int) -> np.ndarray:
        """IDs of the live robots radio-connected to ``robot`` now."""
        live = self.world.present & self.world.alive
        for group in components(self.world.pos, live, self.sim_params.comm_range_mm):
            if robot in group:
                return group
        return np.array([robot])

    def _remnant_of(self, leader: int) -> np.ndarray:
        """IDs of the robots a declaring Leader's census should count: the live robots
        radio-connected to it, less those that already work for a target of the epoch it
        elected for. Those belong to a sibling remnant of the same damage that elected
        first, and one of its robots has come within range (`T` `remove random=0.2`
        seed 10: a searcher of a 3-robot remnant beside the 33-robot one)."""
        group = self._radio_group_of(leader)
        ri = self.controller.ri
        elected_for = ri[leader, R_EPOCH] + 1
        sibling = (ri[group, R_EPOCH] == elected_for) & (ri[group, R_PHASE] == PHASE_NORMAL)
        return group[~sibling]

    def _too_small_slots(self) -> np.ndarray:
        """(S,) bool per target slot: the empty target of a remnant too small to regrow
        (slot 0, the first target, never is)."""
        return np.array([s > 0 and len(c) == 0 for s, c in enumerate(self.controller.slot_cells)])

    def _groups(self) -> list[np.ndarray]:
        """The remnants, as arrays of robot IDs, largest first: radio-connected groups of
        live robots working for the same target slot, and those of a remnant too small
        to regrow (one empty slot for all of them) apart by the census that counted them.
        A remnant that regrows to within radio range of another without merging with it
        stays a remnant of its own: counted into the half regrown beside it, a robot the
        cut left alone made that half's census look one short (traced on the demo's `T`
        seed 7), and a 3-robot remnant beside the other half (seed 15, `wave_s=1200`)
        looked formed while it was not."""
        live = self.world.present & self.world.alive
        slots = self.controller.ri[:, R_TSLOT]
        empty = self._too_small_slots()[slots]
        keys = np.where(empty, len(self.controller.slot_cells) + 1 + self.counted_in, slots)
        radius = self.sim_params.comm_range_mm
        groups = [
            group
            for k in np.unique(keys[live])
            for group in components(self.world.pos, live & (keys == k), radius)
        ]
        return sorted(groups, key=lambda g: (-len(g), int(g[0])))

    def _check(self) -> None:
        if self.recorder is not None:
            self.recorder.capture()
        states = self.controller.states
        danger = np.flatnonzero(states == State.DANGER)
        if len(danger) and self._detected_for != self.last_damage_s:
            self._detected_for = self.last_damage_s
            self._event("detected", robots=len(danger))
        if not self._may_settle():
            return  # no remnant can be formed or too small: nothing to note
        comps = self._check_report()
        for comp in comps:
            slot = comp["slot"]
            if comp["formed"] and slot not in self.reformed_at:
                self.reformed_at[slot] = self.sim_time_s
                first = self._is_first_target(slot)
                if first and self.formed_at_s is None:
                    self.formed_at_s = self.sim_time_s
                    self._event("formed", cells=comp["target_cells"])
                elif not first:
                    self._event("reformed", slot=slot, cells=comp["target_cells"])
        if (
            self.settled_at_s is None
            and comps
            and all(c["formed"] or c["too_small"] for c in comps)
        ):
            self.settled_at_s = self.sim_time_s

    def _is_first_target(self, slot: int) -> bool:
        """Target ``slot`` is the run's first: the original (slot 0), or, before any
        damage, a slot with its cells (kept by a false alarm, see ``ETParams.false_alarm``)."""
        info = self.controller.slot_info
        return slot == 0 or (
            self.last_damage_s is None and info[slot, SLOT_SHAPE] == info[0, SLOT_SHAPE]
        )

    def _target_size(self, slot: int) -> int:
        """Distinct tags of target ``slot``'s cells (targets never change once stored)."""
        size = self._target_sizes.get(slot)
        if size is None:
            cells = self.controller.slot_cells[slot]
            size = len({(int(x), int(y)) for x, y in np.asarray(cells).reshape(-1, 2)})
            self._target_sizes[slot] = size
        return size

    def _may_settle(self) -> bool:
        """False when no remnant can be formed or too small now, so that the full check
        (:meth:`_check_report`) would find nothing: a remnant is formed only when every
        tag of its target is held by one of its Stable robots, so it has at least that
        many Stable robots, and it is too small only with an empty scaled target. The
        remnant's target is the slot most of its robots work for, one of the slots the
        live robots work for; so when no such slot is empty and the live Stable robots
        are fewer than the least target of those slots, none is either."""
        live = self.world.present & self.world.alive
        if not live.any():
            return False
        slots = np.unique(self.controller.ri[live, R_TSLOT])
        least = min(self._target_size(int(slot)) for slot in slots)
        if least == 0:
            return True
        stable = int(np.count_nonzero(live & (self.controller.states == State.STABLE)))
        return stable >= least

    def _check_report(self) -> list[dict[str, Any]]:
        """What :meth:`_check` needs of :meth:`component_report` (per group: its slot,
        target size, formed, too small), without the measures it does not use."""
        holds, stable = self._masks()
        tags = self.controller.tags
        too_small = self._too_small_slots()
        report = []
        for group in self._groups():
            slot = self._slot_of(group)
            target = self.controller.slot_cells[slot]
            formed = False
            if len(target) > 0 and int(np.count_nonzero(stable[group])) >= self._target_size(slot):
                member = np.zeros(self.world.n, dtype=bool)
                member[group] = True
                formed = is_formed(tags, holds & member, stable & member, target)
            report.append(
                {
                    "target_cells": len(target),
                    "formed": bool(formed),
                    "too_small": bool(too_small[slot]),
                    "slot": slot,
                }
            )
        return report

    @property
    def finished(self) -> bool:
        """Settled (every remnant formed or too small) and no damage left to apply."""
        return self.settled_at_s is not None and not self.pending_damage

    def run(self, progress=None) -> dict[str, Any]:  # type: ignore[no-untyped-def]
        """Advance until every remnant formed after the last damage, or ``max_time_s``."""
        max_ticks = round(self.config.max_time_s * self.ticks_per_s)
        while not self.finished and self.world.tick < max_ticks:
            step = min(CHECK_EVERY_TICKS, max_ticks - self.world.tick)
            self.advance(step)
            if progress is not None:
                progress(self)
        return self.summary()

    # -- measures -----------------------------------------------------------------------
    def _masks(self) -> tuple[np.ndarray, np.ndarray]:
        states = self.controller.states
        live = self.world.present & self.world.alive
        holds = live & self.controller.holds_site
        stable = live & (states == State.STABLE)
        return holds, stable

    def formed(self) -> bool:
        """Every remnant holds its current target with Stable robots, no tag twice."""
        comps = self.component_report()
        return bool(comps) and all(c["formed"] for c in comps)

    def _slot_of(self, group: np.ndarray) -> int:
        """The target slot most robots of ``group`` (IDs) work for."""
        return int(np.bincount(self.controller.ri[group, R_TSLOT]).argmax())

    def component_report(self) -> list[dict[str, Any]]:
        """Per radio-connected group of working robots: its target and how it stands."""
        holds, stable = self._masks()
        tags = self.controller.tags
        states = self.controller.states
        pos = self.world.pos
        d = self.config.et.spacing_mm
        report = []
        for group in self._groups():
            member = np.zeros(self.world.n, dtype=bool)
            member[group] = True
            slot = self._slot_of(group)
            target = self.controller.slot_cells[slot]
            counted = int(self.counted_in[group].max())
            census = self.censuses[counted] if counted >= 0 else None
            too_small = bool(self._too_small_slots()[slot])
            g_holds = holds & member
            g_formed = len(target) > 0 and is_formed(tags, g_holds, stable & member, target)
            start = 0.0 if self._is_first_target(slot) else (self.last_damage_s or 0.0)
            done = self.reformed_at.get(slot)
            if g_formed and done is None:
                done = self.sim_time_s
            free = free_sites(tags, g_holds, target) if len(target) else []
            g_err = placement_error_mm(pos[group], tags[group], holds[group], d)
            report.append(
                {
                    "robots": len(group),
                    "target_cells": len(target),
                    "formed": bool(g_formed),
                    "jaccard": round(jaccard(tags, g_holds, target), 6) if len(target) else None,
                    "census_count": None if census is None else census["count"],
                    "time_to_stable_s": None if done is None else round(done - start, 3),
                    "too_small": bool(too_small),
                    "slot": slot,
                    # Why a remnant is not formed: the sites still free (at most
                    # FREE_SITES_SHOWN of them listed) and the robots still searching.
                    "free_sites": len(free),
                    "free_tags": [list(t) for t in free[:FREE_SITES_SHOWN]],
                    "searching": int(np.count_nonzero(states[group] == State.SEARCH)),
                    # ... and of those, the ones standing in a hole of the target (an
                    # ``O``'s middle), which a closed ring shuts in for good
                    "shut_in_holes": shut_in_holes(
                        pos[group], tags[group], holds[group],
                        states[group] == State.SEARCH, target, d,
                    ),
                    # ... and whether the free sites join a hole's edge to the outside, a
                    # way across the ring that every capture rule refuses
                    "way_across": way_across(free, target),
                    # Where the robots stand, whatever their tags say: RMS off their sites
                    # after the group's best rigid fit, and the links between holders of
                    # neighbouring tags that have torn apart (``stretched_links``).
                    "placement_error_mm": None if g_err is None else round(g_err, 3),
                    "stretched_links": stretched_links(pos[group], tags[group], holds[group], d),
                }
            )
        return report

    def target_sites_world(self) -> np.ndarray:
        """Where each remnant's current target sits in the world, (M, 2) mm: its sites
        mapped by the best rigid fit of its tagged robots (a moved or regrown remnant's
        target follows the remnant). Remnants with fewer than two tagged robots add none."""
        holds, _ = self._masks()
        tags = self.controller.tags
        d = self.config.et.spacing_mm
        out = [np.zeros((0, 2))]
        for group in self._groups():
            tagged = group[holds[group]]
            target = self.controller.slot_cells[self._slot_of(group)]
            if len(tagged) < 2 or len(target) == 0:
                continue
            fit = rigid_fit(tags_to_xy(tags[tagged], d), self.world.pos[tagged])
            out.append(apply_fit(fit, tags_to_xy(target, d)))
        return np.vstack(out)

    def summary(self) -> dict[str, Any]:
        """The JSON summary (DESIGN §5 measures; keys documented in the README)."""
        holds, _ = self._masks()
        tags = self.controller.tags
        live = self.world.present & self.world.alive
        states = self.controller.states
        # Each remnant has its own frame: fit and score each on its own.
        sq, count = 0.0, 0
        for group in self._groups():
            g_err = placement_error_mm(
                self.world.pos[group], tags[group], holds[group], self.config.et.spacing_mm
            )
            if g_err is not None:
                n_held = int(holds[group].sum())
                sq += g_err**2 * n_held
                count += n_held
        err = (sq / count) ** 0.5 if count else None
        comps = self.component_report()
        leaders: dict[int, int] = {}
        for comp_ids in self._groups():
            leaders[int(comp_ids[0])] = int(np.sum(states[comp_ids] == State.LEADER))
        return {
            "shape": self.config.shape,
            "robots": int(self.world.n),
            "target_cells": len(self.target),
            "seed": self.config.seed,
            "loss": self.config.loss,
            "noise_mm": self.config.noise_mm,
            "layout": self.config.layout,
            "census": self.config.census,
            # threads = 1 and threads > 1 draw the motion and radio noise differently
            "threads": int(self.sim_params.threads),
            # and a message read one tick later changes every run from there on
            "message_delay_ticks": int(self.sim_params.message_delay_ticks),
            # and the portable maths give other bits than the platform's (but the same
            # on every machine)
            "portable_math": bool(self.sim_params.portable_math),
            "damage": list(self.config.damage),
            "formed": self.formed_at_s is not None,
            "formation_time_s": self.formed_at_s,
            "settled": self.finished,
            "sim_time_s": round(self.sim_time_s, 3),
            "wall_time_s": round(self.wall_s, 3),
            "jaccard": round(
                sum(c["robots"] * (c["jaccard"] or 0.0) for c in comps)
                / max(1, sum(c["robots"] for c in comps)),
                6,
            ),
            "placement_error_mm": None if err is None else round(err, 3),
            "duplicate_tags": sorted(
                {
                    tuple(t)
                    for group in self._groups()
                    for t in duplicate_tags(tags[group], holds[group])
                }
            ),
            "max_leaders_per_component": max(leaders.values(), default=0),
            "states": {
                STATE_NAMES[s]: int(np.sum(live & (states == s))) for s in range(len(State))
            },
            "components": comps,
            "events": list(self.events),
            "notes": list(self.notes),
        }
