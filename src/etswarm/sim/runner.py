"""Running a simulator for a while: chunks sized for a responsive progress bar, frames
captured by a recorder at its interval, early stop when the controller asks."""

from __future__ import annotations

import time
from collections.abc import Callable

from etswarm.sim.recorder import Recorder
from etswarm.sim.simulator import Simulator


def run_for(sim: Simulator, ticks: int, recorder: Recorder | None = None,
            progress: Callable[[int], None] | None = None,
            target_call_s: float = 0.2) -> int:
    """Run ``ticks`` ticks; returns the ticks run (fewer if the controller stopped).

    Each compiled call runs as many ticks as take about ``target_call_s`` seconds (so a
    progress callback, given the ticks done per call, updates a few times a second) but
    never past the recorder's next frame. Frames are taken at every multiple of the
    recorder's interval, including the start.
    """
    chunk = max(1, sim.params.ticks_per_s)
    done = 0
    if recorder is not None and recorder.due():
        recorder.capture()
    while done < ticks:
        step = min(ticks - done, chunk)
        if recorder is not None:
            step = min(step, recorder.ticks_to_next_frame())
        t0 = time.perf_counter()
        ran = sim.run_ticks(step)
        elapsed = time.perf_counter() - t0
        done += ran
        if recorder is not None and recorder.due():
            recorder.capture()
        if progress is not None:
            progress(ran)
        if ran < step:
            break
        if step == chunk:
            scale = target_call_s / max(elapsed, 1e-6)
            chunk = int(min(max(chunk * min(scale, 4.0), 1), 1_000_000))
    return done
