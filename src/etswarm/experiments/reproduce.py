"""``etswarm reproduce``: the paper's experiments as one resumable sweep, figures and a report.

The paper (Mishra, Semwal, Nair, GECCO 2018) shows: the `T` forming over time (Fig. 5), the
`T` at message loss 0.2 with robots that never became Stable (Fig. 6), the `T` cut
vertically then horizontally and regenerating (Fig. 8), the dumbbell and the starfish
(Figs. 9-10), and one number: the `T` formed in 2 h 50 min 8 s of simulated time.

Here every run is a case of one sweep (``OUT/sweep``, so an interrupted reproduction
resumes), executed by :func:`paper_run`: the real ET runner (``etswarm.algorithm.run``)
with snapshots of the swarm taken while it runs. Then :func:`write_paper_report` draws
the figures into ``OUT/figures`` and writes ``OUT/report.md`` with the comparison table.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.collections import EllipseCollection
from matplotlib.figure import Figure

from etswarm.experiments.report import format_duration
from etswarm.experiments.runner import SweepOutcome, run_sweep
from etswarm.experiments.spec import load_spec
from etswarm.experiments.store import RunStore

#: The paper's formation time of `T` (Fig. 5 caption): 2 h 50 min 8 s of simulated time.
PAPER_T_FORMATION_S = 2 * 3600 + 50 * 60 + 8

#: Seconds of simulated time between two snapshots of a run.
SNAPSHOT_EVERY_S = 120.0

#: Fig. 8's cuts: vertically through the stem of the formed `T`, a minute after it formed;
#: then horizontally, a minute after every remnant re-formed (etswarm.damage syntax).
CUT_VERTICAL = "split x=-1.25 at=formed+60"
CUT_HORIZONTAL = "split y=0.43 at=formed+60"

#: Task of the reproduction sweep.
PAPER_TASK = "etswarm.experiments.reproduce:paper_run"


# -- the task ---------------------------------------------------------------------------------
def paper_run(params: dict[str, Any]) -> dict[str, Any]:
    """Run one ET experiment like ``etswarm.algorithm.api.run_experiment``, with snapshots.

    ``params`` are run_experiment's, plus ``snapshot_every_s`` (simulated seconds between
    snapshots; 0 for none) and ``figure`` (a label, ignored by the run). The summary gets a
    ``snapshots`` list: ``{t_s, x_mm, y_mm, state, alive}`` for every present robot, the
    first at the start and the last at the end of the run.
    """
    from etswarm.algorithm.run import ETRun

    params = dict(params)
    every = float(params.pop("snapshot_every_s", 0.0) or 0.0)
    params.pop("figure", None)
    run = ETRun(_run_config(params))
    snapshots: list[dict[str, Any]] = [_snapshot(run)]
    next_at = every

    def capture(current: Any) -> None:
        nonlocal next_at
        if every > 0 and current.sim_time_s + 1e-9 >= next_at:
            snapshots.append(_snapshot(current))
            while next_at <= current.sim_time_s + 1e-9:
                next_at += every

    summary = run.run(progress=capture)
    if snapshots[-1]["t_s"] != round(run.sim_time_s, 3):
        snapshots.append(_snapshot(run))
    summary["snapshots"] = snapshots
    return summary


def _run_config(params: dict[str, Any]) -> Any:
    """The runner's RunConfig from run_experiment-style flat params.

    Keys: run_experiment's ``RUN_KEYS`` and any other RunConfig field (``damage``, as a
    list of ``KIND REGION [at=TIME]`` strings), ET parameters as ``et_<name>``.
    """
    from etswarm.algorithm.api import RUN_KEYS
    from etswarm.algorithm.params import ETParams
    from etswarm.algorithm.run import RunConfig
    from etswarm.errors import EtswarmError

    run_kwargs: dict[str, Any] = {}
    et_kwargs: dict[str, Any] = {}
    et_names = set(ETParams.__dataclass_fields__)
    run_names = (set(RUN_KEYS) | set(RunConfig.__dataclass_fields__)) - {"et"}
    for key, value in params.items():
        if key in run_names:
            run_kwargs[key] = tuple(value) if isinstance(value, list) else value
        elif key.startswith("et_") and key[3:] in et_names:
            et_kwargs[key[3:]] = value
        else:
            raise EtswarmError(f"unknown run parameter {key!r}")
    return RunConfig(**run_kwargs, et=ETParams(**et_kwargs))


def _snapshot(run: Any) -> dict[str, Any]:
    world = run.world
    present = np.asarray(world.present, dtype=bool)
    pos = np.asarray(world.pos, dtype=float)[present]
    return {
        "t_s": round(float(run.sim_time_s), 3),
        "x_mm": np.round(pos[:, 0], 1).tolist(),
        "y_mm": np.round(pos[:, 1], 1).tolist(),
        "state": np.asarray(run.controller.states)[present].astype(int).tolist(),
        "alive": np.asarray(world.alive, dtype=bool)[present].tolist(),
    }


# -- the sweep --------------------------------------------------------------------------------
def damage_supported() -> bool:
    """Whether the ET runner takes a ``damage`` parameter (needed for Fig. 8)."""
    from etswarm.errors import EtswarmError

    try:
        from etswarm.algorithm.run import RunConfig
    except ImportError as err:
        raise EtswarmError(f"the ET runner cannot be imported ({err})") from err
    return "damage" in RunConfig.__dataclass_fields__


def paper_spec_text(seeds: int, shape_seeds: int, max_time_s: float, damage: bool) -> str:
    """The TOML of the reproduction sweep (written to OUT/paper.toml and run from there)."""
    lines = [
        "# The experiments of Mishra, Semwal & Nair (GECCO 2018), as an etswarm sweep.",
        "# Written by `etswarm reproduce`; re-running it resumes where it stopped.",
        "[sweep]",
        'name = "paper"',
        f'task = "{PAPER_TASK}"',
        f"seeds = {{start = 0, count = {seeds}}}",
        'description = "T (Figs. 5-6), T cut twice (Fig. 8), dumbbell and starfish (Figs. 9-10)"',
        "",
        "[fixed]",
        "loss = 0.2",
        "noise_mm = 2.0",
        f"max_time_s = {float(max_time_s)}",
        f"snapshot_every_s = {SNAPSHOT_EVERY_S}",
        "",
        "[[cases]]",
        'figure = "5-6"',
        'shape = "T"',
    ]
    for shape, figure in (("dumbbell", "9"), ("starfish", "10")):
        lines += [
            "",
            "[[cases]]",
            f'figure = "{figure}"',
            f'shape = "{shape}"',
            f"seeds = {{start = 0, count = {shape_seeds}}}",
        ]
    if damage:
        # Regions are in lattice spacings from the gene's (0, 0) site: x = -1.25 runs down
        # the middle of the T's stem, y = 0.43 between its rows Y = 0 and Y = 1.
        lines += [
            "",
            "[[cases]]",
            'figure = "8"',
            'shape = "T"',
            f'damage = ["{CUT_VERTICAL}", "{CUT_HORIZONTAL}"]',
            f"max_time_s = {2 * float(max_time_s)}",
            f"seeds = {{start = 0, count = {max(1, shape_seeds // 2)}}}",
        ]
    return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class Reproduction:
    """What ``reproduce`` did: the sweep outcome and the report it wrote."""

    sweep: SweepOutcome
    report: Path | None
    notes: tuple[str, ...]


def reproduce(
    out_dir: str | Path,
    *,
    seeds: int = 20,
    shape_seeds: int | None = None,
    max_time_s: float = 4 * 3600.0,
    workers: int | None = None,
    scheduler: str | None = None,
    show_progress: bool = True,
) -> Reproduction:
    """Run (or resume) the paper's experiments in ``out_dir`` and write figures and report.

    ``seeds`` runs of `T` (the comparison table), ``shape_seeds`` (default: half as many)
    of the dumbbell and the starfish, half as many (at least 1) of the cut `T`, which may run
    twice as long (``max_time_s`` each). No report is written when the
    sweep was interrupted. Runs recorded as failed are run again.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    shape_seeds = shape_seeds if shape_seeds is not None else max(1, seeds // 2)
    notes: list[str] = []
    damage = damage_supported()
    if not damage:
        notes.append(
            "Fig. 8 (regeneration after two cuts) was not run: the ET runner has no `damage`"
            " parameter yet."
        )
    spec_path = out / "paper.toml"
    spec_path.write_text(paper_spec_text(seeds, shape_seeds, max_time_s, damage), "utf-8")
    spec = load_spec(spec_path)
    outcome = run_sweep(
        spec,
        out / "sweep",
        scheduler=scheduler,
        workers=workers,
        retry_failed=True,  # a crash is worth another try when the reproduction is re-run
        show_progress=show_progress,
    )
    if outcome.interrupted:
        return Reproduction(outcome, None, tuple(notes))
    report = write_paper_report(out, notes)
    return Reproduction(outcome, report, tuple(notes))


# -- figures and report -----------------------------------------------------------------------
def _records(out: Path) -> list[dict[str, Any]]:
    store = RunStore(out / "sweep")
    spec = load_spec(out / "paper.toml")
    found = [store.read(run.run_id) for run in spec.runs()]
    return [r for r in found if r is not None]


def _ok(records: Sequence[dict[str, Any]], figure: str) -> list[dict[str, Any]]:
    return [
        r for r in records if r["status"] == "ok" and r["params"].get("figure") == figure
    ]


def _representative(runs: Sequence[dict[str, Any]]) -> dict[str, Any] | None:
    """The formed run with the median formation time, else the one with the best Jaccard."""
    if not runs:
        return None
    formed = [r for r in runs if r["summary"].get("formed")]
    if formed:
        formed.sort(key=lambda r: (r["summary"]["formation_time_s"], r["params"]["seed"]))
        return formed[(len(formed) - 1) // 2]
    return max(runs, key=lambda r: (r["summary"].get("jaccard") or 0.0, -r["params"]["seed"]))


def _state_names() -> list[str]:
    from etswarm.algorithm.states import STATE_NAMES

    return list(STATE_NAMES)


def _state_colour(code: int) -> tuple[float, float, float]:
    from etswarm.viewer.palette import state_colour

    r, g, b = state_colour(code)
    return (r / 255, g / 255, b / 255)


def snapshot_limits(snaps: Sequence[dict[str, Any]], pad_mm: float = 40.0) -> tuple:
    """((x0, x1), (y0, y1)) in mm holding every robot of ``snaps``, square, padded."""
    xs = np.concatenate([np.asarray(s["x_mm"], dtype=float) for s in snaps] + [np.zeros(1)])
    ys = np.concatenate([np.asarray(s["y_mm"], dtype=float) for s in snaps] + [np.zeros(1)])
    if len(xs) > 1:
        xs, ys = xs[:-1], ys[:-1]
    cx, cy = (xs.min() + xs.max()) / 2, (ys.min() + ys.max()) / 2
    half = max(xs.max() - xs.min(), ys.max() - ys.min()) / 2 + pad_mm
    return ((cx - half, cx + half), (cy - half, cy + half))


def draw_snapshot(
    ax: Any,
    snap: dict[str, Any],
    link_mm: float = 70.0,
    limits: tuple | None = None,
    body_radius_mm: float = 16.5,
) -> None:
    """Robots of one snapshot as bodies to scale coloured by state, links within range.

    ``limits`` ((x0, x1), (y0, y1)) in mm fixes the frame (the same for a sequence).
    """
    x = np.asarray(snap["x_mm"], dtype=float)
    y = np.asarray(snap["y_mm"], dtype=float)
    state = np.asarray(snap["state"], dtype=int)
    alive = np.asarray(snap.get("alive", [True] * len(x)), dtype=bool)
    if x.size:
        dx = x[:, None] - x[None, :]
        dy = y[:, None] - y[None, :]
        near = np.triu((dx * dx + dy * dy) <= link_mm * link_mm, k=1)
        for i, j in zip(*np.nonzero(near), strict=True):
            ax.plot([x[i], x[j]], [y[i], y[j]], color="0.8", lw=0.5, zorder=1)
    dead = (0.35, 0.35, 0.35)
    colours = [_state_colour(s) if a else dead for s, a in zip(state, alive, strict=True)]
    bodies = EllipseCollection(
        widths=2 * body_radius_mm,
        heights=2 * body_radius_mm,
        angles=0.0,
        units="xy",
        offsets=np.column_stack([x, y]) if x.size else np.zeros((0, 2)),
        offset_transform=ax.transData,
        facecolors=colours,
        edgecolors="0.2",
        linewidths=0.4,
        zorder=2,
    )
    ax.add_collection(bodies)
    (x0, x1), (y0, y1) = limits or snapshot_limits([snap])
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(f"t = {format_duration(snap['t_s'])}", fontsize=8)


def _legend(fig: Figure, states: Sequence[int], outside: bool = False) -> None:
    from matplotlib.lines import Line2D

    names = _state_names()
    handles = [
        Line2D([], [], marker="o", ls="", markerfacecolor=_state_colour(s),
               markeredgecolor="0.2", label=names[s])
        for s in sorted(set(states))
        if 0 <= s < len(names)
    ]
    where: Any = "outside lower center" if outside else "lower center"
    fig.legend(handles=handles, loc=where, ncol=len(handles), fontsize=8, frameon=False)


def _pick_snapshots(snaps: Sequence[dict[str, Any]], count: int) -> list[dict[str, Any]]:
    """``count`` snapshots evenly spread in time, first and last included."""
    if len(snaps) <= count:
        return list(snaps)
    index = np.linspace(0, len(snaps) - 1, count).round().astype(int)
    return [snaps[i] for i in dict.fromkeys(index.tolist())]


def figure_sequence(
    record: dict[str, Any],
    title: str,
    path: Path,
    panels: int = 6,
    snaps: Sequence[dict[str, Any]] | None = None,
) -> Path:
    """Snapshots of one run on a grid of 3 columns, in one frame (Figs. 5 and 8).

    ``snaps`` default to ``panels`` snapshots evenly spread over the run.
    """
    if snaps is None:
        snaps = _pick_snapshots(record["summary"]["snapshots"], panels)
    cols = min(3, len(snaps))
    rows = math.ceil(len(snaps) / cols)
    fig = Figure(figsize=(3.4 * cols, 3.4 * rows + 0.9), layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    states: list[int] = []
    limits = snapshot_limits(snaps)
    for number, (ax, snap) in enumerate(zip(axes, snaps, strict=False)):
        draw_snapshot(ax, snap, limits=limits)
        label = f", {snap['label']}" if snap.get("label") else ""
        ax.set_title(f"({chr(ord('a') + number)}) {ax.get_title()}{label}", fontsize=8)
        states += snap["state"]
    for ax in axes[len(snaps):]:
        ax.set_axis_off()
    fig.suptitle(title, fontsize=10)
    _legend(fig, states, outside=True)
    fig.savefig(path, dpi=110)
    return path


def figure_final(record: dict[str, Any], title: str, path: Path) -> Path:
    """The last snapshot of a run, robots that are placed but not Stable labelled (Fig. 6)."""
    from etswarm.algorithm.states import PLACED_STATES, State

    snap = record["summary"]["snapshots"][-1]
    names = _state_names()
    fig = Figure(figsize=(6, 5.5))
    ax = fig.subplots()
    draw_snapshot(ax, snap)
    placed = {int(s) for s in PLACED_STATES}
    for x, y, s in zip(snap["x_mm"], snap["y_mm"], snap["state"], strict=True):
        if s in placed and s != int(State.STABLE):
            ax.annotate(names[s], (x, y), xytext=(6, 6), textcoords="offset points", fontsize=7)
    ax.set_title(f"{title}\n(t = {format_duration(snap['t_s'])})", fontsize=9)
    _legend(fig, snap["state"])
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(path, dpi=110)
    return path


def figure_shape(record: dict[str, Any], title: str, path: Path) -> Path:
    """The shape's bitmap beside the swarm at the end of the run (Figs. 9-10)."""
    from etswarm.shapes import load_shape

    shape = load_shape(record["params"]["shape"])
    fig = Figure(figsize=(9, 4.2))
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 1.4]})
    left.imshow(np.asarray(shape.bitmap, dtype=float), cmap="Greys", vmin=0, vmax=1.4)
    left.set_title(f"bitmap `{shape.name}` ({shape.n_cells} cells)", fontsize=9)
    left.set_xticks([])
    left.set_yticks([])
    snap = record["summary"]["snapshots"][-1]
    draw_snapshot(right, snap)
    right.set_title(f"swarm at t = {format_duration(snap['t_s'])}", fontsize=9)
    fig.suptitle(title, fontsize=10)
    _legend(fig, snap["state"])
    fig.tight_layout(rect=(0, 0.07, 1, 0.95))
    fig.savefig(path, dpi=110)
    return path


