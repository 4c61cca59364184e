"""Splitting a controller's per-robot work between threads by what it cost last tick.

The split loop (:mod:`etswarm.sim.kernel`, ``SimParams.control_threads > 1``) runs the
controller's ``part_step`` on every thread, each on its own range of robot indices.
Ranges handed out afresh every tick (pieces taken from a shared counter) sent a robot's
memory rows to whichever core took its piece; in an ET formation of 1000 robots the
controller's work then cost 1.7 times the CPU of one thread, and two threads ran no
faster than one. So each thread keeps one range of robots from tick to tick, and the
ranges follow the work: every thread times its range (CPU cycles), and after each tick
the boundaries move part of the way towards the points that would have split that
tick's cost evenly, each shift of cycles priced in robots at the mean cost per robot of
the two ranges beside the boundary.

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
    cycles would have reached ``k / parts`` of their sum.

    The cycles a boundary must shift are priced in robots at the mean of the two
    neighbouring parts' cycles per robot, the same price whichever way it moves. Pricing
    each move at the cost of the part it moves into (each part's cycles spread evenly over
    its robots) moved the boundary further when the part before it was the cheaper one
    (the cheap Queued robots of the high IDs) than back when it was dearer (thread 0's
    searchers, with its radio and motion): the boundary then stood where the first part
    cost 3 µs a tick more than the second, on average (disc1000, session 72)."""
    total = 0.0
    for p in range(parts):
        total += max(bal[cost_index(parts, p)], 0)
    if total <= 0.0:
        return
    before = 0.0  # cycles of the parts before boundary k
    for k in range(1, parts):
        before += max(bal[cost_index(parts, k - 1)], 0)
        excess = before - total * k / parts
        price = 0.0
        for p in (k - 1, k):
            robots = max(bal[BAL_BOUNDS + p + 1] - bal[BAL_BOUNDS + p], 1)
            price += 0.5 * max(bal[cost_index(parts, p)], 0) / robots
        old = bal[BAL_BOUNDS + k]
        bal[target_index(parts, k)] = old if price <= 0.0 else round(old - excess / price)
    for k in range(1, parts):
        old = bal[BAL_BOUNDS + k]
        gap = bal[target_index(parts, k)] - old
        step = int(BAL_STEP * gap)
        if step == 0 and gap != 0:
            step = 1 if gap > 0 else -1  # the last few robots one at a time
        new = old + step
        # boundaries stay in order
        bal[BAL_BOUNDS + k] = min(max(new, bal[BAL_BOUNDS + k - 1]), bal[BAL_BOUNDS + k + 1])
