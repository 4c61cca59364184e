"""Standard plots and a Markdown summary of a sweep's results table.

Plots (PNG, matplotlib ``Figure`` on the Agg canvas, no pyplot state), each drawn only
when its columns exist and vary:

- ``formation_time_vs_robots.png``: every run as a point, median line and IQR band, one
  series per combination of the other swept parameters;
- ``success_vs_loss.png``: share of runs that formed, with 95 % Wilson intervals;
- ``census_error.png``: distribution of the census error (count minus robots);
- ``reform_time.png``: time for the remnants to re-form after damage, per group.

``report.md`` holds a table grouped by the swept parameters (runs, errors, success rate,
median formation time, ...), the plots and the most frequent errors. Runs that crashed
count in "runs" and "errors" but not in the measures.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from etswarm.errors import EtswarmError
from etswarm.experiments.table import read_table

MAX_SERIES = 8


@dataclass
class ReportFiles:
    """What ``write_report`` wrote: the Markdown file and the plots (paths)."""

    markdown_path: Path
    plots: list[Path] = field(default_factory=list)


def parameter_columns(frame: pd.DataFrame, meta: dict[str, Any]) -> list[str]:
    """The parameter columns: from the table's metadata, else those before ``status``."""
    names = meta.get("parameters")
    if names:
        return [n for n in names if n in frame.columns]
    columns = list(frame.columns)
    if "run_id" in columns and "status" in columns:
        return columns[columns.index("run_id") + 1 : columns.index("status")]
    return []


def swept_columns(frame: pd.DataFrame, parameters: Sequence[str]) -> list[str]:
    """Parameters other than the seed that take more than one value in ``frame``."""
    return [
        p for p in parameters if p != "seed" and frame[p].astype(str).nunique(dropna=False) > 1
    ]


def numbers(series: pd.Series) -> np.ndarray:
    """A column as float64 with NaN for missing (booleans as 0/1). Shape (rows,)."""
    return pd.to_numeric(series.astype(object), errors="coerce").to_numpy(dtype=float)


def wilson_interval(successes: int, trials: int, z: float = 1.96) -> tuple[float, float]:
    """The Wilson score interval of a binomial proportion (95 % by default)."""
    if trials == 0:
        return (math.nan, math.nan)
    p = successes / trials
    denom = 1 + z * z / trials
    centre = (p + z * z / (2 * trials)) / denom
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / denom
    return (max(0.0, centre - half), min(1.0, centre + half))


def format_duration(seconds: float | None) -> str:
    """``0.25 s``, ``18.2 s``, ``12 min 34 s``, ``2 h 50 min 8 s``; ``-`` when missing."""
    if seconds is None or not math.isfinite(seconds):
        return "-"
    if seconds < 10:
        return f"{seconds:.2f} s"
    if seconds < 60:
        return f"{seconds:.1f} s"
    whole = round(seconds)
    hours, rest = divmod(whole, 3600)
    minutes, secs = divmod(rest, 60)
    if hours:
        return f"{hours} h {minutes} min {secs} s"
    return f"{minutes} min {secs} s"


def _time_unit(max_seconds: float) -> tuple[float, str]:
    if max_seconds >= 3 * 3600:
        return 3600.0, "h"
    if max_seconds >= 300:
        return 60.0, "min"
    return 1.0, "s"


def _series(frame: pd.DataFrame, by: Sequence[str]) -> list[tuple[str, pd.DataFrame]]:
    """Split ``frame`` by the columns ``by``: (label, rows); at most MAX_SERIES groups."""
    if not by:
        return [("", frame)]
    groups = [
        (", ".join(f"{name}={value}" for name, value in zip(by, key, strict=True)), part)
        for key, part in _group_rows(frame, by)
    ]
    return groups[:MAX_SERIES]


def _robots_column(frame: pd.DataFrame) -> str | None:
    for name in ("result.robots", "robots"):
        if name in frame.columns and np.isfinite(numbers(frame[name])).any():
            return name
    return None


