"""PNG snapshots at the moments that matter: start, formation, each damage, each reform.

For ``--snapshots`` style output (the paper's Figs. 5–8): feed :class:`EventSnapshots`
the scene and the run's event list as the run advances; it saves one picture at the
start and one for every event it has not seen yet, each fitted to the whole swarm.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from etswarm.viewer.render import render
from etswarm.viewer.scene import Scene
from etswarm.viewer.video import save_png
from etswarm.viewer.view import ViewState


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "event"


class EventSnapshots:
    """Save ``NN-<kind>-<h>h<mm>m<ss>s.png`` files into ``out_dir``.

    Args:
        out_dir: folder for the PNGs (created).
        size: picture size in pixels (width, height).
    """

    def __init__(self, out_dir: str | Path, size: tuple[int, int] = (1000, 750)) -> None:
        self.out_dir = Path(out_dir)
        self.size = size
        self.saved: list[Path] = []
        self._seen = 0

    def capture(self, scene: Scene, label: str) -> Path:
        """Save ``scene`` now under ``label``."""
        view = ViewState.fitted(scene, *self.size, show_trails=False)
        t = int(scene.sim_time_s)
        stamp = f"{t // 3600}h{t % 3600 // 60:02d}m{t % 60:02d}s"
        name = f"{len(self.saved):02d}-{_slug(label)}-{stamp}.png"
        path = save_png(render(scene, view), self.out_dir / name)
        self.saved.append(path)
        return path

    def start(self, scene: Scene) -> Path:
        """The picture of the starting swarm."""
        return self.capture(scene, "start")

    def update(self, scene: Scene, events: list[dict[str, Any]]) -> list[Path]:
        """Save a picture for each event of ``events`` not seen before (in order)."""
        new = events[self._seen :]
        self._seen = len(events)
        return [self.capture(scene, str(e.get("kind", "event"))) for e in new]