def figure_formation_times(runs: Sequence[dict[str, Any]], path: Path) -> Path:
    """Our `T` formation times (one dot per seed) against the paper's single run."""
    times = [r["summary"]["formation_time_s"] for r in runs if r["summary"].get("formed")]
    fig = Figure(figsize=(7, 3))
    ax = fig.subplots()
    if times:
        values = np.asarray(times, dtype=float) / 3600
        rng = np.random.default_rng(0)  # vertical jitter only
        ax.scatter(values, rng.uniform(-0.1, 0.1, values.size), s=20, label="ours, one per seed")
        ax.axvline(float(np.median(values)), color="C0", ls="--", label="our median")
    ax.axvline(PAPER_T_FORMATION_S / 3600, color="C3", label="paper (one run)")
    ax.set(
        xlabel="formation time of T (simulated hours)",
        yticks=[],
        ylim=(-0.5, 0.5),
        title=f"T at loss 0.2: {len(times)} of {len(runs)} runs formed",
    )
    ax.set_xlim(left=0)
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path


def _not_stable(record: dict[str, Any]) -> dict[str, int]:
    """Counts of robots in each non-Stable state at the end of a run."""
    states = record["summary"].get("states") or {}
    return {k: int(v) for k, v in states.items() if k != "Stable" and v}


