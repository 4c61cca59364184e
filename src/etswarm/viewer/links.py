"""Communication links: pairs of talking robots within IR range."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree


def comm_links(pos: np.ndarray, talking: np.ndarray, range_mm: float) -> np.ndarray:
    """Pairs of robots that can hear each other.

    Args:
        pos: (N, 2) robot centres (mm).
        talking: (N,) bool, robots that take part (present and alive).
        range_mm: IR range, centre to centre (mm); pairs strictly closer are linked.

    Returns:
        (L, 2) int array of robot indices ``i < j``.
    """
    idx = np.flatnonzero(talking)
    if idx.size < 2 or range_mm <= 0:
        return np.zeros((0, 2), np.int64)
    tree = cKDTree(pos[idx])
    pairs = tree.query_pairs(np.nextafter(range_mm, 0), output_type="ndarray")
    if pairs.size == 0:
        return np.zeros((0, 2), np.int64)
    return np.sort(idx[pairs], axis=1)
