"""Arrays without reference counting, for the hot loops of compiled code.

numba counts references to every array it holds in a variable: an atomic increment when
a variable takes the array (an argument on entry to a function, a name bound to it, an
argument of a function inlined by numba) and an atomic decrement when the variable dies.
Its pruning pass removes only the pairs it can match in simple control flow, so a
function called per robot or per message (or inlined into such a loop) pays a pair of
atomic operations per array argument and call. On one core that costs about as much as
the work itself; on two cores both threads update the same counters, whose cache line
then moves between the cores on every update.

``borrowed(a)`` is ``a`` without its reference count (its meminfo pointer is null, for
which numba's increment and decrement return at once). It is only valid while the
caller holds ``a`` itself: take it at the start of a compiled function for the arrays its
loops use, never return or keep it.

A null meminfo still costs a call per array and use (``NRT_incref`` and ``NRT_decref`` are
never inlined; they test the pointer and return). The hottest work therefore runs in
functions compiled with no reference counting at all (``@njit(_nrt=False)``), which the
functions they call inherit unless they set it themselves: the controller's per-robot
loop (``controller.busy_part``), the radio's deliveries (``radio.deliver``), motion
(``motion.move_phase``) and collisions (``collide.resolve_overlaps``). Such a function
may not allocate, and an array a callee allocated and returned to it would never be
freed: the few functions that allocate, and those that take an allocated array back,
say ``_nrt=True`` (``tests/algorithm/test_no_counting_leaks.py`` runs a regeneration
with numba's allocation statistics on and finds every block freed). On disc1000 from
3000 s this took the tick from 78 to 64 µs of CPU (``benchmarks/profile_phases.py``).
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


def _strip(context, builder, typ, value):  # type: ignore[no-untyped-def]
    """``value`` of type ``typ`` with every array in it (tuples recursively) borrowed."""
    if isinstance(typ, types.Array):
        ary = cgutils.create_struct_proxy(typ)(context, builder, value=value)
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()
    if isinstance(typ, types.BaseTuple):
        for k, member in enumerate(typ):
            item = builder.extract_value(value, k)
            value = builder.insert_value(value, _strip(context, builder, member, item), k)
    return value


def _borrowable(typ) -> bool:  # type: ignore[no-untyped-def]
    """An array, a number or a boolean, or a tuple of such (nested): types whose values
    hold no reference counted object but arrays."""
    if isinstance(typ, types.BaseTuple):
        return all(_borrowable(t) for t in typ)
    return isinstance(typ, (types.Array, types.Number, types.Boolean))


@intrinsic
def borrowed(typingctx, a):
    """``a`` (an array, or a tuple or named tuple of arrays and numbers) with a null
    meminfo and parent in every array: the same data, shape and strides, no reference
    counting (see the module doc)."""
    if not _borrowable(a):
        return None

    def codegen(context, builder, signature, args):
        return _strip(context, builder, signature.args[0], args[0])

    return a(a), codegen
