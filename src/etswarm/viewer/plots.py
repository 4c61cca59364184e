"""Pictures of a saved run (matplotlib, Agg): states over time, timeline, NN errors.

Colours are the renderer's state palette, so the plots match the videos.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import MaxNLocator
from scipy.spatial import cKDTree

from etswarm.algorithm.states import PLACED_STATES, STATE_NAMES, State
from etswarm.viewer import palette
from etswarm.viewer.record import RunRecord

#: A neighbour counts when closer than this many lattice spacings (DESIGN §3).
NEIGHBOUR_FACTOR = 1.3


def _rgb01(rgb: tuple[int, int, int]) -> tuple[float, float, float]:
    return (rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)


def time_axis(t_s: np.ndarray) -> tuple[np.ndarray, str, float]:
    """(scaled times, unit label, divisor) choosing s, min or h by the run's length."""
    span = float(t_s[-1]) if len(t_s) else 0.0
    if span > 2 * 3600:
        return t_s / 3600, "simulated time (h)", 3600.0
    if span > 180:
        return t_s / 60, "simulated time (min)", 60.0
    return t_s, "simulated time (s)", 1.0


def event_style(kind: str) -> tuple[tuple[float, float, float], str]:
    """(colour, line style) of an event kind: damage red dashed, formation green, other grey."""
    k = kind.lower()
    if any(w in k for w in ("damage", "split", "remove", "kill", "cut")):
        return _rgb01(palette.STATE_COLOURS[State.DANGER]), "--"
    if "form" in k:
        return _rgb01(palette.STATE_COLOURS[State.STABLE]), "-"
    return (0.45, 0.45, 0.45), ":"


def _draw_events(ax, record: RunRecord, div: float, label: bool = True) -> None:  # type: ignore[no-untyped-def]
    for e in record.events:
        kind = str(e.get("kind", "event"))
        colour, style = event_style(kind)
        x = float(e["t_s"]) / div
        ax.axvline(x, color=colour, linestyle=style, linewidth=1.4, zorder=5)
        if label:
            ax.text(
                x,
                0.97,
                kind,
                transform=ax.get_xaxis_transform(),
                rotation=90,
                va="top",
                ha="right",
                fontsize=8,
                color=colour,
                zorder=6,
                bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.7, "pad": 1},
            )


def plot_states(record: RunRecord, path: str | Path) -> Path:
    """Stacked area of robots per state over time, events as vertical lines."""
    counts = record.state_counts()
    t, xlabel, div = time_axis(record.t_s)
    fig, ax = plt.subplots(figsize=(10, 5), dpi=110)
    series, colours, labels = [], [], []
    for code in State:
        series.append(counts[:, code])
        colours.append(_rgb01(palette.state_colour(code)))
        labels.append(STATE_NAMES[code])
    if counts[:, 8].any():
        series.append(counts[:, 8])
        colours.append(_rgb01(palette.NEUTRAL))
        labels.append("no ET state")
    ax.stackplot(t, np.array(series), colors=colours, labels=labels, linewidth=0)
    ax.set_xlim(t[0], t[-1] if t[-1] > t[0] else t[0] + 1)
    ax.set_ylim(0, max(1, int(counts.sum(axis=1).max())) * 1.05)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("robots")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_title(f"Robots per state{': ' + record.title if record.title else ''}")
    _draw_events(ax, record, div)
    handles, names = ax.get_legend_handles_labels()
    ax.legend(
        handles[::-1], names[::-1], loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False
    )
    fig.tight_layout()
    return _save(fig, path)


def phases(record: RunRecord) -> list[tuple[float, float, str]]:
    """(start s, end s, "forming" | "regenerating") intervals from the events.

    Forming runs from the start to the first "formed" event; each damage event starts a
    regeneration that ends at the next "formed" event (or the end of the recording).
    """
    out: list[tuple[float, float, str]] = []
    start, label = float(record.t_s[0]), "forming"
    open_phase = True
    for e in record.events:
        kind = str(e.get("kind", "")).lower()
        t = float(e["t_s"])
        colour, _ = event_style(kind)
        if "form" in kind and open_phase:
            out.append((start, t, label))
            open_phase = False
        elif colour == _rgb01(palette.STATE_COLOURS[State.DANGER]):
            if open_phase:
                out.append((start, t, label))
            start, label, open_phase = t, "regenerating", True
    if open_phase:
        out.append((start, float(record.t_s[-1]), label))
    return out


