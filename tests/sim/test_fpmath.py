"""The portable maths functions: accurate, and the same bits whatever maths code the CPU
gets from glibc (a stand-in for another machine)."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

from etswarm.sim import fpmath

#: Switches off glibc's FMA and AVX2 variants of its maths functions (names of glibc 2.26-2.32
#: and of later versions; unknown names are ignored).
NO_FMA = "glibc.cpu.hwcaps=-AVX2_Usable,-FMA_Usable,-AVX2,-FMA"


def ulps(ours: float, ref: float) -> float:
    """How many units in the last place of ``ref`` lie between the two."""
    return abs(ours - ref) / np.spacing(abs(ref)) if ref != 0 else abs(ours) / np.spacing(0.0)


#: The part of pi/2 that ``fpmath.sin_cos``'s three-term reduction leaves out (fdlibm's
#: ``pio2_3t``, 8.48e-32), rounded up: each of the k quarter turns taken off the argument
#: errs by this much, absolutely.
PIO2_TAIL = 8.5e-32


@settings(deadline=None)  # the first call may compile
@given(st.floats(min_value=-1e5, max_value=1e5, allow_nan=False))
def test_sine_and_cosine_within_two_ulps_of_libm(x: float) -> None:
    """Two units in the last place, plus the reduction's absolute error near a zero of the
    sine or cosine, where the result is tiny: found by hypothesis at x = pi/2 (to double
    precision), whose cosine 6.12e-17 came out 8.6e-32 (7 of its units) from libm's."""
    s, c = fpmath.sin_cos(x)
    turns = abs(round(x / (math.pi / 2)))
    for ours, ref in ((s, math.sin(x)), (c, math.cos(x))):
        assert abs(ours - ref) <= 2 * np.spacing(max(abs(ref), 1e-300)) + turns * PIO2_TAIL


def test_the_cosine_of_a_quarter_turn_errs_by_the_reduction_not_by_two_units() -> None:
    ref = math.cos(math.pi / 2)
    error = abs(fpmath.sin_cos(math.pi / 2)[1] - ref)
    assert 2 * np.spacing(ref) < error <= 2 * np.spacing(ref) + PIO2_TAIL


@settings(deadline=None)  # the first call may compile
@given(
    st.floats(min_value=-1e8, max_value=1e8, allow_nan=False),
    st.floats(min_value=-1e8, max_value=1e8, allow_nan=False),
)
def test_atan2_within_two_ulps_of_libm(y: float, x: float) -> None:
    assert ulps(fpmath.atan2(y, x), math.atan2(y, x)) <= 2


@settings(deadline=None)  # the first call may compile
@given(st.floats(min_value=1e-300, max_value=1e300))
def test_log_within_one_ulp_of_libm(x: float) -> None:
    assert ulps(fpmath.log(x), math.log(x)) <= 1


@settings(deadline=None)  # the first call may compile
@given(st.floats(min_value=-745.0, max_value=709.0))
def test_exp_within_one_ulp_of_libm(x: float) -> None:
    ref = math.exp(x)
    if ref > 1e-300:
        assert ulps(fpmath.exp(x), ref) <= 1


def test_the_ziggurat_tables_match_their_numbers() -> None:
    """The base layer and each layer hold the same area under exp(-x^2 / 2), the edges
    fall to 0, and the compiled and Python exp agree bit for bit on them."""
    x, f = fpmath._ZIG_X, fpmath._ZIG_F
    assert x[1] == fpmath._ZIG_R and x[-1] == 0.0 and np.all(np.diff(x) < 0)
    assert 0.0 < x[-2] < 0.3  # the top layer is the thin cap
    areas = x[1:-1] * (f[2:] - f[1:-1])
    assert np.allclose(areas, fpmath._ZIG_AREA, rtol=1e-9)
    assert all(fpmath.exp(v) == fpmath.exp.py_func(v) for v in -0.5 * x * x)


def test_special_values_follow_the_math_module() -> None:
    for y, x in [(0.0, 1.0), (0.0, -1.0), (-0.0, -1.0), (1.0, 0.0), (-1.0, 0.0), (2.0, -2.0),
                 (math.inf, math.inf), (-math.inf, -math.inf), (1.0, -math.inf)]:
        assert fpmath.atan2(y, x) == pytest.approx(math.atan2(y, x), rel=1e-15, abs=0.0)
    assert fpmath.log(1.0) == 0.0
    assert fpmath.log(0.0) == -math.inf
    assert math.isnan(fpmath.log(-1.0))
    assert fpmath.sin_cos(0.0) == (0.0, 1.0)


def test_normal_draws_follow_the_normal_distribution() -> None:
    draws = fpmath.normal_array(np.random.default_rng(3), 400_001)
    assert draws.shape == (400_001,)
    assert abs(draws.mean()) < 0.006
    assert abs(draws.std() - 1.0) < 0.005
    assert stats.kstest(draws, "norm").pvalue > 1e-3
    for edge in (1.0, 1.96, 3.0, 3.8):  # the last beyond r: the tail
        share = np.mean(np.abs(draws) > edge)
        expect = 2.0 * stats.norm.sf(edge)
        assert abs(share - expect) < 5.0 * np.sqrt(expect / draws.size) + 1e-6, edge


