"""The compiled tick loop, one specialisation per controller, cached on disk.

Why generated modules: numba cannot cache a function that takes a dispatcher argument
(the argument's type holds the dispatcher's address, so every process misses the cache),
nor a closure over one. What it does cache is a module-level ``@njit(cache=True)`` function
that calls another jitted function through a global name. So for each controller step
function this module writes a tiny Python module (the template below) into a kernel cache
directory, with ``controller_step`` bound to the controller's dispatcher before the module
body runs, and imports it; numba caches that module's ``run_ticks`` in the directory's
``__pycache__``. A second process that uses the same controller loads the machine code
instead of compiling (measured: about 1 s instead of 10-20 s). numba writes every cache,
this one too, to the folder of this version of etswarm's sources
(:mod:`etswarm.compile_cache`).

The controller's own step functions are cached too (``@njit(cache=True)`` on ``et_step``,
``et_part`` and ``et_rest``): compiling the ET controller takes about 110 s, the loops
round it 5-40 s, so a process that finds the controller on disk links its machine code
into each loop instead of compiling it, and a direct call from Python loads it. Measured on a 2-core
machine from empty caches, one process: serial, split and threaded loops 117, 47 and
74 s before; with the controller on disk 6, 31 and 39 s.

numba does not notice when a function called by a cached function changes, so the file
name carries a hash of the sources that end up inside the kernel: every ``.py`` file of
``etswarm/sim`` and of the directory holding the controller's module, plus the numba
version. Editing any of them gives a new kernel file (old ones can be deleted freely).
A controller defined without a source file (an interactive session) is compiled without
caching.

With ``SimParams.threads > 1`` the simulator asks for the threaded loop
(``load_kernel(step, threaded=True)``, its own file ``..._mt_<hash>.py`` and cache): a
``parallel=True`` function that starts one thread per ``prange`` iteration once per call;
each thread runs every tick's phases on its share (:mod:`etswarm.sim.parallel`), the
threads meet at spin-then-yield barriers (:mod:`etswarm.sim.sync`), and the last thread
to arrive runs the one-thread work (the controller, grid rebuilds, pass bookkeeping);
while the controller runs, the other threads build contact lists.
The default loop is generated and compiled exactly as before.

With ``SimParams.control_threads > 1`` (and threads = 1) the simulator asks for the split
loop (``load_kernel(step, split=True, ...)``, file ``..._split_<hash>.py``): the serial
loop's phases and random draws, but the controller's ``part_step`` runs on every thread,
each on its own range of robots; the ranges follow the work each thread measured
(:mod:`etswarm.sim.balance`). Once every thread has finished its range, the last
range's thread (the high IDs: a packed repository's Queued robots, which hear most of
the messages) runs ``rest_step``, motion, collisions and the next tick's radio while the
others wait at the barrier (``sync.arrive_as``). Parts touch only their own robots' rows,
so the results are the serial loop's, byte for byte, on any number of threads. With
``SimParams.message_delay_ticks`` = 1 the radio fills the inbox of the next tick (both
loops alternate two inboxes): in the split loop the last range's thread then runs the
last tick's motion and collisions and this tick's radio (from a copy of the senders'
messages) before its range, beside the other threads' ranges (and gets fewer robots for
it); the one-thread work left is copying the commands and the next senders' messages.

The directory is ``$ETSWARM_KERNEL_DIR`` if set, else ``~/.cache/etswarm/kernels``
(or a temporary directory when that is not writable).
"""

from __future__ import annotations

import hashlib
import importlib.util
import inspect
import os
import re
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from types import ModuleType
from typing import Any

import numba

#: The serial and split loops' phase arrays taken without reference counting
#: (etswarm.sim.borrow), as the loops' source (filled into the templates).
_BORROW_SERIAL_ARRAYS = """\
    grid, mem = borrowed(grid), borrowed(mem)
    pos, heading, motor, led = borrowed((pos, heading, motor, led))
    alive, present, speed, turn_rate = borrowed((alive, present, speed, turn_rate))
    tx_phase, out_on, out_type, out_data = borrowed((tx_phase, out_on, out_type, out_data))
    in_count, in_type, in_data, in_dist = borrowed((in_count, in_type, in_data, in_dist))
    counters, dirty, dirty_flag, spare, trig = borrowed((counters, dirty, dirty_flag, spare,
                                                         trig))
    box = (in_count, in_type, in_data, in_dist)
    nxt = borrowed(nxt)"""