def _median_iqr(values: Sequence[float]) -> str:
    if not values:
        return "-"
    q1, med, q3 = np.percentile(np.asarray(values, dtype=float), [25, 50, 75])
    low, mid, high = (format_duration(float(v)) for v in (q1, med, q3))
    return f"{mid} (IQR {low} - {high})"


def comparison_rows(records: Sequence[dict[str, Any]]) -> list[tuple[str, str, str]]:
    """(measure, ours, paper) rows of the comparison table."""
    rows: list[tuple[str, str, str]] = []
    t_runs = _ok(records, "5-6")
    t_all = [r for r in records if r["params"].get("figure") == "5-6"]
    formed = [r for r in t_runs if r["summary"].get("formed")]
    times = [float(r["summary"]["formation_time_s"]) for r in formed]
    rows.append(
        ("`T` formed within the time limit (loss 0.2)", f"{len(formed)} of {len(t_all)} seeds",
         "yes (one run shown)")
    )
    rows.append(
        ("`T` formation time, simulated", _median_iqr(times),
         format_duration(PAPER_T_FORMATION_S))
    )
    if times:
        ratio = float(np.median(times)) / PAPER_T_FORMATION_S
        rows.append(("ratio ours / paper (median)", f"{ratio:.2f}", "1"))
    stuck = [sum(_not_stable(r).values()) for r in t_runs]
    if stuck:
        rows.append(
            ("`T` robots not Stable at the end (median, max)",
             f"{int(np.median(stuck))}, {max(stuck)}", "2 (Fig. 6)")
        )
    jac = [float(j) for r in t_runs if (j := r["summary"].get("jaccard")) is not None]
    if jac:
        rows.append(("`T` Jaccard with the target (median)", f"{np.median(jac):.3f}", "-"))
    for figure, shape in (("9", "dumbbell"), ("10", "starfish")):
        runs = _ok(records, figure)
        total = [r for r in records if r["params"].get("figure") == figure]
        if not total:
            continue
        done = [float(r["summary"]["formation_time_s"]) for r in runs if r["summary"].get("formed")]
        rows.append(
            (f"`{shape}` formed (formation time)",
             f"{len(done)} of {len(total)} ({_median_iqr(done)})",
             "formed (no time given)")
        )
    regen = [r for r in records if r["params"].get("figure") == "8"]
    if regen:
        ok = _ok(records, "8")
        cuts = [len(damage_times(r)) for r in ok]
        both = sum(1 for c in cuts if c >= 2)
        reformed = [r for r in ok if len(damage_times(r)) >= 2 and _settled(r)]
        rows.append(
            ("`T` cut twice (each cut a minute after the shape formed)",
             f"{both} of {len(regen)} runs got both cuts", "yes (one run shown)")
        )
        rows.append(
            ("every remnant re-formed its scaled `T` after the second cut",
             f"{len(reformed)} of {len(regen)}", "yes (Fig. 8)")
        )
        errors = [
            int(c["census_count"]) - int(c["robots"])
            for r in ok
            if damage_times(r)
            for c in r["summary"].get("components") or []
            if c.get("census_count") is not None
        ]
        if errors:
            exact = sum(1 for e in errors if e == 0)
            rows.append(
                ("census of the remnants: exact counts", f"{exact} of {len(errors)}"
                 f" (errors from {min(errors):+d} to {max(errors):+d})", "-")
            )
    return rows


