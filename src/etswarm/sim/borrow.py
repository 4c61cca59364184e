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
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def borrowed(typingctx, a):
    """``a`` (any array) with a null meminfo and parent: the same data, shape and strides,
    no reference counting (see the module doc)."""
    if not isinstance(a, types.Array):
        return None

    def codegen(context, builder, signature, args):
        aryty = signature.args[0]
        ary = cgutils.create_struct_proxy(aryty)(context, builder, value=args[0])
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()

    return a(a), codegen
