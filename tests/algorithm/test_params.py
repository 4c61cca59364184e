"""ETParams: range checks, the ``--et NAME=VALUE`` parser and its CLI option."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from etswarm.algorithm.params import (
    C_LOST_HOMING,
    F_PAIR_AIM,
    F_WIDEN_MAX,
    LOST_HOMING_AHEAD,
    LOST_HOMING_ON,
    ETParams,
    parse_et_option,
)
from etswarm.cli.run_command import run as run_command
from etswarm.errors import EtswarmError


def test_et_options_parse_to_the_field_type() -> None:
    assert parse_et_option("pair_aim_mm=-1.5") == ("pair_aim_mm", -1.5)
    assert parse_et_option("widen-max=2") == ("widen_max", 2.0)
    assert parse_et_option("eval_every_ticks=3") == ("eval_every_ticks", 3)
    assert parse_et_option("census=walk") == ("census", "walk")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("pair_aim", "expected NAME=VALUE"),
        ("bogus=1", "expected NAME=VALUE"),
        ("pair_aim_mm=", "expected NAME=VALUE"),
        ("pair_aim_mm=near", "pair_aim_mm takes a number"),
        ("eval_every_ticks=1.5", "eval_every_ticks takes a number"),
    ],
)
def test_bad_et_options_are_one_line_errors(text: str, message: str) -> None:
    with pytest.raises(EtswarmError, match=message) as err:
        parse_et_option(text)
    assert "\n" not in str(err.value)


def test_signed_and_bounded_fields() -> None:
    _ci, cf = ETParams(pair_aim_mm=-2.0, follow_offset_mm=-1.0, widen_max=1.0).pack(31, 0, 0)
    assert cf[F_PAIR_AIM] == -2.0 and cf[F_WIDEN_MAX] == 1.0
    with pytest.raises(EtswarmError, match="widen_max must be >= 1"):
        ETParams(widen_max=0.5)
    with pytest.raises(EtswarmError, match="pair_tol_mm must be > 0"):
        ETParams(pair_tol_mm=-1.0)


def test_lost_homing_takes_three_modes() -> None:
    modes = ("off", "on", "ahead")
    codes = [ETParams(lost_homing=m).pack(31, 0, 0)[0][C_LOST_HOMING] for m in modes]
    assert codes == [0, LOST_HOMING_ON, LOST_HOMING_AHEAD]
    with pytest.raises(EtswarmError, match="lost_homing must be one of") as err:
        ETParams(lost_homing="forward")
    assert "\n" not in str(err.value)


def test_the_run_command_takes_et_options() -> None:
    ok = CliRunner().invoke(
        run_command, ["triangle", "--et", "pair_aim_mm=-1", "--max-time", "2", "--json"]
    )
    assert ok.exit_code == 0, ok.output
    bad = CliRunner().invoke(run_command, ["triangle", "--et", "widen_max=0.5", "--json"])
    assert bad.exit_code != 0
    assert isinstance(bad.exception, EtswarmError)  # the CLI group prints it on one line
    assert "widen_max must be >= 1" in str(bad.exception)


def test_the_pair_window_centre_relaxes_back_to_d() -> None:
    from etswarm.algorithm.localise import window_centre

    minutes = 31 * 60
    _ci, fixed = ETParams(pair_aim_mm=-2.0).pack(31, 0, 0)
    _ci, relaxing = ETParams(pair_aim_mm=-2.0, pair_aim_relax_s=600.0).pack(31, 0, 0)
    assert window_centre(fixed, 0) == window_centre(fixed, 60 * minutes) == 38.0
    assert window_centre(relaxing, 0) == 38.0
    assert window_centre(relaxing, 5 * minutes) == pytest.approx(39.0)
    assert window_centre(relaxing, 10 * minutes) == window_centre(relaxing, 99 * minutes) == 40.0
    with pytest.raises(EtswarmError, match="pair_aim_relax_s must be >= 0"):
        ETParams(pair_aim_relax_s=-1.0)