_TEMPLATE = '''"""etswarm tick loop for controller {qualname} (generated by etswarm.sim.kernel)."""
from numba import njit

from etswarm.sim.borrow import borrowed
from etswarm.sim.collide import collide_phase
from etswarm.sim.motion import move_phase
from etswarm.sim.neighbours import grid_sync
from etswarm.sim.radio import radio_phase, senders_by_phase

# controller_step is bound by etswarm.sim.kernel before this body runs.


@njit(cache={cache})
def run_ticks(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
              turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
              in_dist, counters, dirty, dirty_flag, spare, trig, rng_motion, rng_radio, rng_ctl,
              mem, nxt):
    if n <= 0:
        return 0
    # the phases' arrays without reference counting (etswarm.sim.borrow)
{borrow}
    stop = mem[0]
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    n_dirty = grid_sync(grid, pos, present, dirty, dirty_flag, grid.state[2])
    for k in range(n):
        tick = tick0 + k
        # the inbox the radio fills (rx) and the one the controller reads (cx): the same
        # one, or with a delay of one tick the two alternate (see SimParams)
        rx, cx = box, box
        if cfg.msg_delay != 0:
            if k % 2 == 0:
                rx = nxt
            else:
                cx = nxt
        radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, rx[0], rx[1], rx[2], rx[3], counters, rng_radio, order, first)
        controller_step(tick, alive, cx[0], cx[1], cx[2], cx[3], motor, led,
                        out_on, out_type, out_data, mem, rng_ctl)
        n_dirty = move_phase(cfg, grid, pos, heading, motor, alive, present, speed,
                             turn_rate, dirty, dirty_flag, n_dirty, trig, rng_motion)
        n_dirty = collide_phase(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare,
                                counters)
        if stop[0] != 0:
            return k + 1
    return n
'''

_TEMPLATE_THREADED = '''"""etswarm threaded tick loop for controller {qualname}."""
from numba import njit, prange

from etswarm.sim.borrow import borrowed
from etswarm.sim.parallel import (
    CS_CONT, CS_DONE, CS_STOP, collide_after_pass, collide_begin, collide_end,
    collide_pass_grab, control_begin, control_done, grid_sync_flags, move_finish,
    move_part, part_bounds, prebuild_lists, radio_bad, radio_count, radio_file_part,
    radio_list_part,
)
from etswarm.sim.radio import senders_by_phase
from etswarm.sim.sync import arrive, atomic_load, release

# controller_part and controller_rest are bound by etswarm.sim.kernel before this body
# runs (the controller's part_step and rest_step, or no_part_step and its step).


@njit(cache={cache})
def thread_ticks(p, n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                 turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
                 in_dist, counters, flags, trig, rng_ctl, mem, scratch, order, first):
    # the phases' arrays without reference counting (etswarm.sim.borrow): both threads
    # would otherwise update the same counters at every call
    grid, mem, scratch = borrowed(grid), borrowed(mem), borrowed(scratch)
    pos, heading, motor, led = borrowed((pos, heading, motor, led))
    alive, present, speed, turn_rate = borrowed((alive, present, speed, turn_rate))
    tx_phase, out_on, out_type, out_data = borrowed((tx_phase, out_on, out_type, out_data))
    in_count, in_type, in_data, in_dist = borrowed((in_count, in_type, in_data, in_dist))
    counters, flags, trig, order, first = borrowed((counters, flags, trig, order, first))
    # the last thread to reach a barrier does the one-thread work, then releases the rest
    parts = scratch.parts[0]
    sync = scratch.sync
    cs = scratch.cstate
    lo, hi = part_bounds(p, pos.shape[0], scratch)
    for k in range(n):
        tick = tick0 + k
        radio_list_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                        out_data, scratch, order, first)
        if arrive(sync, parts):
            release(sync)
        radio_file_part(p, tick, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                        out_data, in_count, in_type, in_data, in_dist, counters, scratch,
                        order, first)
        # the controller's per-robot work on the robots whose inboxes this thread filed
        bad = radio_bad(scratch)  # then part 0 filed every inbox: parts wait (below)
        if not bad:
            controller_part(lo, hi, tick, alive, in_count, in_type, in_data, in_dist, motor,
                            led, out_on, out_type, out_data, mem)
        if arrive(sync, parts):
            # this thread runs the rest of the controller; the others build contact lists
            radio_count(counters, scratch)
            control_begin(scratch)
            release(sync)
            if bad:
                controller_part(0, pos.shape[0], tick, alive, in_count, in_type, in_data,
                                in_dist, motor, led, out_on, out_type, out_data, mem)
            controller_rest(tick, alive, in_count, in_type, in_data, in_dist, motor, led,
                            out_on, out_type, out_data, mem, rng_ctl)
            control_done(scratch)
        else:
            prebuild_lists(p, cfg, grid, scratch)
        if arrive(sync, parts):
            release(sync)
        move_part(p, tick, cfg, grid, pos, heading, motor, alive, present, speed, turn_rate,
                  flags, trig, scratch)
        if arrive(sync, parts):
            move_finish(grid, pos, present, flags, scratch)
            collide_begin(grid, scratch)
            release(sync)
        while atomic_load(cs, CS_CONT) != 0:
            collide_pass_grab(p, cfg, grid, pos, motor, flags, scratch)
            if arrive(sync, parts):
                collide_after_pass(cfg, grid, pos, present, flags, scratch)
                if cs[CS_CONT] == 0:
                    collide_end(grid, pos, present, flags, counters, scratch)
                    cs[CS_STOP] = 1 if mem[0][0] != 0 else 0
                    cs[CS_DONE] = k + 1
                release(sync)
        if atomic_load(cs, CS_STOP) != 0:
            return
    return


@njit(cache={cache}, parallel=True)
def run_ticks(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
              turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
              in_dist, counters, flags, trig, rng_ctl, mem, scratch):
    if n <= 0:
        return 0
    grid_sync_flags(grid, pos, present, flags, scratch.robot_flag)
    scratch.cstate[CS_DONE] = 0
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    for p in prange(scratch.parts[0]):
        thread_ticks(p, n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
                     turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type,
                     in_data, in_dist, counters, flags, trig, rng_ctl, mem, scratch, order,
                     first)
    return scratch.cstate[CS_DONE]
'''

