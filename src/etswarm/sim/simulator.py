"""The simulator: a world, a controller, parameters and seeded streams, stepped in ticks.

Each tick runs fixed phases: (1) radio: clear inboxes, deliver this tick's broadcasts;
(2) control: the controller reads inboxes and writes motor, led, out_*; (3) move;
(4) collide; (5) ``world.tick += 1``. With ``SimParams.message_delay_ticks`` = 1 the
radio fills the inbox the controller reads at the next tick (two inboxes alternate), so
a broadcast is read one tick later.

Two kinds of controller plug in:

* **fast path**: an object with ``step`` (an ``@njit(cache=True)`` function with the
  signature ``step(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on,
  out_type, out_data, mem, rng)``) and ``mem`` (a tuple whose element 0 is a (1,) int64
  stop flag). :meth:`Simulator.run_ticks` then runs all ``n`` ticks inside one compiled
  call (see :mod:`etswarm.sim.kernel`). If the controller sets ``mem[0][0] != 0`` during
  its control phase, the kernel finishes that tick and returns early; the flag is left
  set for the host to read and clear. Optionally also ``part_step`` and ``rest_step``
  (both ``@njit``): ``part_step(lo, hi, tick, alive, in_count, in_type, in_data,
  in_dist, motor, led, out_on, out_type, out_data, mem)`` does the per-robot work of
  robots ``lo .. hi - 1`` touching only their rows and drawing nothing, and
  ``rest_step`` (``step``'s signature) the rest; ``part_step`` over all robots followed
  by ``rest_step`` must give exactly what ``step`` gives. With ``threads > 1`` the
  threaded loop then runs the parts on all threads at once (each thread right after
  filing its robots' inboxes) and ``rest_step`` on one; ``step`` is used otherwise.
* **slow path**: any object with a Python method ``step(view)``, where ``view`` is a
  :class:`ControlView` of arrays for all robots; one Python call per tick.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numba
import numpy as np

from etswarm.errors import EtswarmError
from etswarm.seeding import stream
from etswarm.sim.balance import balance_size
from etswarm.sim.collide import collide_phase
from etswarm.sim.kernel import compiling, load_kernel
from etswarm.sim.motion import move_phase
from etswarm.sim.neighbours import Grid, grid_sync, make_grid
from etswarm.sim.parallel import (
    ThreadScratch,
    collide_phase_mt,
    grid_sync_flags,
    make_scratch,
    move_phase_mt,
    radio_phase_mt,
)
from etswarm.sim.params import SimParams
from etswarm.sim.radio import radio_phase, senders_by_phase
from etswarm.sim.world import World

#: Contact-list drift (mm): see etswarm.sim.neighbours. Results do not depend on it; 2 mm
#: builds fewer lists than 1 mm (0.14 instead of 0.25 per robot-tick in the random-walk
#: benchmark) at a small cost in list length.
DRIFT_MM = 2.0


@dataclass
class ControlView:
    """What a slow-path controller sees and writes (arrays are the World's own).

    Read: ``tick``, ``alive`` (N,), ``in_count`` (N,), ``in_type`` (N, K), ``in_data``
    (N, K, 9), ``in_dist`` (N, K) mm. Write: ``motor`` (N,), ``led`` (N,), ``out_on`` (N,),
    ``out_type`` (N,), ``out_data`` (N, 9). ``rng`` is the run's controller stream.
    """

    tick: int
    alive: np.ndarray
    in_count: np.ndarray
    in_type: np.ndarray
    in_data: np.ndarray
    in_dist: np.ndarray
    motor: np.ndarray
    led: np.ndarray
    out_on: np.ndarray
    out_type: np.ndarray
    out_data: np.ndarray
    rng: np.random.Generator


def is_fast_controller(controller: Any) -> bool:
    """True when ``controller`` follows the compiled (fast-path) protocol."""
    return hasattr(controller, "mem") and hasattr(getattr(controller, "step", None), "py_func")


class Simulator:
    """Runs ``controller`` on ``world`` with ``params``; randomness from ``seed``'s streams.

    Streams: "motion" (motion noise), "radio" (loss and distance noise), "controller"
    (passed to the controller). The world's calibration and placement used children of
    "motion", "radio" and "placement" when it was built. With ``params.threads > 1`` the
    phases run on threads (:mod:`etswarm.sim.parallel`) and draw motion and radio noise
    from a counter-based hash keyed by one draw from the "threads" stream.
    """

    def __init__(self, world: World, controller: Any, params: SimParams | None = None,
                 seed: int = 0) -> None:
        self.world = world
        self.controller = controller
        self.params = params or SimParams()
        self.seed = int(seed)
        if world.inbox_capacity != self.params.inbox_capacity:
            raise EtswarmError(
                f"world inbox capacity {world.inbox_capacity} differs from sim parameter "
                f"inbox_capacity {self.params.inbox_capacity}"
            )
        self.rng_motion = stream(self.seed, "motion")
        self.rng_radio = stream(self.seed, "radio")
        self.rng_controller = stream(self.seed, "controller")
        self.cfg = self.params.kernel_config()
        n = world.n
        r = self.params.body_radius_mm
        margin = max(1.0, 0.15 * r)  # grid slack; collision budgets are up to margin / 2
        # threads > 1: smaller cells (see etswarm.sim.parallel); the one-thread phases'
        # loops are written for cells of at least 4 r + 4 margin
        cell = 4.0 * r + 4.0 * margin if self.params.threads == 1 else 2.0 * r + 3.1 * margin
        self.grid: Grid = make_grid(n, cell, margin, DRIFT_MM)
        self._dirty = np.zeros(n, dtype=np.int32)
        self._dirty_flag = np.zeros(n, dtype=np.uint8)
        self._spare = np.zeros(n, dtype=np.int32)
        self._trig = np.full((n, 6), np.nan)  # motion's cached cos/sin (see move_phase)
        self.threads = self.params.threads
        self._scratch: ThreadScratch | None = None
        if self.threads > 1:
            key = int(stream(self.seed, "threads").integers(0, 2**63, dtype=np.int64))
            self._scratch = make_scratch(n, self._threads_used(), key)
            self._chooser = ThreadChooser(self._threads_used())
        # message_delay_ticks 1: the inbox the radio fills for the next tick, swapped with
        # the world's after every tick (after a kernel call that ran an odd number), and
        # the split loop's copy of a tick's senders' messages and of its motor commands
        self._next_inbox: list[np.ndarray] = list(self._inbox())
        self._sent_copy = (world.out_on, world.out_type, world.out_data,
                           np.zeros_like(world.motor))
        if self.params.message_delay_ticks:
            self._next_inbox = [np.zeros_like(a) for a in self._inbox()]
            self._sent_copy = (np.zeros_like(world.out_on), np.zeros_like(world.out_type),
                               np.zeros_like(world.out_data), np.zeros_like(world.motor))
        self.fast = is_fast_controller(controller)
        part_step = getattr(controller, "part_step", None)
        rest_step = getattr(controller, "rest_step", None)
        # control_threads > 1: the controller's per-robot work on threads, the rest as at
        # threads = 1 (same results); only for a controller that offers its step split
        self._split: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        if (self.fast and self.threads == 1 and self.params.control_threads > 1
                and part_step is not None and rest_step is not None):
            most = max(1, min(self.params.control_threads, numba.config.NUMBA_NUM_THREADS))
            self._split = (np.zeros(2, dtype=np.int64), np.zeros(3, dtype=np.int64),
                           np.zeros(balance_size(most), dtype=np.int64))
            self._chooser = ThreadChooser(most)
        if self.fast:
            mem = controller.mem
            if (not isinstance(mem, tuple) or not mem or not isinstance(mem[0], np.ndarray)
                    or mem[0].dtype != np.int64 or mem[0].shape != (1,)):
                raise TypeError("controller.mem must be a tuple whose element 0 is a (1,) "
                                "int64 stop-flag array")
            self._kernel = load_kernel(controller.step, threaded=self._scratch is not None,
                                       part_step=part_step, rest_step=rest_step,
                                       split=self._split is not None)
            with compiling(self._kernel):  # one process at a time compiles a kernel
                self._call_kernel(0)  # compile, or load from the disk cache, now
        elif not callable(getattr(controller, "step", None)):
            raise TypeError("controller needs a step(view) method or an njit step + mem")

    @property
    def stop_requested(self) -> bool:
        """True when a fast controller has raised its stop flag (mem[0][0] != 0)."""
        return bool(self.fast and self.controller.mem[0][0] != 0)

    def run_ticks(self, n: int) -> int:
        """Run up to ``n`` ticks; return how many ran (fewer if the controller asked to stop)."""
        if n <= 0:
            return 0
        if self.fast:
            done = self._call_kernel(n)
            self.world.tick += done
            return done
        for k in range(n):
            self._slow_tick()
            if getattr(self.controller, "stop_requested", False):
                return k + 1
        return n

    def _inbox(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The world's inbox arrays: what the controller reads at the next tick."""
        w = self.world
        return w.in_count, w.in_type, w.in_data, w.in_dist

    def _after_ticks(self, ran: int) -> int:
        """With a message delay, after ``ran`` ticks the inbox of the next tick is the one
        the kernel filled last: the spare when ``ran`` is odd. Swap it into the world."""
        if self.params.message_delay_ticks and ran % 2 == 1:
            for k, name in enumerate(_INBOX_NAMES):
                held = getattr(self.world, name)
                setattr(self.world, name, self._next_inbox[k])
                self._next_inbox[k] = held
        return ran

    def _threads_used(self) -> int:
        """Threads actually started: ``params.threads``, at most numba's thread count."""
        return max(1, min(self.threads, numba.config.NUMBA_NUM_THREADS))

    def _call_kernel(self, n: int) -> int:
        """Run the compiled loop for ``n`` ticks (0: just make sure it is compiled)."""
        w = self.world
        if self._scratch is not None:
            return self._call_threaded(n)
        if self._split is not None:
            return self._call_split(n)
        return self._after_ticks(int(self._kernel(
            int(n), int(w.tick), self.cfg, self.grid, w.pos, w.heading, w.motor, w.led,
            w.alive, w.present, w.speed, w.turn_rate, w.tx_phase, w.out_on, w.out_type,
            w.out_data, w.in_count, w.in_type, w.in_data, w.in_dist, w.counters,
            self._dirty, self._dirty_flag, self._spare, self._trig, self.rng_motion,
            self.rng_radio, self.rng_controller, self.controller.mem, tuple(self._next_inbox),
        )))

    def _run_chosen(self, n: int, call: Callable[[int, int, int], int]) -> int:
        """Run ``n`` ticks in calls of about SUB_CALL_S seconds each, on the thread count
        that is fastest now (see :class:`ThreadChooser`): ``call(threads, ticks, done)``
        runs one kernel call of up to ``ticks`` ticks from ``done`` ticks past the world's
        clock and returns the ticks it ran."""
        done = 0
        while True:
            threads = self._chooser.pick()
            step = min(n - done, self._chooser.call_ticks())
            t0 = time.perf_counter()
            with _NumbaThreads(threads):
                ran = call(threads, step, done)
            self._chooser.record(threads, ran, time.perf_counter() - t0)
            done += ran
            if done >= n or ran < step:
                return done

    def _call_threaded(self, n: int) -> int:
        """Run the threaded loop for ``n`` ticks (see :meth:`_run_chosen`)."""
        w = self.world
        scr = self._scratch
        assert scr is not None

        def call(threads: int, ticks: int, done: int) -> int:
            scr.parts[0] = threads
            return int(self._kernel(
                int(ticks), int(w.tick + done), self.cfg, self.grid, w.pos, w.heading,
                w.motor, w.led, w.alive, w.present, w.speed, w.turn_rate, w.tx_phase,
                w.out_on, w.out_type, w.out_data, w.in_count, w.in_type, w.in_data,
                w.in_dist, w.counters, self._dirty_flag, self._trig, self.rng_controller,
                self.controller.mem, scr,
            ))

        return self._run_chosen(n, call)

    def _call_split(self, n: int) -> int:
        """Run the split loop (the controller's parts on threads, see
        :mod:`etswarm.sim.kernel`) for ``n`` ticks (see :meth:`_run_chosen`); results do
        not depend on the thread count."""
        w = self.world
        assert self._split is not None
        sync, state, bal = self._split

        def call(threads: int, ticks: int, done: int) -> int:
            return self._after_ticks(int(self._kernel(
                int(ticks), int(w.tick + done), self.cfg, self.grid, w.pos, w.heading,
                w.motor, w.led, w.alive, w.present, w.speed, w.turn_rate, w.tx_phase,
                w.out_on, w.out_type, w.out_data, w.in_count, w.in_type, w.in_data,
                w.in_dist, w.counters, self._dirty, self._dirty_flag, self._spare,
                self._trig, self.rng_motion, self.rng_radio, self.rng_controller,
                self.controller.mem, sync, state, threads, tuple(self._next_inbox),
                self._sent_copy, bal,
            )))

        return self._run_chosen(n, call)

    def _view(self) -> ControlView:
        w = self.world
        return ControlView(w.tick, w.alive, w.in_count, w.in_type, w.in_data, w.in_dist,
                           w.motor, w.led, w.out_on, w.out_type, w.out_data,
                           self.rng_controller)

    def _slow_tick(self) -> None:
        """One tick with a Python controller: the same phases as the compiled loop."""
        w = self.world
        g = self.grid
        scr = self._scratch
        if scr is not None:
            # the threaded phases on the calling thread: threads meeting at every phase
            # would cost more than they save next to a Python controller, and results do
            # not depend on the thread count
            scr.parts[0] = 1
            grid_sync_flags(g, w.pos, w.present, self._dirty_flag, scr.robot_flag)
            radio_phase_mt(w.tick, self.cfg, g, w.pos, w.alive, w.present, w.tx_phase,
                           w.out_on, w.out_type, w.out_data, w.in_count, w.in_type,
                           w.in_data, w.in_dist, w.counters, scr)
            self.controller.step(self._view())
            move_phase_mt(w.tick, self.cfg, g, w.pos, w.heading, w.motor, w.alive,
                          w.present, w.speed, w.turn_rate, self._dirty_flag, self._trig,
                          scr)
            collide_phase_mt(self.cfg, g, w.pos, w.present, w.motor, self._dirty_flag,
                             w.counters, scr)
            w.tick += 1
            return
        n_dirty = grid_sync(g, w.pos, w.present, self._dirty, self._dirty_flag, g.state[2])
        order, first = senders_by_phase(w.tx_phase, self.cfg.tx_period)
        filled = self._next_inbox if self.params.message_delay_ticks else self._inbox()
        radio_phase(w.tick, self.cfg, g, w.pos, w.alive, w.present, w.tx_phase, w.out_on,
                    w.out_type, w.out_data, *filled, w.counters, self.rng_radio, order, first)
        self.controller.step(self._view())
        n_dirty = move_phase(self.cfg, g, w.pos, w.heading, w.motor, w.alive, w.present,
                             w.speed, w.turn_rate, self._dirty, self._dirty_flag, n_dirty,
                             self._trig, self.rng_motion)
        collide_phase(self.cfg, g, w.pos, w.present, w.motor, self._dirty, self._dirty_flag,
                      n_dirty, self._spare, w.counters)
        self._after_ticks(1)
        w.tick += 1

    def run_seconds(self, seconds: float) -> int:
        """Run ``seconds`` of simulated time (rounded to whole ticks); return ticks run."""
        return self.run_ticks(round(seconds * self.params.ticks_per_s))


#: The world's inbox arrays, in the order the kernels take them.
_INBOX_NAMES = ("in_count", "in_type", "in_data", "in_dist")

class _NumbaThreads:
    """Context: numba runs parallel loops on ``count`` threads, restored on exit."""

    def __init__(self, count: int) -> None:
        self.count = count
        self.before = 1

    def __enter__(self) -> None:
        self.before = numba.get_num_threads()
        if self.before != self.count:
            numba.set_num_threads(self.count)

    def __exit__(self, *exc: object) -> None:
        if self.before != self.count:
            numba.set_num_threads(self.before)


class ThreadChooser:
    """Picks how many threads each call of the threaded loop runs on: ``most`` or 1.

    Results do not depend on the count, only the speed does: on a machine whose cores are
    busy with other work, threads that wait for each other at every phase can be slower
    than one. Calls are sized to about ``SUB_CALL_S`` seconds; the count not in use is
    tried now and then for half a call (after 4, 8, 16 calls while it keeps losing; a
    shorter try mostly measured the threads waking up and the grid moving between the
    cores' caches) and the faster one (seconds per tick, averaged over its recent calls) is
    used. The first call on each count is not timed (it starts the threads).
    ``adaptive=False`` always uses ``most``. ``ticks_on`` counts the ticks run on each
    count.
    """

    SUB_CALL_S = 0.05

    def __init__(self, most: int, adaptive: bool = True) -> None:
        self.most = most
        self.adaptive = adaptive
        self.ticks_on: dict[int, int] = {most: 0, 1: 0}
        self.ticks_per_call = 16
        self.sec_per_tick: dict[int, float | None] = {most: None, 1: None}
        self.current = most
        self.gap = 4
        self.since_try = 0
        self.trying = False
        self.warmed: set[int] = set()

    def pick(self) -> int:
        """Thread count for the next call."""
        if self.most == 1 or not self.adaptive:
            return self.most
        other = 1 if self.current == self.most else self.most
        self.trying = self.since_try >= self.gap or (
            self.sec_per_tick[self.current] is not None and self.sec_per_tick[other] is None
            and self.since_try >= 1)
        return other if self.trying else self.current

    def call_ticks(self) -> int:
        """Ticks for the next call: about SUB_CALL_S seconds, half that for a try of the
        count not in use (which may be much slower)."""
        return max(1, self.ticks_per_call // 2) if self.trying else self.ticks_per_call

    def record(self, threads: int, ticks: int, seconds: float) -> None:
        """The last call ran ``ticks`` ticks on ``threads`` threads in ``seconds``."""
        if ticks <= 0:
            return
        self.ticks_on[threads] = self.ticks_on.get(threads, 0) + ticks
        if threads not in self.warmed:
            # the first call on a count starts its threads and fills its caches: it
            # would make the count look slower than it is for many calls
            self.warmed.add(threads)
            return
        per_tick = seconds / ticks
        old = self.sec_per_tick[threads]
        self.sec_per_tick[threads] = per_tick if old is None else 0.5 * (old + per_tick)
        if not self.trying:
            target = max(1, int(self.SUB_CALL_S / max(per_tick, 1e-9)))
            self.ticks_per_call = min(target, 1 << 20)
            self.since_try += 1
            return
        self.since_try = 0
        mine = self.sec_per_tick[self.current]
        if mine is not None and self.sec_per_tick[threads] < mine:  # type: ignore[operator]
            self.current = threads
            self.gap = 4
        else:
            self.gap = min(2 * self.gap, 16)
