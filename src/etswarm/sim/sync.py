"""Thread synchronisation for the threaded tick loop: atomics and a barrier.

The threaded kernel (:mod:`etswarm.sim.kernel`, threads > 1) starts its threads once per
call (one ``prange`` iteration per thread) and separates the phases of every tick with
:func:`barrier` instead of starting a parallel loop per phase: a barrier costs well under
a microsecond when the threads have cores to themselves. A thread that waits spins on
an atomic load and, after ``SPINS_BEFORE_YIELD`` rounds, calls ``sched_yield`` in every
round, so on a machine busy with other work it gives its core away instead of burning it.

``sync`` is a (2,) int64 array: [threads arrived, generation]; start it at zero. Every
one of the ``threads`` threads must call :func:`barrier` the same number of times, and
the threads must really run at the same time (one thread per prange iteration).
"""

from __future__ import annotations

from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

#: Spin rounds before a waiting thread starts yielding its core.
SPINS_BEFORE_YIELD = 2000


def _item_pointer(context, builder, arr_type, arr, idx):
    """Pointer to item ``idx`` of a contiguous 1-D array."""
    array = context.make_array(arr_type)(context, builder, value=arr)
    return builder.gep(array.data, [idx])


def _is_int64_vector(arr, idx) -> bool:  # type: ignore[no-untyped-def]
    """The numba types of an atomic operation's target: a 1-D int64 array and an integer
    index."""
    return (isinstance(arr, types.Array) and arr.dtype == types.int64 and arr.ndim == 1
            and isinstance(idx, types.Integer))


@intrinsic
def atomic_add(typingctx, arr, idx, val):
    """``arr[idx] += val`` as one atomic step (int64 array); returns the old value."""
    if not (_is_int64_vector(arr, idx) and isinstance(val, types.Integer)):
        return None

    def codegen(context, builder, signature, args):
        ptr = _item_pointer(context, builder, signature.args[0], args[0], args[1])
        value = context.cast(builder, args[2], signature.args[2], types.int64)
        return builder.atomic_rmw("add", ptr, value, "seq_cst")

    return types.int64(arr, idx, val), codegen


@intrinsic
def atomic_load(typingctx, arr, idx):
    """``arr[idx]`` read atomically (int64 array; never cached in a register)."""
    if not _is_int64_vector(arr, idx):
        return None

    def codegen(context, builder, signature, args):
        ptr = _item_pointer(context, builder, signature.args[0], args[0], args[1])
        return builder.load_atomic(ptr, "seq_cst", 8)

    return types.int64(arr, idx), codegen


@intrinsic
def atomic_store(typingctx, arr, idx, val):
    """``arr[idx] = val`` as one atomic store (int64 array): everything this thread wrote
    before it is visible to a thread that reads the value with :func:`atomic_load`."""
    if not (_is_int64_vector(arr, idx) and isinstance(val, types.Integer)):
        return None

    def codegen(context, builder, signature, args):
        ptr = _item_pointer(context, builder, signature.args[0], args[0], args[1])
        value = context.cast(builder, args[2], signature.args[2], types.int64)
        builder.store_atomic(value, ptr, "seq_cst", 8)
        return context.get_dummy_value()

    return types.void(arr, idx, val), codegen


@intrinsic
def sched_yield(typingctx):
    """Call the C library's ``sched_yield`` (let another runnable thread have the core)."""

    def codegen(context, builder, signature, args):
        fnty = ir.FunctionType(ir.IntType(32), [])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "sched_yield")
        builder.call(fn, [])
        return context.get_dummy_value()

    return types.void(), codegen


@njit(cache=True)
def arrive(sync, threads):
    """Barrier whose last thread to arrive is let through alone: it gets True and must
    call :func:`release` (after doing work no other thread may overlap); the others
    get False once it has. Saves a second barrier around one-thread work."""
    generation = atomic_load(sync, 1)
    if atomic_add(sync, 0, 1) == threads - 1:
        atomic_add(sync, 0, -threads)
        return True
    spins = 0
    while atomic_load(sync, 1) == generation:
        spins += 1
        if spins > SPINS_BEFORE_YIELD:
            sched_yield()
    return False


@njit(cache=True)
def arrive_as(sync, threads, chosen):
    """:func:`arrive` whose thread let through alone is the one that passes ``chosen``
    True, once every other thread has arrived, whichever was last. Exactly one thread
    per barrier must pass True, and it must call :func:`release`."""
    if chosen:
        wait_for(sync, 0, threads - 1)
        atomic_add(sync, 0, 1 - threads)
        return True
    generation = atomic_load(sync, 1)
    atomic_add(sync, 0, 1)
    spins = 0
    while atomic_load(sync, 1) == generation:
        spins += 1
        if spins > SPINS_BEFORE_YIELD:
            sched_yield()
    return False


@njit(cache=True)
def release(sync):
    """Let the threads waiting in :func:`arrive` go on."""
    atomic_add(sync, 1, 1)


@njit(cache=True)
def wait_for(arr, idx, value):
    """Wait until ``arr[idx]`` (int64, written with :func:`atomic_store` by another
    thread) equals ``value``; spins, then yields as :func:`barrier` does."""
    spins = 0
    while atomic_load(arr, idx) != value:
        spins += 1
        if spins > SPINS_BEFORE_YIELD:
            sched_yield()


@njit(cache=True)
def barrier(sync, threads):
    """Wait until all ``threads`` threads have called this (see module doc)."""
    generation = atomic_load(sync, 1)
    if atomic_add(sync, 0, 1) == threads - 1:
        atomic_add(sync, 0, -threads)
        atomic_add(sync, 1, 1)
        return
    spins = 0
    while atomic_load(sync, 1) == generation:
        spins += 1
        if spins > SPINS_BEFORE_YIELD:
            sched_yield()
