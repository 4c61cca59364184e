"""Read a saved run directory into a :class:`~etswarm.viewer.record.RunRecord`.

A run directory holds the simulator's ``recording.npz`` (see
:mod:`etswarm.sim.recorder`) and optionally the ET runner's ``summary.json`` whose
``events`` list (``[{"t_s": float, "kind": str, ...}]``) marks formation, damage and
regeneration. ``RUN_DIR`` may also name the ``.npz`` file itself.

The recording's ``led`` column holds the ET state code when the header says the run was
an ET run (``controller`` is ``"et"``, or the header names a ``shape``); for any other
controller (the random walk writes a neighbour count there) robots are drawn without a
state. Optional extra arrays ``tag`` (F, N, 2), ``has_tag``, ``ts`` and ``nn`` (F, N) are
used when a recording holds them (labels, neighbour-count errors), as are the header
keys ``spacing_mm``, ``target_tags`` ([[X, Y], ...]) and ``title``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.viewer.record import RunRecord
from etswarm.viewer.scene import NO_STATE

RECORDING_NAME = "recording.npz"
SUMMARY_NAME = "summary.json"


def find_recording(run_dir: str | Path) -> Path:
    """The recording file of ``run_dir`` (or ``run_dir`` itself when it is a file)."""
    path = Path(run_dir)
    if path.is_file():
        return path
    if not path.exists():
        raise EtswarmError(f"{path}: no such run directory")
    candidate = path / RECORDING_NAME
    if candidate.exists():
        return candidate
    others = sorted(path.glob("*.npz"))
    if len(others) == 1:
        return others[0]
    raise EtswarmError(
        f"{path}: no {RECORDING_NAME} here (record a run with --out DIR, e.g. "
        "`etswarm sim --out DIR`)"
    )


def is_et_header(header: dict[str, Any]) -> bool:
    """True when the recording's ``led`` column holds ET state codes."""
    controller = str(header.get("controller", "")).lower()
    return controller in ("et", "etcontroller", "et_controller") or "shape" in header


def read_events(summary_path: Path) -> list[dict[str, Any]]:
    """The ``events`` list of a summary.json ([] when the file is absent)."""
    if not summary_path.exists():
        return []
    try:
        data = json.loads(summary_path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as err:
        raise EtswarmError(f"{summary_path}: not readable JSON ({err})") from None
    events = data.get("events", []) if isinstance(data, dict) else []
    if not isinstance(events, list):
        raise EtswarmError(f"{summary_path}: 'events' must be a list")
    out = []
    for k, e in enumerate(events):
        if not isinstance(e, dict) or "t_s" not in e or "kind" not in e:
            raise EtswarmError(f"{summary_path}: event {k} needs 't_s' and 'kind'")
        try:
            t = float(e["t_s"])
        except (TypeError, ValueError):
            raise EtswarmError(f"{summary_path}: event {k} has a non-numeric t_s") from None
        out.append({**e, "t_s": t, "kind": str(e["kind"])})
    return out


def load_run_dir(run_dir: str | Path) -> RunRecord:
    """Load the recording (and events) of a saved run for replay and plots."""
    from etswarm.sim.recorder import load_recording

    path = find_recording(run_dir)
    rec = load_recording(path)
    if rec.n_frames == 0:
        raise EtswarmError(f"{path}: the recording holds no frames")
    header = rec.header
    params = header.get("params", {}) if isinstance(header.get("params"), dict) else {}
    tps = int(header.get("ticks_per_s", params.get("ticks_per_s", 31)))
    state = (
        rec.led.astype(np.uint8)
        if is_et_header(header)
        else np.full(rec.led.shape, NO_STATE, np.uint8)
    )
    extras = _optional_arrays(path)
    spacing = float(header.get("spacing_mm", 40.0))
    sites = np.zeros((0, 2))
    if header.get("target_tags"):
        tags = np.asarray(header["target_tags"], dtype=np.float64).reshape(-1, 2)
        sites = np.stack(
            [spacing * (tags[:, 0] - tags[:, 1] / 2), spacing * tags[:, 1] * math.sqrt(3) / 2],
            axis=1,
        )
    summary_dir = path.parent
    title = str(header.get("title") or _default_title(header, path))
    try:
        return RunRecord(
            t_s=rec.tick / tps,
            pos=rec.pos,
            heading=rec.heading,
            state=state,
            present=rec.present,
            alive=rec.alive,
            tag=extras.get("tag"),
            has_tag=extras.get("has_tag"),
            ts=extras.get("ts"),
            nn=extras.get("nn"),
            events=read_events(summary_dir / SUMMARY_NAME),
            ticks_per_second=tps,
            comm_range_mm=float(params.get("comm_range_mm", 70.0)),
            body_radius_mm=float(params.get("body_radius_mm", 16.5)),
            spacing_mm=spacing,
            target_sites=sites,
            title=title,
            meta=header,
        )
    except ValueError as err:
        raise EtswarmError(f"{path}: {err}") from None


def _optional_arrays(path: Path) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    with np.load(path, allow_pickle=False) as data:
        for name in ("tag", "has_tag", "ts", "nn"):
            if name in data.files:
                out[name] = data[name]
    return out


def _default_title(header: dict[str, Any], path: Path) -> str:
    what = header.get("shape") or header.get("controller") or "run"
    seed = header.get("seed")
    return f"{what}{f', seed {seed}' if seed is not None else ''} ({path.parent.name or path.name})"