def damage_times(record: dict[str, Any]) -> list[float]:
    """Simulated times (s) of the damage events of a run."""
    events = record["summary"].get("events") or []
    return [float(e["t_s"]) for e in events if e.get("kind") == "damage"]


def _settled(record: dict[str, Any]) -> bool:
    summary = record["summary"]
    if "settled" in summary:
        return bool(summary["settled"])
    comps = summary.get("components") or []
    return bool(comps) and all(c.get("formed") for c in comps)


def damage_snapshots(record: dict[str, Any], panels: int = 6) -> list[dict[str, Any]]:
    """Snapshots telling a damage story: before and after each cut, and the end.

    Without damage events, ``panels`` snapshots evenly spread.
    """
    snaps = record["summary"]["snapshots"]
    cuts = damage_times(record)
    if not cuts:
        return _pick_snapshots(snaps, panels)
    times = np.asarray([s["t_s"] for s in snaps], dtype=float)
    chosen: dict[int, str] = {}
    for number, cut in enumerate(cuts, start=1):
        before = np.nonzero(times < cut)[0]
        after = np.nonzero(times > cut)[0]
        if before.size:
            chosen.setdefault(int(before[-1]), f"before cut {number}")
        if after.size:
            chosen.setdefault(int(after[0]), f"after cut {number}")
    chosen.setdefault(len(snaps) - 1, "end")
    if len(chosen) < panels and times[-1] > cuts[-1]:
        middle = (cuts[-1] + times[-1]) / 2
        chosen.setdefault(int(np.argmin(np.abs(times - middle))), "regrowing")
    return [{**snaps[i], "label": chosen[i]} for i in sorted(chosen)][:panels]