PROBE = textwrap.dedent(
    """
    import hashlib, numpy as np
    from etswarm.sim import fpmath
    rng = np.random.default_rng(11)
    x = rng.uniform(-7.0, 7.0, 200_000)
    y = rng.uniform(-7.0, 7.0, 200_000)
    s, c = fpmath.sin_cos_array(x)
    parts = [s, c, fpmath.atan2_array(y, x), np.array([fpmath.log(v) for v in np.abs(x[:20000])]),
             fpmath.normal_array(np.random.default_rng(4), 20_000)]
    print(hashlib.sha256(b"".join(p.tobytes() for p in parts)).hexdigest())
    """
)


def run_probe(env: dict[str, str], script: str) -> str:
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                          text=True, timeout=600, check=True)
    return done.stdout.strip().splitlines()[-1]


def test_same_bits_with_and_without_glibc_fma_code() -> None:
    """glibc's own sin and cos give other bits here without FMA (checked on the machine
    this was written on); ours must not."""
    base = dict(os.environ)
    plain = run_probe(base, PROBE)
    other = run_probe({**base, "GLIBC_TUNABLES": NO_FMA}, PROBE)
    assert plain == other


FORMATION = textwrap.dedent(
    """
    import hashlib
    from etswarm.algorithm.run import ETRun, RunConfig
    from etswarm.sim import SimParams
    run = ETRun(RunConfig(shape="starfish", seed=1, max_time_s=2000.0),
                sim_params=SimParams(portable_math=True))
    run.advance(int(2000 * run.ticks_per_s))
    w = run.world
    print(hashlib.sha256(w.pos.tobytes() + w.heading.tobytes()
                         + run.controller.states.tobytes()).hexdigest())
    """
)

RANDOM_WALKS = textwrap.dedent(
    """
    import hashlib
    from etswarm.sim import RandomWalk, SimParams, Simulator, random_world
    digest = hashlib.sha256()
    for threads in (1, 2):
        p = SimParams(arena_mm=700.0, loss=0.2, dist_noise_mm=2.0, heading_noise_deg=2.0,
                      speed_noise=0.1, speed_spread=0.1, turn_rate_spread=0.1,
                      threads=threads, portable_math=True)
        sim = Simulator(random_world(200, p, 5), RandomWalk(200), p, 5)
        sim.run_ticks(3000)
        for arr in sim.world.state_arrays().values():
            digest.update(arr.tobytes())
    print(digest.hexdigest())
    """
)


def test_a_portable_formation_gives_the_same_state_without_glibc_fma_code() -> None:
    """A starfish grown for 2000 s with ``portable_math``: the same positions, headings
    and states. (Without it the two differ on the machine this was written on.)"""
    base = dict(os.environ)
    assert run_probe(base, FORMATION) == run_probe({**base, "GLIBC_TUNABLES": NO_FMA}, FORMATION)


def test_portable_random_walks_with_every_noise_give_the_same_state_without_fma() -> None:
    """The one-thread and the threaded loop, with motion, heading and distance noise (3000
    ticks: without ``portable_math`` these differ on the machine this was written on)."""
    base = dict(os.environ)
    assert run_probe(base, RANDOM_WALKS) == run_probe({**base, "GLIBC_TUNABLES": NO_FMA},
                                                      RANDOM_WALKS)


def test_sweeps_and_the_cli_set_portable_maths() -> None:
    """``sim_portable_math`` in a sweep's parameters and ``--native-math`` on ``etswarm
    run`` reach the run, and its summary says so (portable is the default)."""
    from click.testing import CliRunner

    from etswarm.algorithm.api import run_experiment
    from etswarm.cli.main import cli
    from etswarm.errors import EtswarmError

    off = run_experiment({"shape": "triangle", "seed": 2, "max_time_s": 60.0,
                          "sim_portable_math": False})
    on = run_experiment({"shape": "triangle", "seed": 2, "max_time_s": 60.0})
    assert on["portable_math"] is True and off["portable_math"] is False
    assert "sim_portable_math" in run_experiment.parameters  # type: ignore[attr-defined]
    with pytest.raises(EtswarmError, match="unknown run parameter 'sim_threads'"):
        run_experiment({"shape": "triangle", "sim_threads": 2})
    for flag, shown in (("--native-math", "false"), ("--portable-math", "true"), (None, "true")):
        args = ["run", "triangle", "--max-time", "60", "--json", "--control-threads", "1"]
        result = CliRunner().invoke(cli, args + ([flag] if flag else []))
        assert result.exit_code == 0, result.output
        assert f'"portable_math": {shown}' in result.output


#: The digest ``RANDOM_WALKS`` printed when the portable maths became the default (session
#: 53, x86-64). numpy's generator, numba, or this simulator's physics changing the bits of
#: a run shows here; a deliberate change of the physics records a new one.
RANDOM_WALKS_SESSION_53 = "b6ca5a7fa3a0a4ab493232020986819d4ced16aa107f8d88481a194db64faeb7"


def test_portable_random_walks_give_the_bits_recorded_in_session_53(capsys) -> None:
    """The default run of a seed is the same on every machine, so on every machine it is
    the one recorded here."""
    exec(RANDOM_WALKS, {})
    assert capsys.readouterr().out.strip() == RANDOM_WALKS_SESSION_53
