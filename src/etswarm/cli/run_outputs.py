"""Driving an ET run for the CLI: progress bar, video, event snapshots, summary file.

Shared by ``etswarm run`` and ``etswarm demo``. Whatever the user asked to save is written
as the run goes (snapshots at each event, video frames as they are made) and closed
properly when the run ends, fails or is interrupted.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

from etswarm.algorithm.live import ETLive
from etswarm.algorithm.run import ETRun


def hms(seconds: float) -> str:
    """``h:mm:ss`` of a number of seconds."""
    s = round(seconds)
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}"


def _status(run: ETRun) -> str:
    placed = int((run.controller.states >= 2).sum())
    last = run.events[-1]["kind"] if run.events else ""
    return f"sim {hms(run.sim_time_s)}  placed {placed}/{run.world.n}  {last}"


def drive(
    run: ETRun,
    *,
    video: Path | None = None,
    fps: float = 10.0,
    speedup: float = 300.0,
    snapshots: Path | None = None,
    record: Path | None = None,
    quiet: bool = False,
    size: tuple[int, int] = (1000, 750),
) -> dict[str, Any]:
    """Run ``run`` to its end (settled or out of time) and return its summary.

    With ``video``, frames are rendered every ``speedup / fps`` simulated seconds; with
    ``snapshots``, a PNG is saved at the start and at every event; with ``record``, the
    world is recorded every 10 simulated seconds into that .npz (for ``etswarm replay``
    and ``etswarm plot``). Files are closed properly when the run ends or is interrupted.
    """
    from etswarm.sim.recorder import Recorder

    if record is not None:
        run.recorder = Recorder(
            record,
            run.world,
            meta={
                "controller": "et",
                "shape": run.config.shape,
                "title": f"ET {run.config.shape}, seed {run.config.seed}",
                "spacing_mm": run.config.et.spacing_mm,
                "target_tags": run.target.tolist(),
                "ticks_per_s": run.ticks_per_s,
            },
        )
        run.recorder.capture()
    try:
        return _drive(run, video, fps, speedup, snapshots, quiet, size)
    finally:
        if run.recorder is not None:
            run.recorder.close()


def _drive(run, video, fps, speedup, snapshots, quiet, size):  # type: ignore[no-untyped-def]
    from etswarm.viewer.snapshots import EventSnapshots

    live = ETLive(run)
    shots = EventSnapshots(snapshots, size=size) if snapshots is not None else None
    if shots is not None:
        shots.start(live.scene())
    columns = (
        TextColumn("[bold]{task.description}"),
        BarColumn(),
        TextColumn("{task.fields[status]}"),
        TimeElapsedColumn(),
    )
    max_s = run.config.max_time_s
    with Progress(*columns, transient=True, disable=quiet) as bar:
        task = bar.add_task(run.config.shape, total=max_s, status="")

        def tick(r: ETRun) -> None:
            bar.update(task, completed=r.sim_time_s, status=_status(r))
            if shots is not None:
                shots.update(live.scene(), r.events)

        if video is None:
            run.run(tick)
        else:
            _drive_video(live, video, fps, speedup, size, tick)
    return run.summary()


def _drive_video(live: ETLive, path: Path, fps: float, speedup: float, size, tick) -> None:  # type: ignore[no-untyped-def]
    """Render a frame every ``speedup / fps`` simulated seconds until the run ends; the view
    re-fits every frame so a queue that empties or a remnant moved away stays in the picture."""
    import dataclasses

    from etswarm.viewer.render import render
    from etswarm.viewer.video import VideoWriter
    from etswarm.viewer.view import ViewState

    ticks_per_frame = max(1, round(speedup * live.ticks_per_second / fps))
    view: ViewState | None = None
    with VideoWriter(path, fps) as writer:
        while True:
            scene = dataclasses.replace(live.scene(), speedup=speedup)
            if view is None:
                view = ViewState.fitted(scene, *size)
            else:
                view.fit(scene)
            writer.write(render(scene, view))
            tick(live.run)
            if live.finished:
                break
            live.advance(ticks_per_frame)


def write_summary(summary: dict[str, Any], out: Path) -> Path:
    """Write ``summary`` as ``out/summary.json`` (atomically); return the path."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / "summary.json"
    tmp = out / ".summary.json.tmp"
    tmp.write_text(json.dumps(summary, indent=2) + "\n")
    tmp.replace(path)
    return path


