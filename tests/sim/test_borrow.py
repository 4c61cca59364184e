"""A borrowed array is the same array without reference counting."""

from __future__ import annotations

import sys
from typing import NamedTuple

import numpy as np
from numba import njit

from etswarm.sim.borrow import borrowed


@njit
def _bump(a, k):  # type: ignore[no-untyped-def]
    """Add 1 to a[k] (a callee that receives the array per call)."""
    a[k] += 1


@njit
def fill_borrowed(a, t):  # type: ignore[no-untyped-def]
    """Write through borrowed views of a 1-D array and a transposed 3-D view."""
    b = borrowed(a)
    u = borrowed(t)
    for k in range(b.shape[0]):
        _bump(b, k)
        b[k] += k
    for i in range(u.shape[0]):
        for j in range(u.shape[1]):
            u[i, j, 1] = i * 100 + j
    return b.sum(), u[u.shape[0] - 1, u.shape[1] - 1, 1]


def test_borrowed_reads_and_writes_the_array() -> None:
    a = np.zeros(50)
    t = np.zeros((4, 3, 5)).transpose(0, 2, 1)  # (4, 5, 3), not contiguous
    refs = sys.getrefcount(a), sys.getrefcount(t)
    total, last = fill_borrowed(a, t)
    assert np.array_equal(a, np.arange(50) + 1.0)
    assert total == a.sum()
    assert np.array_equal(t[:, :, 1], np.arange(4)[:, None] * 100 + np.arange(5)[None, :])
    assert last == 304
    assert not t[:, :, 0].any() and not t[:, :, 2].any()
    assert (sys.getrefcount(a), sys.getrefcount(t)) == refs  # nothing kept or leaked


class _Pair(NamedTuple):
    a: np.ndarray
    k: int


@njit
def tuple_sums(pair, both):  # type: ignore[no-untyped-def]
    """Borrow a named tuple (array and number) and a plain tuple of arrays, write, sum."""
    p = borrowed(pair)
    x, y = borrowed(both)
    p.a[p.k] = 7.0
    x[0] += y[1]
    return p.a.sum(), x[0]


def test_borrowed_tuples_keep_their_members() -> None:
    pair = _Pair(np.zeros(4), 2)
    both = (np.ones(3), np.arange(3.0))
    assert tuple_sums(pair, both) == (7.0, 2.0)
    assert pair.a[2] == 7.0 and both[0][0] == 2.0
