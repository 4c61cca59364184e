"""The ET controller packaged for the simulator: kernel, robot memory and the gene.

``ETController`` owns the arrays of every robot's private memory (see ``memory``) and the
gene grids, and exposes them as the ``mem`` tuple the compiled ``et_step`` receives.
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.controller import et_step
from etswarm.algorithm.layout import Layout
from etswarm.algorithm.memory import (
    R_FLOOR_SINCE,
    R_NN,
    R_QMIN_SINCE,
    R_SINCE,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    allocate,
)
from etswarm.algorithm.params import C_GENE_X0, C_GENE_Y0, ETParams
from etswarm.algorithm.states import State
from etswarm.shapes.lattice import neighbour_counts


def gene_grids(cells: np.ndarray) -> tuple[np.ndarray, np.ndarray, int, int]:
    """Dense gene lookup for a cell set: ``(flag (GX, GY) uint8, nn (GX, GY) int8, x0, y0)``.

    ``flag[X - x0, Y - y0]`` is 1 on the cells; ``nn`` counts each cell's neighbours among
    the cells. The grid has a one-cell margin of zeros.
    """
    cells = np.asarray(cells, dtype=np.int64)
    x0 = int(cells[:, 0].min()) - 1
    y0 = int(cells[:, 1].min()) - 1
    gx = int(cells[:, 0].max()) - x0 + 2
    gy = int(cells[:, 1].max()) - y0 + 2
    flag = np.zeros((gx, gy), dtype=np.uint8)
    nn = np.zeros((gx, gy), dtype=np.int8)
    flag[cells[:, 0] - x0, cells[:, 1] - y0] = 1
    nn[cells[:, 0] - x0, cells[:, 1] - y0] = neighbour_counts(cells)
    return flag, nn, x0, y0


class ETController:
    """The ET controller in the simulator's fast-path form: ``step`` and ``mem``."""

    step = staticmethod(et_step)

    def __init__(self, n_robots: int, target: np.ndarray, et: ETParams, ticks_per_s: int):
        self.ri, self.nb, self.nb_dist = allocate(n_robots)
        self.stop = np.zeros(1, dtype=np.int64)
        self.et = et
        self.ticks_per_s = ticks_per_s
        self.set_target(target)

    def set_target(self, target: np.ndarray) -> None:
        """Load the gene of ``target`` ((P, 2) tags) into every robot."""
        self.target = np.asarray(target, dtype=np.int64)
        flag, nn, x0, y0 = gene_grids(self.target)
        self.gene_flag, self.gene_nn = flag, nn
        release_limit = max(0, len(self.target) - 3)
        self.ci, self.cf = self.et.pack(self.ticks_per_s, release_limit, x0, y0)

    @property
    def mem(self) -> tuple:
        return (
            self.stop, self.ri, self.nb, self.nb_dist, self.gene_flag, self.gene_nn,
            self.ci, self.cf,
        )

    def seed(self, layout: Layout) -> None:
        """Initialise the seeds (paper: one Active TS 1, two Inactive TS 2)."""
        ri = self.ri
        ri[:, R_FLOOR_SINCE] = -(10**9)
        ri[:, R_QMIN_SINCE] = 0
        for k, (rid, (x, y)) in enumerate(zip(layout.seed_ids, layout.seed_tags, strict=True)):
            ri[rid, R_STATE] = State.ACTIVE if k == 0 else State.INACTIVE
            ri[rid, R_TS] = 1 if k == 0 else 2
            ri[rid, R_TAG_X] = x
            ri[rid, R_TAG_Y] = y
            ri[rid, R_NN] = self.gene_nn[x - self.ci[C_GENE_X0], y - self.ci[C_GENE_Y0]]
            ri[rid, R_SINCE] = 0

    @property
    def states(self) -> np.ndarray:
        """(N,) int64 state codes."""
        return self.ri[:, R_STATE]

    @property
    def tags(self) -> np.ndarray:
        """(N, 2) int64 tags (meaningful where the robot is placed)."""
        return self.ri[:, [R_TAG_X, R_TAG_Y]]
