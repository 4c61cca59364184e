"""Splitting a controller's per-robot work between threads by what it cost last tick.

The split loop (:mod:`etswarm.sim.kernel`, ``SimParams.control_threads > 1``) runs the
controller's ``part_step`` on every thread, each on its own range of robot indices.
Ranges handed out afresh every tick (pieces taken from a shared counter) sent a robot's
memory rows to whichever core took its piece; in an ET formation of 1000 robots the
controller's work then cost 1.7 times the CPU of one thread, and two threads ran no
faster than one. So each thread keeps one range of robots from tick to tick, and the
ranges follow the work: every thread times its range (CPU cycles), and after each tick
the boundaries move part of the way towards the points that would have split that
tick's cost evenly, taking the cost as spread evenly within each range.

Which thread does which robots never changes the results (parts touch only their own
robots' rows), so the boundaries need no care for determinism.

``bal`` is an int64 array of :func:`balance_size` entries: ``[parts, bounds (parts + 1),
cycles (parts), room for the next bounds (parts + 1)]``; part ``p`` holds robots
``bounds[p] .. bounds[p + 1] - 1``.
"""

from __future__ import annotations

from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic

#: Index of the number of parts the boundaries were made for.
BAL_PARTS = 0
#: Index of the first boundary (parts + 1 of them: 0, ..., robots).
BAL_BOUNDS = 1
#: A boundary moves this share of the way to its even-cost point per tick (costs vary
#: from tick to tick with the robots that are due; a slow move averages them).
BAL_STEP = 0.125


def balance_size(most: int) -> int:
    """Entries of the ``bal`` array for up to ``most`` parts."""
    return 3 * most + 3


@intrinsic
def cycle_count(typingctx):
    """The CPU's cycle counter (LLVM ``readcyclecounter``; the TSC on x86), as int64."""

    def codegen(context, builder, signature, args):
        fnty = ir.FunctionType(ir.IntType(64), [])
        fn = builder.module.declare_intrinsic("llvm.readcyclecounter", fnty=fnty)
        return builder.call(fn, [])

    return types.int64(), codegen


@njit(cache=True)
def cost_index(parts, p):  # type: ignore[no-untyped-def]
    """Index in ``bal`` of part ``p``'s cycles of the last tick."""
    return BAL_BOUNDS + parts + 1 + p


@njit(cache=True)
def target_index(parts, k):  # type: ignore[no-untyped-def]
    """Index in ``bal`` where :func:`rebalance` keeps boundary ``k``'s even-cost point."""
    return BAL_BOUNDS + 2 * parts + 1 + k


@njit(cache=True)
def ready_bounds(bal, parts, n):  # type: ignore[no-untyped-def]
    """Even boundaries for ``parts`` parts of ``n`` robots, unless ``bal`` holds some for
    that split already (kept from the last call)."""
    if bal[BAL_PARTS] == parts and bal[BAL_BOUNDS + parts] == n:
        return
    bal[BAL_PARTS] = parts
    for p in range(parts + 1):
        bal[BAL_BOUNDS + p] = n * p // parts
    for p in range(parts):
        bal[cost_index(parts, p)] = 0


@njit(cache=True)
def rebalance(bal, parts):  # type: ignore[no-untyped-def]
    """Move each inner boundary ``BAL_STEP`` of the way towards where the last tick's
    cycles (each part's spread evenly over its robots) reach ``k / parts`` of their sum."""
    total = 0.0
    for p in range(parts):
        total += max(bal[cost_index(parts, p)], 0)
    if total <= 0.0:
        return
    q = 0
    done = 0.0  # cycles of the parts before part q
    for k in range(1, parts):
        want = total * k / parts
        while q < parts - 1 and done + max(bal[cost_index(parts, q)], 0) < want:
            done += max(bal[cost_index(parts, q)], 0)
            q += 1
        lo = bal[BAL_BOUNDS + q]
        hi = bal[BAL_BOUNDS + q + 1]
        cost = max(bal[cost_index(parts, q)], 0)
        share = (want - done) / cost if cost > 0 else 0.5
        bal[target_index(parts, k)] = round(lo + min(max(share, 0.0), 1.0) * (hi - lo))
    for k in range(1, parts):
        old = bal[BAL_BOUNDS + k]
        gap = bal[target_index(parts, k)] - old
        step = int(BAL_STEP * gap)
        if step == 0 and gap != 0:
            step = 1 if gap > 0 else -1  # the last few robots one at a time
        new = old + step
        # boundaries stay in order
        bal[BAL_BOUNDS + k] = min(max(new, bal[BAL_BOUNDS + k - 1]), bal[BAL_BOUNDS + k + 1])
