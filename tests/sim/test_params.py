"""Simulator parameters: TOML loading, overrides and one-line errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from etswarm.errors import EtswarmError
from etswarm.sim import SimParams


def test_defaults_follow_the_design() -> None:
    p = SimParams()
    assert (p.ticks_per_s, p.tx_period, p.comm_range_mm, p.body_radius_mm) == (31, 15, 70.0, 16.5)
    assert (p.speed_mm_s, p.turn_rate_deg_s, p.inbox_capacity) == (7.0, 13.0, 32)


def test_toml_file_with_and_without_table(tmp_path: Path) -> None:
    f = tmp_path / "a.toml"
    f.write_text("loss = 0.2\ndist_noise_mm = 2\n")
    assert SimParams.from_toml(f).loss == 0.2
    g = tmp_path / "b.toml"
    g.write_text("[sim]\ntx_period = 10\n[et]\nwhatever = 1\n")
    assert SimParams.from_toml(g).tx_period == 10


@pytest.mark.parametrize(
    ("text", "pattern"),
    [
        ("lose = 0.2\n", r"unknown sim parameter 'lose' in .*bad.toml"),
        ("loss = 1.5\n", r"sim parameter loss in .*bad.toml: 1.5 is outside \[0, 1\]"),
        ("tx_period = 2.5\n", r"tx_period .* expected an integer"),
        ("speed_mm_s = 'fast'\n", r"speed_mm_s .* expected a number"),
        ("loss = \n", r"invalid TOML"),
        ("portable_math = 1\n", r"portable_math .* expected true or false, got 1"),
    ],
)
def test_bad_files_give_one_line_errors(tmp_path: Path, text: str, pattern: str) -> None:
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(EtswarmError, match=pattern) as err:
        SimParams.from_toml(f)
    assert "\n" not in str(err.value)


def test_overrides_and_missing_file(tmp_path: Path) -> None:
    p = SimParams().with_overrides(loss=0.3, dist_noise_mm=None)
    assert p.loss == 0.3 and p.dist_noise_mm == 0.0
    with pytest.raises(EtswarmError, match="unknown sim parameter 'speed'"):
        SimParams().with_overrides(speed=3)
    with pytest.raises(EtswarmError, match="comm_range_mm: -1 is outside"):
        SimParams(comm_range_mm=-1)
    with pytest.raises(EtswarmError, match="not found"):
        SimParams.from_toml(tmp_path / "nope.toml")


def test_portable_math_from_toml_and_in_the_header(tmp_path: Path) -> None:
    f = tmp_path / "p.toml"
    f.write_text("portable_math = false\n")
    p = SimParams.from_toml(f)
    assert p.portable_math is False and p.kernel_config().portable is False
    # headers always say which maths ran (files before session 53 lack the key: native)
    assert p.to_dict()["portable_math"] is False
    assert SimParams().to_dict()["portable_math"] is True
    assert SimParams().kernel_config().portable is True  # the default since session 53
