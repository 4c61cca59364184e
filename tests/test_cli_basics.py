"""The CLI entry point: version, help, and one-line errors."""

import subprocess
import sys

import numpy as np

from etswarm.seeding import stream


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "etswarm.cli.main", *args], capture_output=True, text=True
    )


def test_version_and_help() -> None:
    out = run_cli("--version")
    assert out.returncode == 0
    assert "etswarm" in out.stdout
    assert run_cli("--help").returncode == 0


def test_unknown_command_is_an_error_without_traceback() -> None:
    out = run_cli("no-such-command")
    assert out.returncode != 0
    assert "Traceback" not in out.stderr


def test_named_streams_are_reproducible_and_independent() -> None:
    a1 = stream(7, "motion").random(5)
    a2 = stream(7, "motion").random(5)
    b = stream(7, "radio").random(5)
    assert np.array_equal(a1, a2)
    assert not np.array_equal(a1, b)


def test_a_bad_option_value_is_one_line_that_names_the_option() -> None:
    out = run_cli("run", "T", "--layout", "ring")
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1
    assert "--layout" in lines[0] and "'ring'" in lines[0]
    assert lines[0].startswith("etswarm run: error:")
    assert "etswarm run --help" in lines[0]


def test_a_missing_argument_is_one_line() -> None:
    out = run_cli("run")
    assert out.returncode == 2
    assert out.stderr.strip().splitlines() == [
        "etswarm run: error: Missing argument 'SHAPE'. (see 'etswarm run --help')"
    ]