def describe(summary: dict[str, Any]) -> list[str]:
    """Human-readable lines about a summary."""
    t = summary["formation_time_s"]
    lines = [
        f"{summary['shape']}: {'formed' if summary['formed'] else 'NOT formed'}"
        + (f" in {hms(t)} simulated" if t is not None else "")
        + f"; {summary['robots']} robots, jaccard {summary['jaccard']:.3f}, "
        f"placement error {summary['placement_error_mm']} mm, "
        f"wall {summary['wall_time_s']:.1f} s, "
        f"x{summary['sim_time_s'] / max(summary['wall_time_s'], 1e-9):.0f} real time",
        "states: " + ", ".join(f"{k} {v}" for k, v in summary["states"].items() if v),
    ]
    if summary["damage"]:
        method = summary.get("census", "tree")
        for k, comp in enumerate(summary["components"]):
            head = (
                f"remnant {k}: {comp['robots']} robots, census {comp['census_count']} "
                f"({method}), "
            )
            if comp["too_small"]:
                lines.append(head + "too small to seed a scaled shape, stays put")
                continue
            lines.append(
                head
                + f"target {comp['target_cells']} cells, "
                f"{'reformed' if comp['formed'] else 'not reformed'}"
                + (
                    f" {hms(comp['time_to_stable_s'])} after the damage"
                    if comp["formed"] and comp["time_to_stable_s"] is not None
                    else ""
                )
            )
    lines.extend(election_lines(summary["events"]))
    lines.extend(torn_lines(summary["components"]))
    if not summary["settled"]:
        lines.extend(missing_lines(summary["components"]))
    return lines


def torn_lines(components: list[dict[str, Any]]) -> list[str]:
    """A line per group whose robots stand torn apart where their tags are neighbours
    (``stretched_links``): its tags may say formed while the robots stand in pieces."""
    return [
        f"group {k}: {n} link{'' if n == 1 else 's'} between robots of neighbouring sites "
        f"stretched past 1.5 spacings (placement error {comp['placement_error_mm']} mm)"
        for k, comp in enumerate(components)
        if (n := comp.get("stretched_links"))
    ]


def election_lines(events: list[dict[str, Any]]) -> list[str]:
    """One line on the run's elections (one census each), if any: how many, and how many
    were false alarms (the census counted every robot of the target and kept it)."""
    elections = sum(e["kind"] == "census" for e in events)
    if not elections:
        return []
    kept = sum(e["kind"] == "target_kept" for e in events)
    return [
        f"elections: {elections}"
        + (f", {kept} of them false alarms (nobody lost: the target kept)" if kept else "")
    ]


def missing_lines(components: list[dict[str, Any]]) -> list[str]:
    """Lines on what the unformed groups of robots lack: free sites and searchers (those in
    a hole of the target, and whether the free sites make a way across a ring); lone
    robots out of range of every other (lost searchers) on one line."""
    lines = []
    lone = 0
    for k, comp in enumerate(components):
        if comp["formed"] or comp["too_small"]:
            continue
        if comp["robots"] == 1 and comp["free_sites"] == comp["target_cells"]:
            lone += 1
            continue
        shown = " ".join(f"({x},{y})" for x, y in comp["free_tags"])
        more = comp["free_sites"] - len(comp["free_tags"])
        lines.append(
            f"group {k}: {comp['free_sites']} target sites free: {shown}"
            + (f" and {more} more" if more > 0 else "")
            + f"; {comp['searching']} robots searching"
            + (f", {inside} of them in the shape's hole" if (inside := comp.get("shut_in_holes"))
               else "")
            + ("; the free sites make a way across the ring" if comp.get("way_across") else "")
        )
    if lone:
        lines.append(f"{lone} robot(s) out of range of every other robot")
    return lines
