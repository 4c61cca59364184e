"""Software prefetch for compiled loops that visit array elements in a scattered order.

``prefetch(a, i)`` asks the CPU to start loading element ``a[i]`` of a 1-D array (for an
array of more dimensions: the start of ``a[i]``, its first element) into the
caches (``llvm.prefetch``: read/write hint "write", highest locality, data cache) and
returns at once. It changes no value and never faults, even for an index out of range,
so a loop can issue it a few iterations ahead of the access without a bounds check.
Used where a phase walks robots in index order but touches their grid slots, which lie
scattered in memory (:mod:`etswarm.sim.motion`).
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.extending import intrinsic


@intrinsic
def prefetch(typingctx, a, i):
    """Hint: fetch ``a[i]`` (the first element of ``a[i]`` if ``a`` has more than one
    dimension; ``i`` an integer) into the cache; no effect on any value."""
    if not isinstance(a, types.Array) or not isinstance(i, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        arr_type, idx_type = signature.args
        arr = context.make_array(arr_type)(context, builder, value=args[0])
        idx = context.cast(builder, args[1], idx_type, types.intp)
        stride = builder.extract_value(arr.strides, 0)
        offset = builder.mul(idx, stride)
        base = builder.ptrtoint(arr.data, ir.IntType(64))
        byte_ptr = ir.IntType(8).as_pointer()
        addr = builder.inttoptr(builder.add(base, offset), byte_ptr)
        i32 = ir.IntType(32)
        fnty = ir.FunctionType(ir.VoidType(), [byte_ptr, i32, i32, i32])
        fn = builder.module.declare_intrinsic("llvm.prefetch", fnty=fnty)
        builder.call(fn, [addr, ir.Constant(i32, 1), ir.Constant(i32, 3), ir.Constant(i32, 1)])
        return context.get_dummy_value()

    return types.void(a, i), codegen
