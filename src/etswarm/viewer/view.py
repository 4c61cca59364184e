"""How a scene is looked at: canvas, camera, toggles and the trail history.

World coordinates are mm with y up; screen coordinates are pixels with y down and the
origin at the canvas's top-left corner. ``centre_mm`` is the world point at the canvas
centre and ``zoom`` is pixels per mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from etswarm.viewer.scene import Scene

#: Screen space kept free for overlays when fitting (pixels).
LEGEND_RESERVE_PX = 140
TITLE_RESERVE_PX = 30
STATUS_RESERVE_PX = 50


class Trails:
    """Recent positions of every robot, fed one scene at a time.

    Keeps up to ``length`` samples; a new sample is taken only when the scene's time is
    at least ``min_dt_s`` after the last one (a scene pushed twice counts once). Time
    going backwards or a change in robot count clears the history.
    """

    def __init__(self, length: int = 40, min_dt_s: float = 0.0) -> None:
        if length < 2:
            raise ValueError(f"trail length must be >= 2, got {length}")
        self.length = int(length)
        self.min_dt_s = float(min_dt_s)
        self._pos: np.ndarray | None = None  # (length, N, 2) float32
        self._present: np.ndarray | None = None  # (length, N) bool
        self._count = 0
        self._next = 0
        self._last_time: float | None = None

    def clear(self) -> None:
        """Forget every sample."""
        self._pos = None
        self._present = None
        self._count = 0
        self._next = 0
        self._last_time = None

    def push(self, scene: Scene) -> bool:
        """Record the robots' positions in ``scene``; True when a sample was taken."""
        t = float(scene.sim_time_s)
        if self._pos is not None and self._pos.shape[1] != scene.n:
            self.clear()
        if self._last_time is not None:
            if t < self._last_time:
                self.clear()
            elif t == self._last_time or t - self._last_time < self.min_dt_s:
                return False
        if self._pos is None:
            self._pos = np.zeros((self.length, scene.n, 2), np.float32)
            self._present = np.zeros((self.length, scene.n), bool)
        assert self._present is not None
        self._pos[self._next] = scene.pos
        self._present[self._next] = scene.present
        self._next = (self._next + 1) % self.length
        self._count = min(self._count + 1, self.length)
        self._last_time = t
        return True

    def __len__(self) -> int:
        return self._count

    def history(self) -> tuple[np.ndarray, np.ndarray]:
        """(positions (K, N, 2) mm, present (K, N) bool), oldest sample first."""
        if self._pos is None or self._count == 0:
            return np.zeros((0, 0, 2), np.float32), np.zeros((0, 0), bool)
        assert self._present is not None
        order = (np.arange(self._count) + self._next - self._count) % self.length
        return self._pos[order], self._present[order]


@dataclass
class ViewState:
    """Camera, toggles and trail history of one view. Mutable; the window edits it.

    Attributes:
        width, height: canvas size in pixels.
        centre_mm: (2,) world point at the canvas centre (mm).
        zoom: pixels per mm.
        show_links, show_trails, show_labels, show_legend, show_status, show_targets:
            what to draw.
        trails: the trail history; :func:`etswarm.viewer.render.render` feeds it.
        selected: index of the highlighted robot, or None.
        label_min_radius_px: labels appear when a body is at least this big on screen.
    """

    width: int = 1000
    height: int = 750
    centre_mm: np.ndarray = field(default_factory=lambda: np.zeros(2))
    zoom: float = 1.0
    show_links: bool = True
    show_trails: bool = True
    show_labels: bool = True
    show_legend: bool = True
    show_status: bool = True
    show_targets: bool = True
    trails: Trails = field(default_factory=Trails)
    selected: int | None = None
    label_min_radius_px: float = 20.0

    def __post_init__(self) -> None:
        self.centre_mm = np.asarray(self.centre_mm, dtype=np.float64).reshape(2)
        if self.width < 16 or self.height < 16:
            raise ValueError(f"canvas must be at least 16x16 px, got {self.width}x{self.height}")
        if not self.zoom > 0:
            raise ValueError(f"zoom must be > 0, got {self.zoom}")

    def world_to_screen(self, pts_mm: np.ndarray) -> np.ndarray:
        """(..., 2) mm -> (..., 2) float pixels."""
        pts = np.asarray(pts_mm, dtype=np.float64)
        out = np.empty_like(pts)
        out[..., 0] = self.width / 2 + (pts[..., 0] - self.centre_mm[0]) * self.zoom
        out[..., 1] = self.height / 2 - (pts[..., 1] - self.centre_mm[1]) * self.zoom
        return out

    def screen_to_world(self, pts_px: np.ndarray | tuple[float, float]) -> np.ndarray:
        """(..., 2) pixels -> (..., 2) mm."""
        pts = np.asarray(pts_px, dtype=np.float64)
        out = np.empty_like(pts)
        out[..., 0] = self.centre_mm[0] + (pts[..., 0] - self.width / 2) / self.zoom
        out[..., 1] = self.centre_mm[1] - (pts[..., 1] - self.height / 2) / self.zoom
        return out

    def zoom_at(self, factor: float, screen_px: tuple[float, float]) -> None:
        """Zoom by ``factor`` keeping the world point under ``screen_px`` fixed."""
        anchor = self.screen_to_world(screen_px)
        self.zoom = float(np.clip(self.zoom * factor, 1e-4, 40.0))
        after = self.screen_to_world(screen_px)
        self.centre_mm = self.centre_mm + (anchor - after)

    def pan_px(self, dx: float, dy: float) -> None:
        """Move the picture by (dx, dy) pixels (content follows the mouse)."""
        self.centre_mm = self.centre_mm + np.array([-dx / self.zoom, dy / self.zoom])

    def fit(self, scene: Scene, margin: float = 0.04) -> None:
        """Centre and zoom so every present robot and target site is in view, clear of
        the legend (left), the title (top) and the status line (bottom) when shown."""
        pts = [scene.pos[scene.present], scene.target_sites]
        allpts = np.concatenate([p for p in pts if len(p)] or [np.zeros((1, 2))])
        lo = allpts.min(axis=0) - scene.body_radius_mm
        hi = allpts.max(axis=0) + scene.body_radius_mm
        span = np.maximum(hi - lo, 4 * scene.body_radius_mm)
        left = LEGEND_RESERVE_PX if self.show_legend else 0
        top = TITLE_RESERVE_PX if scene.title else 0
        bottom = STATUS_RESERVE_PX if self.show_status else 0
        if self.width - left < 0.6 * self.width:
            left = 0
        if self.height - top - bottom < 0.6 * self.height:
            top = bottom = 0
        usable = np.array(
            [
                (self.width - left) * (1 - 2 * margin),
                (self.height - top - bottom) * (1 - 2 * margin),
            ]
        )
        self.zoom = float(np.min(usable / span))
        mid = (lo + hi) / 2
        dx, dy = left / 2, (top - bottom) / 2  # screen offset of the usable area's centre
        self.centre_mm = np.array([mid[0] - dx / self.zoom, mid[1] + dy / self.zoom])

    @classmethod
    def fitted(
        cls, scene: Scene, width: int = 1000, height: int = 750, **kwargs: object
    ) -> ViewState:
        """A view of ``width`` x ``height`` px that shows the whole ``scene``."""
        view = cls(width=width, height=height, **kwargs)  # type: ignore[arg-type]
        view.fit(scene)
        return view