_TEMPLATE_SPLIT = '''"""etswarm tick loop for controller {qualname}, its parts on threads."""
from numba import njit, prange

from etswarm.sim.borrow import borrowed
from etswarm.sim.collide import collide_phase
from etswarm.sim.motion import move_phase
from etswarm.sim.neighbours import grid_sync
from etswarm.sim.radio import radio_phase, senders_by_phase, snapshot_senders
from etswarm.sim.balance import BAL_BOUNDS, cost_index, cycle_count, ready_bounds, rebalance
from etswarm.sim.sync import arrive_as, atomic_load, release

# controller_part and controller_rest are bound by etswarm.sim.kernel before this body
# runs (the controller's part_step and rest_step).

# fields of ``state``: dirty robots carried between ticks, ticks run, stop
ST_DIRTY = 0
ST_DONE = 1
ST_STOP = 2


@njit(cache={cache})
def thread_ticks(p, parts, n, tick0, cfg, grid, pos, heading, motor, led, alive, present,
                 speed, turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type,
                 in_data, in_dist, counters, dirty, dirty_flag, spare, trig, rng_motion,
                 rng_radio, rng_ctl, mem, sync, state, order, first, nxt, snap, bal):
{borrow}
    sync, state, order, first, snap, bal = borrowed((sync, state, order, first, snap, bal))
    delay = cfg.msg_delay
    stop = mem[0]
    # with a delay, the commands of the tick whose motion is still to run (see below)
    motor_prev = snap[3]
    for k in range(n):
        tick = tick0 + k
        rx, cx = box, box
        if delay != 0:
            if k % 2 == 0:
                rx = nxt
            else:
                cx = nxt
        # this thread's robots (etswarm.sim.balance), timed; with a delay, the last
        # part's thread also runs the last tick's motion and collisions and then this
        # tick's radio (into the other inbox, from the copy of the senders' messages)
        # beside the others' parts, and their time counts as its part's: the control
        # reads neither positions nor the others' commands, so it need not wait for
        # them. That thread holds the high IDs, the Queued robots of a packed repository,
        # which hear most of the messages: their inboxes are filled on the core that
        # reads them.
        started = cycle_count()
        if delay != 0 and p == parts - 1:
            if k > 0:
                n_dirty = move_phase(cfg, grid, pos, heading, motor_prev, alive, present,
                                     speed, turn_rate, dirty, dirty_flag, state[ST_DIRTY],
                                     trig, rng_motion)
                state[ST_DIRTY] = collide_phase(cfg, grid, pos, present, motor_prev, dirty,
                                                dirty_flag, n_dirty, spare, counters)
            radio_phase(tick, cfg, grid, pos, alive, present, tx_phase, snap[0], snap[1],
                        snap[2], rx[0], rx[1], rx[2], rx[3], counters, rng_radio, order,
                        first)
        controller_part(bal[BAL_BOUNDS + p], bal[BAL_BOUNDS + p + 1], tick, alive, cx[0],
                        cx[1], cx[2], cx[3], motor, led, out_on, out_type, out_data, mem)
        bal[cost_index(parts, p)] = cycle_count() - started
        if arrive_as(sync, parts, p == parts - 1):
            # the last part's thread, once all have arrived, runs the rest of the tick and
            # readies the next one: with a delay it keeps the tick's commands for the
            # motion and copies the next senders' messages; else it moves the robots and
            # runs the radio, whose inboxes are mostly its own robots' (see above)
            rebalance(bal, parts)
            controller_rest(tick, alive, cx[0], cx[1], cx[2], cx[3], motor, led,
                            out_on, out_type, out_data, mem, rng_ctl)
            state[ST_DONE] = k + 1
            last = stop[0] != 0 or k + 1 == n
            if delay != 0 and not last:
                motor_prev[:] = motor
                snapshot_senders(tick + 1, cfg, out_on, out_type, out_data, snap[0],
                                 snap[1], snap[2], order, first)
            else:
                # (the call's last tick moves the robots before it returns)
                n_dirty = move_phase(cfg, grid, pos, heading, motor, alive, present, speed,
                                     turn_rate, dirty, dirty_flag, state[ST_DIRTY], trig,
                                     rng_motion)
                state[ST_DIRTY] = collide_phase(cfg, grid, pos, present, motor, dirty,
                                                dirty_flag, n_dirty, spare, counters)
                if not last:
                    radio_phase(tick + 1, cfg, grid, pos, alive, present, tx_phase, out_on,
                                out_type, out_data, in_count, in_type, in_data, in_dist,
                                counters, rng_radio, order, first)
            if last:
                state[ST_STOP] = 1
            release(sync)
        if atomic_load(state, ST_STOP) != 0:
            return


@njit(cache={cache}, parallel=True)
def run_ticks(n, tick0, cfg, grid, pos, heading, motor, led, alive, present, speed,
              turn_rate, tx_phase, out_on, out_type, out_data, in_count, in_type, in_data,
              in_dist, counters, dirty, dirty_flag, spare, trig, rng_motion, rng_radio, rng_ctl,
              mem, sync, state, parts, nxt, snap, bal):
    if n <= 0:
        return 0
    order, first = senders_by_phase(tx_phase, cfg.tx_period)
    state[ST_DIRTY] = grid_sync(grid, pos, present, dirty, dirty_flag, grid.state[2])
    state[ST_DONE] = 0
    state[ST_STOP] = 0
    ready_bounds(bal, parts, pos.shape[0])
    if cfg.msg_delay != 0:
        snapshot_senders(tick0, cfg, out_on, out_type, out_data, snap[0], snap[1], snap[2],
                         order, first)
    else:
        radio_phase(tick0, cfg, grid, pos, alive, present, tx_phase, out_on, out_type,
                    out_data, in_count, in_type, in_data, in_dist, counters, rng_radio, order,
                    first)
    for p in prange(parts):
        thread_ticks(p, parts, n, tick0, cfg, grid, pos, heading, motor, led, alive, present,
                     speed, turn_rate, tx_phase, out_on, out_type, out_data, in_count,
                     in_type, in_data, in_dist, counters, dirty, dirty_flag, spare, trig,
                     rng_motion, rng_radio, rng_ctl, mem, sync, state, order, first, nxt,
                     snap, bal)
    return state[ST_DONE]
'''