def write_paper_report(out_dir: str | Path, notes: Sequence[str] = ()) -> Path:
    """Draw the figures into OUT/figures and write OUT/report.md; returns its path."""
    out = Path(out_dir)
    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    records = _records(out)
    lines = [
        "# The paper, reproduced",
        "",
        "Mishra, Semwal & Nair, *Shape formation and regeneration of swarms using Epigenetic"
        " Tracking* (GECCO 2018): their experiments run with etswarm. Loss 0.2, distance"
        " noise 2 mm, robots released from a queue; simulated times.",
        "",
        f"Software: {software_version()}.",
        "",
    ]
    lines += ["## Our numbers and the paper's", "", "| measure | etswarm | paper |"]
    lines.append("|---|---|---|")
    lines += [f"| {m} | {o} | {p} |" for m, o, p in comparison_rows(records)]
    lines.append("")
    errors = [r for r in records if r["status"] != "ok"]
    if errors:
        lines += [f"{len(errors)} runs crashed; first error: `{errors[0]['error']}`", ""]

    t_runs = _ok(records, "5-6")
    rep = _representative(t_runs)
    if rep is not None:
        seed = rep["params"]["seed"]
        lines += ["## Fig. 5: `T` forming over time", ""]
        figure_sequence(rep, f"T forming (seed {seed}, loss 0.2)", figures / "fig5_T_formation.png")
        why = (
            "the median formed run"
            if rep["summary"].get("formed")
            else "no run formed; this one came closest to the target"
        )
        lines += [f"Seed {seed} ({why}).", "", "![Fig. 5](figures/fig5_T_formation.png)", ""]
        figure_formation_times(t_runs, figures / "T_formation_times.png")
        lines += ["![formation times](figures/T_formation_times.png)", ""]
        shown = closest_failure(t_runs)
        final = shown or rep
        lines += ["## Fig. 6: `T` at loss 0.2, what went wrong", ""]
        figure_final(final, f"T at loss 0.2, seed {final['params']['seed']}",
                     figures / "fig6_T_loss.png")
        lines += _what_went_wrong(t_runs, shown)
        lines += ["![Fig. 6](figures/fig6_T_loss.png)", ""]
    regen = _ok(records, "8")
    if regen:
        best = max(
            regen,
            key=lambda r: (len(damage_times(r)), _settled(r), -r["params"]["seed"]),
        )
        cuts = damage_times(best)
        lines += ["## Fig. 8: `T` cut vertically, then horizontally", ""]
        lines.append(
            f"Cuts: `{CUT_VERTICAL}`, then `{CUT_HORIZONTAL}` (regions in lattice spacings"
            " from the gene's origin; the cut-off side is moved out of radio range)."
        )
        if cuts:
            when = ", ".join(format_duration(t) for t in cuts)
            lines.append(
                f"Shown: seed {best['params']['seed']}, cut at {when};"
                f" every remnant re-formed: {'yes' if _settled(best) else 'no'}."
            )
            figure_sequence(best, f"T cut twice, seed {best['params']['seed']}",
                            figures / "fig8_T_regeneration.png", snaps=damage_snapshots(best))
            lines += ["", "![Fig. 8](figures/fig8_T_regeneration.png)", ""]
        else:
            lines += [
                "No run was cut: a cut comes a minute after the `T` formed, and no run formed"
                " within the time limit.",
                "",
            ]
    for figure, shape in (("9", "dumbbell"), ("10", "starfish")):
        chosen = _representative(_ok(records, figure))
        if chosen is None:
            continue
        best = chosen
        name = f"fig{figure}_{shape}.png"
        state = "formed" if best["summary"].get("formed") else "not formed"
        figure_shape(best, f"{shape}, seed {best['params']['seed']} ({state})", figures / name)
        lines += [f"## Fig. {figure}: {shape}", "", f"![Fig. {figure}](figures/{name})", ""]
    if notes:
        lines += ["## Notes", ""] + [f"- {n}" for n in notes] + [""]
    lines += [
        "## Files",
        "",
        "- `paper.toml`: the sweep (re-run `etswarm reproduce` to resume or extend it)",
        "- `sweep/results.parquet`, `sweep/runs/*.json`: every run",
        "- `etswarm report sweep` draws the standard sweep plots",
        "",
    ]
    path = out / "report.md"
    path.write_text("\n".join(lines), encoding="utf-8")
    (out / "comparison.json").write_text(
        json.dumps([dict(zip(("measure", "etswarm", "paper"), row, strict=True))
                    for row in comparison_rows(records)], indent=1),
        encoding="utf-8",
    )
    return path


