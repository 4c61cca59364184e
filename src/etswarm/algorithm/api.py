"""Flat-dict entry point for scripts and the sweep runner."""

from __future__ import annotations

from typing import Any

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError
from etswarm.sim.params import SimParams

#: Keys ``run_experiment`` accepts (besides ET parameter names, passed as ``et_<name>``, and
#: simulator parameters, as ``sim_<name>``).
RUN_KEYS = (
    "shape",
    "robots",
    "seed",
    "loss",
    "noise_mm",
    "max_time_s",
    "layout",
    "fit",
    "damage",
    "census",
)

#: Simulator parameters ``run_experiment`` accepts as ``sim_<name>``: every SimParams field
#: but the run's own ``loss`` and ``dist_noise_mm`` (``loss``, ``noise_mm``) and the
#: thread counts (a sweep runs one thread per worker).
SIM_KEYS = frozenset(SimParams.__dataclass_fields__) - {
    "loss", "dist_noise_mm", "source", "threads", "control_threads",
}


def run_experiment(params: dict[str, Any]) -> dict[str, Any]:
    """Run one ET experiment described by ``params`` and return its JSON summary.

    ``params`` holds RunConfig fields (``RUN_KEYS``; ``damage`` is one spec or a list) and
    optional ET parameters prefixed with ``et_`` (e.g. ``et_release_interval_s``) and
    simulator parameters prefixed with ``sim_`` (``SIM_KEYS``, e.g. ``sim_portable_math``);
    ``census`` is ``"tree"`` or ``"walk"``. Unknown keys are an error.
    """
    run_kwargs: dict[str, Any] = {}
    et_kwargs: dict[str, Any] = {}
    sim_kwargs: dict[str, Any] = {}
    et_names = set(ETParams.__dataclass_fields__)
    for key, value in params.items():
        if key == "damage":
            run_kwargs[key] = (value,) if isinstance(value, str) else tuple(value)
        elif key in RUN_KEYS:
            run_kwargs[key] = value
        elif key.startswith("et_") and key[3:] in et_names:
            et_kwargs[key[3:]] = value
        elif key.startswith("sim_") and key[4:] in SIM_KEYS:
            sim_kwargs[key[4:]] = value
        else:
            raise EtswarmError(f"unknown run parameter {key!r}")
    config = RunConfig(**run_kwargs, et=ETParams(**et_kwargs))
    return ETRun(config, sim_params=SimParams(**sim_kwargs)).run()


#: The parameter names a sweep may set (checked before any run starts).
run_experiment.parameters = frozenset(  # type: ignore[attr-defined]
    {*RUN_KEYS, *(f"et_{name}" for name in ETParams.__dataclass_fields__),
     *(f"sim_{name}" for name in SIM_KEYS)}
)
