"""Per-robot residuals of the rigid fit, and the RMS placement error built on them."""

from __future__ import annotations

import math

import numpy as np

from etswarm.measures.formation import fit_residuals_mm, placement_error_mm
from etswarm.shapes.lattice import tags_to_xy

D = 40.0
TAGS = np.array([(x, y) for x in range(-2, 3) for y in range(-2, 3)], dtype=np.int64)


def placed_rotated(angle: float, shift: tuple[float, float]) -> np.ndarray:
    """The ideal sites of ``TAGS`` turned by ``angle`` rad and moved by ``shift`` mm."""
    c, s = math.cos(angle), math.sin(angle)
    return tags_to_xy(TAGS, D) @ np.array([[c, s], [-s, c]]) + np.array(shift)


def test_a_rigidly_moved_lattice_has_no_residuals() -> None:
    pos = placed_rotated(0.7, (123.0, -45.0))
    resid = fit_residuals_mm(pos, TAGS, np.ones(len(TAGS), dtype=bool), D)
    assert resid is not None and resid.shape == (len(TAGS), 2)
    assert np.abs(resid).max() < 1e-9


def test_one_robot_off_its_site_stands_out_and_the_rms_agrees() -> None:
    pos = placed_rotated(-0.3, (10.0, 20.0))
    pos[7] += (25.0, 0.0)
    holds = np.ones(len(TAGS), dtype=bool)
    norms = np.linalg.norm(fit_residuals_mm(pos, TAGS, holds, D), axis=1)
    assert int(np.argmax(norms)) == 7 and norms[7] > 20.0
    assert np.delete(norms, 7).max() < 5.0
    assert placement_error_mm(pos, TAGS, holds, D) == math.sqrt(float(np.mean(
        np.sum(fit_residuals_mm(pos, TAGS, holds, D) ** 2, axis=1))))


def test_only_robots_that_hold_a_tag_are_fitted() -> None:
    pos = placed_rotated(0.2, (0.0, 0.0))
    holds = np.zeros(len(TAGS), dtype=bool)
    holds[[0, 5, 12]] = True
    pos[3] += (500.0, 500.0)  # holds nothing: must not bend the fit
    resid = fit_residuals_mm(pos, TAGS, holds, D)
    assert resid is not None and resid.shape == (3, 2) and np.abs(resid).max() < 1e-9
    holds[[5, 12]] = False
    assert fit_residuals_mm(pos, TAGS, holds, D) is None
    assert placement_error_mm(pos, TAGS, holds, D) is None