def plot_timeline(record: RunRecord, path: str | Path) -> Path:
    """Formation/regeneration timeline: phases shaded, placed and Stable robots over time."""
    t, xlabel, div = time_axis(record.t_s)
    placed_codes = np.array(sorted(int(s) for s in PLACED_STATES))
    placed = (np.isin(record.state, placed_codes) & record.present).sum(axis=1)
    stable = ((record.state == State.STABLE) & record.present).sum(axis=1)
    fig, ax = plt.subplots(figsize=(10, 3.8), dpi=110)
    shade = {"forming": (0.85, 0.92, 1.0), "regenerating": (1.0, 0.9, 0.82)}
    for a, b, label in phases(record):
        ax.axvspan(a / div, b / div, color=shade[label], zorder=0)
        ax.text(
            (a + b) / 2 / div,
            0.02,
            label,
            transform=ax.get_xaxis_transform(),
            ha="center",
            va="bottom",
            fontsize=9,
            color=(0.3, 0.3, 0.3),
        )
    ax.plot(
        t,
        placed,
        color=_rgb01(palette.STATE_COLOURS[State.INACTIVE]),
        lw=2,
        label="placed (holding a tag)",
    )
    ax.plot(t, stable, color=_rgb01(palette.STATE_COLOURS[State.STABLE]), lw=2, label="Stable")
    ax.set_xlim(t[0], t[-1] if t[-1] > t[0] else t[0] + 1)
    ax.set_ylim(0, max(1, int(record.present.sum(axis=1).max())) * 1.1)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("robots")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_title(f"Formation and regeneration{': ' + record.title if record.title else ''}")
    _draw_events(ax, record, div)
    ax.legend(loc="upper left", frameon=False)
    fig.tight_layout()
    return _save(fig, path)


def neighbour_errors(record: RunRecord) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per frame: (robots with fewer placed neighbours than NN, with more, mean |error|).

    A placed robot (holding a tag, present, alive) counts the placed robots within
    1.3 lattice spacings; its error is that count minus its NN. Needs ``nn`` and
    ``has_tag`` in the record.
    """
    if record.nn is None or record.has_tag is None:
        raise ValueError("the recording holds no NN values")
    f = record.frames
    fewer = np.zeros(f, np.int64)
    more = np.zeros(f, np.int64)
    mean_abs = np.zeros(f)
    radius = NEIGHBOUR_FACTOR * record.spacing_mm
    for k in range(f):
        idx = np.flatnonzero(record.has_tag[k] & record.present[k] & record.alive[k])
        if idx.size == 0:
            continue
        tree = cKDTree(record.pos[k, idx])
        counts = np.array([len(c) - 1 for c in tree.query_ball_point(record.pos[k, idx], radius)])
        err = counts - record.nn[k, idx]
        fewer[k] = int((err < 0).sum())
        more[k] = int((err > 0).sum())
        mean_abs[k] = float(np.abs(err).mean())
    return fewer, more, mean_abs


def plot_neighbour_errors(record: RunRecord, path: str | Path) -> Path:
    """Robots whose placed-neighbour count differs from NN, over time."""
    fewer, more, mean_abs = neighbour_errors(record)
    t, xlabel, div = time_axis(record.t_s)
    fig, ax = plt.subplots(figsize=(10, 3.8), dpi=110)
    ax.plot(
        t,
        fewer,
        color=_rgb01(palette.STATE_COLOURS[State.DANGER]),
        lw=2,
        label="fewer neighbours than NN",
    )
    ax.plot(
        t,
        more,
        color=_rgb01(palette.STATE_COLOURS[State.SEARCH]),
        lw=2,
        label="more neighbours than NN",
    )
    ax.set_xlabel(xlabel)
    ax.set_ylabel("placed robots")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_ylim(0, max(1, int(max(fewer.max(), more.max()))) * 1.15)
    twin = ax.twinx()
    twin.plot(t, mean_abs, color=(0.3, 0.3, 0.3), lw=1, ls="--", label="mean |count - NN|")
    twin.set_ylabel("mean |count - NN|")
    twin.set_ylim(0, max(1.0, float(mean_abs.max()) * 1.15))
    ax.set_title(f"Neighbour-count errors{': ' + record.title if record.title else ''}")
    _draw_events(ax, record, div, label=False)
    lines = ax.get_legend_handles_labels()
    lines2 = twin.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="upper right", frameon=False)
    fig.tight_layout()
    return _save(fig, path)


def plot_run(record: RunRecord, out_dir: str | Path) -> list[Path]:
    """Every plot the record allows, as PNGs in ``out_dir``; returns their paths.

    Always ``states.png``; ``timeline.png`` when robots have ET states or there are
    events; ``neighbour_errors.png`` when the record holds NN values and tags.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [plot_states(record, out / "states.png")]
    if record.has_states() or record.events:
        paths.append(plot_timeline(record, out / "timeline.png"))
    if record.nn is not None and record.has_tag is not None:
        paths.append(plot_neighbour_errors(record, out / "neighbour_errors.png"))
    return paths


def _save(fig, path: str | Path) -> Path:  # type: ignore[no-untyped-def]
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p)
    plt.close(fig)
    return p