def closest_failure(runs: Sequence[dict[str, Any]]) -> dict[str, Any] | None:
    """The run nearest to success among those that did not end formed with all robots Stable.

    The paper's Fig. 6 is such a run: the `T` is there, two robots never became Stable.
    Nearest: highest Jaccard, then fewest robots not Stable, then lowest seed.
    """
    failed = [r for r in runs if not r["summary"].get("formed") or _not_stable(r)]
    if not failed:
        return None
    return max(
        failed,
        key=lambda r: (
            r["summary"].get("jaccard") or 0.0,
            -sum(_not_stable(r).values()),
            -r["params"]["seed"],
        ),
    )


def software_version() -> str:
    """``etswarm X.Y.Z`` plus the git commit of the source tree when there is one."""
    import subprocess

    import etswarm

    text = f"etswarm {etswarm.__version__}"
    try:
        where = Path(etswarm.__file__).parent
        commit = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=where, capture_output=True,
            text=True, timeout=5, check=True,
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no", "--", "."], cwd=where,
            capture_output=True, text=True, timeout=5, check=True,
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return text
    return f"{text}, git {commit}{' with uncommitted changes' if dirty else ''}"


def _what_went_wrong(runs: Sequence[dict[str, Any]], shown: dict[str, Any] | None) -> list[str]:
    """Sentences on what kept runs of `T` from ending formed with every robot Stable."""
    clean = [r for r in runs if r["summary"].get("formed") and not _not_stable(r)]
    lines = [f"{len(clean)} of {len(runs)} runs ended formed with every robot Stable."]
    if shown is None:
        lines += ["Nothing went wrong in any run; the figure shows the median run's end.", ""]
        return lines
    summary = shown["summary"]
    stuck = _not_stable(shown)
    parts = ", ".join(f"{n} {state}" for state, n in sorted(stuck.items())) or "none"
    lines.append(
        f"Shown: seed {shown['params']['seed']}, the failed run closest to the target"
        f" (Jaccard {summary.get('jaccard')}, formed: {'yes' if summary.get('formed') else 'no'});"
        f" robots not Stable at the end: {parts}."
    )
    totals: dict[str, int] = {}
    for run in runs:
        for state, n in _not_stable(run).items():
            totals[state] = totals.get(state, 0) + n
    if totals:
        ranked = sorted(totals.items(), key=lambda item: -item[1])
        parts = ", ".join(f"{state} {n}" for state, n in ranked)
        lines.append(f"Robots not Stable at the end, all runs together: {parts}.")
    duplicated = [r for r in runs if r["summary"].get("duplicate_tags")]
    if duplicated:
        lines.append(f"{len(duplicated)} runs ended with a tag held by two robots.")
    never = [r for r in runs if not r["summary"].get("formed")]
    if never:
        seeds = ", ".join(str(r["params"]["seed"]) for r in never)
        lines.append(f"Not formed within the time limit: seeds {seeds}.")
    lines.append("")
    return lines