def plot_formation_time(ok: pd.DataFrame, swept: Sequence[str], path: Path) -> Path | None:
    """Formation time against swarm size; None when there is nothing to draw."""
    robots = _robots_column(ok)
    if robots is None or "formation_time_s" not in ok.columns:
        return None
    x_all = numbers(ok[robots])
    t_all = numbers(ok["formation_time_s"])
    has = np.isfinite(x_all) & np.isfinite(t_all)
    if len(np.unique(x_all[has])) < 2:
        return None
    scale, unit = _time_unit(float(np.nanmax(t_all[has])))
    others = [p for p in swept if p not in ("robots", robots)]
    fig = Figure(figsize=(7, 4.5))
    ax = fig.subplots()
    rng = np.random.default_rng(0)  # jitter only, never a simulation stream
    for label, rows in _series(ok, others):
        x = numbers(rows[robots])
        t = numbers(rows["formation_time_s"]) / scale
        keep = np.isfinite(x) & np.isfinite(t)
        x, t = x[keep], t[keep]
        if x.size == 0:
            continue
        xs = np.unique(x)
        span = (xs.max() - xs.min()) if xs.size > 1 else 1.0
        jitter = rng.uniform(-0.01, 0.01, size=x.size) * span
        points = ax.scatter(x + jitter, t, s=12, alpha=0.4)
        face: Any = points.get_facecolor()
        colour = tuple(face[0][:3])  # opaque line, translucent dots
        q1, med, q3 = (np.array([np.percentile(t[x == v], q) for v in xs]) for q in (25, 50, 75))
        ax.plot(xs, med, "-o", color=colour, label=label or "median", markersize=4)
        ax.fill_between(xs, q1, q3, color=colour, alpha=0.15)
    unformed = int((np.isfinite(x_all) & ~np.isfinite(t_all)).sum())
    title = "Formation time vs swarm size (median, IQR band, runs as dots)"
    if unformed:
        title += f"\n{unformed} runs did not form and are not shown"
    ax.set(xlabel="robots", ylabel=f"formation time ({unit})", title=title)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_success_vs_loss(ok: pd.DataFrame, swept: Sequence[str], path: Path) -> Path | None:
    """Share of runs that formed against message loss; None when loss does not vary."""
    if "loss" not in ok.columns or "formed" not in ok.columns:
        return None
    loss_all = numbers(ok["loss"])
    if len(np.unique(loss_all[np.isfinite(loss_all)])) < 2:
        return None
    others = [p for p in swept if p != "loss"]
    fig = Figure(figsize=(7, 4.5))
    ax = fig.subplots()
    series = _series(ok, others)
    levels_all = np.unique(loss_all[np.isfinite(loss_all)])
    dodge = 0.015 * (levels_all.max() - levels_all.min())
    for number, (label, rows) in enumerate(series):
        shift = dodge * (number - (len(series) - 1) / 2)
        loss = numbers(rows["loss"])
        formed = numbers(rows["formed"]) > 0.5
        levels = np.unique(loss[np.isfinite(loss)])
        rates, low, high = [], [], []
        for level in levels:
            at = loss == level
            n, k = int(at.sum()), int(formed[at].sum())
            lo, hi = wilson_interval(k, n)
            rates.append(k / n)
            low.append(k / n - lo)
            high.append(hi - k / n)
        ax.errorbar(
            levels + shift, rates, yerr=[low, high], fmt="-o", capsize=3, label=label or "formed"
        )
    ax.set(
        xlabel="message loss (probability)",
        ylabel="runs formed (share)",
        ylim=(-0.03, 1.03),
        title="Success vs message loss (95 % Wilson intervals)",
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_census_error(ok: pd.DataFrame, swept: Sequence[str], path: Path) -> Path | None:
    """Histogram of the census error per run; None without census data."""
    if "census_error_mean" not in ok.columns:
        return None
    errors = numbers(ok["census_error_mean"])
    if not np.isfinite(errors).any():
        return None
    by = ["census"] if "census" in swept else []
    finite = errors[np.isfinite(errors)]
    lo, hi = math.floor(finite.min()), math.ceil(finite.max())
    bins: Any = np.arange(lo - 0.5, hi + 1.5, 1.0) if hi - lo <= 60 else 30
    fig = Figure(figsize=(7, 4.5))
    ax = fig.subplots()
    for label, rows in _series(ok, by):
        values = numbers(rows["census_error_mean"])
        values = values[np.isfinite(values)]
        ax.hist(values, bins=bins, alpha=0.6, label=label or "all runs")
    ax.axvline(0, color="black", lw=0.8)
    ax.set(
        xlabel="census error (robots counted - robots in remnant, mean over remnants)",
        ylabel="runs",
        title="Census error",
    )
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_reform_time(ok: pd.DataFrame, swept: Sequence[str], path: Path) -> Path | None:
    """Time to re-form after damage per group of swept parameters; None without data."""
    if "reform_time_s" not in ok.columns or not _has_damage(ok):
        return None
    times = numbers(ok["reform_time_s"])
    if not np.isfinite(times).any():
        return None
    scale, unit = _time_unit(float(np.nanmax(times)))
    groups = _series(ok, list(swept))
    fig = Figure(figsize=(max(5.0, 1.2 * len(groups) + 2), 4.5))
    ax = fig.subplots()
    labels = []
    rng = np.random.default_rng(0)  # jitter only
    for position, (label, rows) in enumerate(groups):
        values = numbers(rows["reform_time_s"]) / scale
        values = values[np.isfinite(values)]
        labels.append(label.replace(", ", "\n") or "all runs")
        if values.size == 0:
            continue
        ax.scatter(position + rng.uniform(-0.12, 0.12, values.size), values, s=12, alpha=0.5)
        ax.hlines(np.median(values), position - 0.25, position + 0.25, color="black")
    ax.set_xticks(range(len(groups)), labels, fontsize=7)
    ax.set(ylabel=f"reform time ({unit})", title="Time to re-form after damage (bar: median)")
    ax.set_ylim(bottom=0)
    ax.grid(axis="y", alpha=0.3)
    return _save(fig, path)


def _has_damage(frame: pd.DataFrame) -> bool:
    """Whether some run was damaged: a non-empty ``damage`` value or a damage event."""
    if any(c.startswith("events.damage") for c in frame.columns):
        return True
    if "damage" not in frame.columns:
        return False
    values = frame["damage"].dropna().astype(str).str.strip()
    return bool((~values.isin(["", "[]", "none", "None"])).any())


def _save(fig: Figure, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path


def summary_table(frame: pd.DataFrame, swept: Sequence[str]) -> pd.DataFrame:
    """One row per combination of the swept parameters, measures as formatted text."""
    rows = []
    groups = _group_rows(frame, swept)
    for key, part in groups:
        ok = part[part["status"].astype(str) == "ok"]
        row: dict[str, Any] = dict(zip(swept, key, strict=True))
        row["runs"] = len(part)
        row["errors"] = len(part) - len(ok)
        if "formed" in ok.columns and len(ok):
            formed = numbers(ok["formed"]) > 0.5
            row["formed"] = f"{formed.sum()}/{len(ok)} ({100 * formed.mean():.0f} %)"
        for column, title, fmt in (
            ("formation_time_s", "median formation time", format_duration),
            ("reform_time_s", "median reform time", format_duration),
            ("jaccard", "median Jaccard", lambda v: f"{v:.3f}"),
            ("placement_error_mm", "median placement error (mm)", lambda v: f"{v:.1f}"),
            ("census_error_mean", "median census error", lambda v: f"{v:+.1f}"),
            ("wall_time_s", "median wall time", format_duration),
        ):
            if column == "reform_time_s" and not _has_damage(frame):
                continue  # without damage it only repeats the formation time
            always = column == "formation_time_s"  # "-" says no run formed
            if column in ok.columns and (always or np.isfinite(numbers(frame[column])).any()):
                values = numbers(ok[column])
                values = values[np.isfinite(values)]
                row[title] = fmt(float(np.median(values))) if values.size else "-"
        rows.append(row)
    columns: dict[str, None] = {}
    for row in rows:  # first-seen order, so a group without measures does not reorder
        columns.update(dict.fromkeys(row))
    order = [*swept, "runs", "errors", "formed"]
    ordered = [c for c in order if c in columns] + [c for c in columns if c not in order]
    return pd.DataFrame(rows, columns=ordered)


def _group_rows(frame: pd.DataFrame, swept: Sequence[str]) -> list[tuple[tuple, pd.DataFrame]]:
    if not swept:
        return [((), frame)]
    keys = pd.DataFrame(
        {name: [_text(v) for v in frame[name].tolist()] for name in swept}, index=frame.index
    )
    out = []
    for key in dict.fromkeys(map(tuple, keys.to_numpy())):
        mask = (keys == list(key)).all(axis=1)
        out.append((key, frame[mask]))
    return out


def _text(value: Any) -> str:
    """A cell as table text; missing values (NA, None, NaN) as ``-``."""
    return "-" if _missing(value) else str(value)


def markdown_table(table: pd.DataFrame) -> str:
    """A pandas frame as a GitHub Markdown table (all cells as text)."""
    columns = [str(c) for c in table.columns]
    lines = ["| " + " | ".join(columns) + " |", "|" + "|".join("---" for _ in columns) + "|"]
    for values in table.itertuples(index=False):
        cells = ["-" if _missing(v) else str(v).replace("|", "\\|") for v in values]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _missing(value: Any) -> bool:
    try:
        return bool(pd.isna(value))
    except (TypeError, ValueError):
        return False


def write_report(results: str | Path, out_dir: str | Path) -> ReportFiles:
    """Draw the plots and write ``report.md`` for a sweep folder or results Parquet file."""
    frame, meta = read_table(results)
    if frame.empty:
        raise EtswarmError(f"{results}: the results table has no runs")
    if "status" not in frame.columns:
        raise EtswarmError(f"{results}: not an etswarm results table (no status column)")
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise EtswarmError(f"--out {out}: cannot create ({err.strerror})") from err
    parameters = parameter_columns(frame, meta)
    swept = swept_columns(frame, parameters)
    ok = frame[frame["status"].astype(str) == "ok"]

    plots: list[tuple[str, Path]] = []
    for title, draw, name in (
        ("Formation time vs robots", plot_formation_time, "formation_time_vs_robots.png"),
        ("Success vs message loss", plot_success_vs_loss, "success_vs_loss.png"),
        ("Census error", plot_census_error, "census_error.png"),
        ("Reform time", plot_reform_time, "reform_time.png"),
    ):
        written = draw(ok, swept, out / name)
        if written is not None:
            plots.append((title, written))
        else:
            (out / name).unlink(missing_ok=True)  # a stale plot from an earlier report

    n_err = int((frame["status"].astype(str) != "ok").sum())
    versions = sorted({str(v) for v in frame.get("version", pd.Series(dtype=object)).dropna()})
    heading = meta.get("sweep") or Path(results).stem
    lines = [
        f"# Sweep report: {heading}",
        "",
        f"- source: `{results}`",
        f"- runs: {len(frame)} ({len(frame) - n_err} ok, {n_err} errors)",
        f"- swept: {', '.join(swept) if swept else 'nothing (one parameter point)'}",
    ]
    if "seed" in frame.columns:
        lines.append(f"- seeds per point: {frame['seed'].nunique()}")
    if versions:
        lines.append(f"- etswarm version: {', '.join(versions)}")
    lines += ["", "## Summary", "", markdown_table(summary_table(frame, swept)), ""]
    if plots:
        lines += ["## Plots", ""]
        for title, path in plots:
            lines += [f"### {title}", "", f"![{title}]({path.name})", ""]
    if n_err:
        errors = frame.loc[frame["status"].astype(str) != "ok", "error"].astype(str)
        lines += ["## Errors", ""]
        for message, count in errors.value_counts().head(10).items():
            lines.append(f"- {count} × `{message}`")
        lines.append("")
    markdown_path = out / "report.md"
    markdown_path.write_text("\n".join(lines), encoding="utf-8")
    return ReportFiles(markdown_path, [p for _, p in plots])