#: Start of the names of the modules :func:`load_kernel` generates.
KERNEL_PREFIX = "_etswarm_kernel_"

_loaded: dict[tuple[int, bool, int, int, bool], ModuleType] = {}


@contextmanager
def compiling(kernel: Any) -> Iterator[None]:
    """Hold an exclusive lock on ``kernel``'s file (``<module>.lock`` beside it) while the
    caller makes the kernel's first call, which compiles it or loads it from numba's cache.

    Only modules that :func:`load_kernel` generated (named ``KERNEL_PREFIX...``) are
    locked. Two processes that need the same kernel at once (a sweep's workers, pytest-xdist's)
    then compile it once: the second waits and loads the first one's machine code from
    disk instead of compiling the same code beside it. Without ``fcntl`` (Windows) or a
    writable folder the call goes ahead unlocked.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX
        yield
        return
    name = getattr(getattr(kernel, "py_func", None), "__module__", "") or ""
    module = sys.modules.get(name) if name.startswith(KERNEL_PREFIX) else None
    source = getattr(module, "__file__", None)
    try:
        handle = open(Path(source).with_suffix(".lock"), "a") if source else None  # noqa: SIM115
    except OSError:
        handle = None
    if handle is None:
        yield
        return
    with handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def kernel_dir() -> Path:
    """Directory holding the generated kernel modules and their numba cache."""
    env = os.environ.get("ETSWARM_KERNEL_DIR")
    candidates = [Path(env)] if env else []
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(Path.home(), ".cache")
    candidates.append(Path(base) / "etswarm" / "kernels")
    candidates.append(Path(tempfile.gettempdir()) / f"etswarm-kernels-{os.getuid()}")
    for path in candidates:
        try:
            path.mkdir(parents=True, exist_ok=True)
            if os.access(path, os.W_OK):
                return path
        except OSError:
            continue
    raise OSError("no writable directory for etswarm kernels; set ETSWARM_KERNEL_DIR")


def _source_hash(step_py: Any, template: str = _TEMPLATE) -> str | None:
    """Hash of the sources compiled into the kernel; None if the controller has no file."""
    try:
        src_file = inspect.getsourcefile(step_py)
    except TypeError:
        return None
    if src_file is None or not os.path.isfile(src_file):
        return None
    digest = hashlib.sha256()
    digest.update(template.encode())
    digest.update(numba.__version__.encode())
    sim_dir = Path(__file__).resolve().parent
    ctl_dir = Path(src_file).resolve().parent
    for folder in sorted({sim_dir, ctl_dir}):
        for path in sorted(folder.glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    digest.update(step_py.__qualname__.encode())
    return digest.hexdigest()[:16]


def load_kernel(step: Any, threaded: bool = False, part_step: Any = None,
                rest_step: Any = None, split: bool = False) -> Any:
    """The compiled ``run_ticks`` for controller dispatcher ``step`` (see module doc).

    ``threaded``: the loop of the threaded phases (:mod:`etswarm.sim.parallel`), a kernel
    of its own (file name ending ``_mt_<hash>``) with the arguments of that template. It
    runs the controller as ``part_step`` on every thread (its robots) and then
    ``rest_step`` on one (both dispatchers; see :mod:`etswarm.sim.simulator`); without
    them, ``step`` on one thread.
    ``split``: the serial loop with the controller's ``part_step`` on threads (both
    dispatchers required; file name ending ``_split_<hash>``), see the module doc.
    """
    if split and (threaded or part_step is None or rest_step is None):
        raise ValueError("the split loop needs the controller's part_step and rest_step")
    if threaded and (part_step is None or rest_step is None):
        part_step = rest_step = None
    if not threaded and not split:
        part_step = rest_step = None
    key = (id(step), bool(threaded), id(part_step), id(rest_step), bool(split))
    template = _TEMPLATE_THREADED if threaded else _TEMPLATE_SPLIT if split else _TEMPLATE
    if key in _loaded:
        return _loaded[key].run_ticks
    py_func = getattr(step, "py_func", None)
    if py_func is None:
        raise TypeError("controller step must be an @njit function (numba dispatcher)")
    digest = _source_hash(py_func, template)
    label = re.sub(r"[^0-9A-Za-z_]", "_", f"{py_func.__module__}_{py_func.__qualname__}")
    if threaded or split:
        label += "_mt" if threaded else "_split"
        if part_step is not None:
            label += "_parts"
            if digest is not None:
                extra = hashlib.sha256(digest.encode())
                for fn in (part_step, rest_step):
                    py = getattr(fn, "py_func", None)
                    if py is None:
                        raise TypeError("controller part_step and rest_step must be @njit "
                                        "functions (numba dispatchers)")
                    extra.update(f"{py.__module__}.{py.__qualname__}".encode())
                digest = extra.hexdigest()[:16]
    source = template.format(qualname=f"{py_func.__module__}.{py_func.__qualname__}",
                              cache=digest is not None, borrow=_BORROW_SERIAL_ARRAYS)
    if digest is None:
        folder = Path(tempfile.mkdtemp(prefix="etswarm-kernel-"))
        name = f"{KERNEL_PREFIX}{label}_{id(step):x}"
    else:
        folder = kernel_dir()
        name = f"{KERNEL_PREFIX}{label}_{digest}"
    path = folder / f"{name}.py"
    if not path.exists() or path.read_text() != source:
        tmp = folder / f".{name}.{os.getpid()}.tmp"
        tmp.write_text(source)
        os.replace(tmp, path)
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    module.controller_step = step  # type: ignore[attr-defined]
    if split:
        module.controller_part = part_step  # type: ignore[attr-defined]
        module.controller_rest = rest_step  # type: ignore[attr-defined]
    if threaded:
        from etswarm.sim.parallel import no_part_step

        module.controller_part = (  # type: ignore[attr-defined]
            part_step if part_step is not None else no_part_step)
        module.controller_rest = (  # type: ignore[attr-defined]
            rest_step if rest_step is not None else step)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    _loaded[key] = module
    return module.run_ticks
