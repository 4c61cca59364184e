"""Flat-dict entry point for scripts and the sweep runner."""

from __future__ import annotations

from typing import Any

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError

#: Keys ``run_experiment`` accepts (besides ET parameter names, passed as ``et_<name>``).
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


def run_experiment(params: dict[str, Any]) -> dict[str, Any]:
    """Run one ET experiment described by ``params`` and return its JSON summary.

    ``params`` holds RunConfig fields (``RUN_KEYS``; ``damage`` is one spec or a list) and
    optional ET parameters prefixed with ``et_`` (e.g. ``et_release_interval_s``);
    ``census`` is ``"tree"`` or ``"walk"``. Unknown keys are an error.
    """
    run_kwargs: dict[str, Any] = {}
    et_kwargs: dict[str, Any] = {}
    et_names = set(ETParams.__dataclass_fields__)
    for key, value in params.items():
        if key == "damage":
            run_kwargs[key] = (value,) if isinstance(value, str) else tuple(value)
        elif key in RUN_KEYS:
            run_kwargs[key] = value
        elif key.startswith("et_") and key[3:] in et_names:
            et_kwargs[key[3:]] = value
        else:
            raise EtswarmError(f"unknown run parameter {key!r}")
    config = RunConfig(**run_kwargs, et=ETParams(**et_kwargs))
    return ETRun(config).run()


#: The parameter names a sweep may set (checked before any run starts).
run_experiment.parameters = frozenset(  # type: ignore[attr-defined]
    {*RUN_KEYS, *(f"et_{name}" for name in ETParams.__dataclass_fields__)}
)
