"""The live viewer: a pygame window over any :class:`~etswarm.viewer.live.LiveRun`.

Keys: space pause/resume · ``.`` step one simulated second (while paused) · replays
only: ``,`` back one recorded frame, Home restart · ``+``/``-``
speed ×2 / ÷2 · arrows pan · ``f`` fit · ``l`` links · ``t`` trails · ``n`` labels ·
``g`` legend · ``i`` status line · ``h`` help · ``r`` start/stop recording the window to
an .mp4 · ``s`` PNG snapshot of the picture · ``q``/Esc quit.

Mouse: wheel zooms at the cursor · middle-drag pans · left-click selects a robot (side
panel with its state, tag, NN, TS, ID and neighbour table) · left-drag a line splits the
swarm along it · shift+left-drag a rectangle removes the robots inside · right-click a
robot kills it.

Runs headless under SDL's dummy video driver; ``max_frames`` bounds the loop and
``frame_hook`` lets a test post events and read pixels between frames.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from datetime import datetime
from pathlib import Path

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.viewer import palette
from etswarm.viewer.live import LiveRun
from etswarm.viewer.pg import pygame_headless_safe
from etswarm.viewer.render import render_onto, surface_to_rgb, text_surface
from etswarm.viewer.scene import Scene
from etswarm.viewer.video import VideoWriter, save_png
from etswarm.viewer.view import ViewState

pygame = pygame_headless_safe()

#: A left-button gesture shorter than this (pixels) is a click, not a drag.
CLICK_SLOP_PX = 5
#: Width of the robot side panel (pixels).
PANEL_WIDTH = 330
#: Seconds a message stays on screen.
TOAST_S = 4.0

HELP_LINES = (
    "space  pause / resume          .  step 1 s (paused)",
    "+ / -  speed x2 / /2           arrows  pan    wheel  zoom",
    "f  fit   l  links   t  trails   n  labels   g  legend   i  status",
    "click  inspect robot     drag  split along line",
    "shift+drag  remove rectangle     right-click  kill robot",
    "r  record video   s  snapshot PNG   h  help   q / Esc  quit",
    "replay:  ,  back one frame    Home  restart",
)


@dataclasses.dataclass
class ViewerResult:
    """What a viewer session produced."""

    frames: int = 0
    snapshots: list[Path] = dataclasses.field(default_factory=list)
    videos: list[Path] = dataclasses.field(default_factory=list)
    quit_by_user: bool = False


class Viewer:
    """One window driving one live run. See the module docstring for the controls.

    Args:
        live_run: the run shown and driven.
        size: window size in pixels (width, height).
        fps: frame rate cap (0 = as fast as possible).
        speed: target simulated seconds per wall second.
        start_paused: begin paused.
        output_dir: folder for snapshots and recordings.
        view: the initial ViewState (fitted to the first scene when None).
        caption: window title.
    """

    def __init__(
        self,
        live_run: LiveRun,
        size: tuple[int, int] = (1200, 800),
        fps: float = 30.0,
        speed: float = 10.0,
        start_paused: bool = False,
        output_dir: str | Path = ".",
        view: ViewState | None = None,
        caption: str = "etswarm",
    ) -> None:
        if speed <= 0:
            raise EtswarmError(f"--speed must be > 0, got {speed}")
        self.run_ = live_run
        self.fps = float(fps)
        self.speed = float(speed)
        self.paused = bool(start_paused)
        self.output_dir = Path(output_dir)
        pygame.display.init()
        self.screen = pygame.display.set_mode(size)
        pygame.display.set_caption(caption)
        self.canvas = pygame.Surface(size, 0, 32)
        self.scene: Scene = live_run.scene()
        if view is None:
            view = ViewState.fitted(self.scene, size[0], size[1])
        else:
            view.width, view.height = size
        self.view = view
        self.clock = pygame.time.Clock()
        self.result = ViewerResult()
        self.show_help = False
        self._tick_debt = 0.0
        self._measured_speed: float | None = None
        self._drag_start: tuple[int, int] | None = None
        self._drag_now: tuple[int, int] | None = None
        self._drag_shift = False
        self._shift_held = False
        self._panning = False
        self._toasts: list[tuple[float, str]] = []
        self._writer: VideoWriter | None = None
        self._running = True
        self._last_wall = time.perf_counter()
        #: (H, W, 3) RGB copy of the window's last frame, kept when the window closes.
        self.last_frame: np.ndarray | None = None

    # ------------------------------------------------------------------ helpers
    def toast(self, message: str) -> None:
        """Show ``message`` for a few seconds."""
        self._toasts.append((time.perf_counter() + TOAST_S, message))
        self._toasts = self._toasts[-4:]

    def pick_robot(self, screen_px: tuple[float, float]) -> int | None:
        """Index of the present robot under ``screen_px`` (within 1.2 body radii), or None."""
        scene = self.scene
        if scene.n == 0:
            return None
        p = self.view.screen_to_world(screen_px)
        d = np.linalg.norm(scene.pos - p, axis=1)
        d[~scene.present] = np.inf
        i = int(np.argmin(d))
        limit = max(1.2 * scene.body_radius_mm, 6.0 / self.view.zoom)
        return i if d[i] <= limit else None

    def _out_path(self, stem: str, suffix: str) -> Path:
        stamp = datetime.now().strftime("%Y%m%d-%H%M%S")
        path = self.output_dir / f"{stem}-{stamp}{suffix}"
        k = 1
        while path.exists():
            path = self.output_dir / f"{stem}-{stamp}-{k}{suffix}"
            k += 1
        return path

    def _damage(self, what: str, call: Callable[[], None]) -> None:
        try:
            call()
        except (EtswarmError, NotImplementedError) as err:
            self.toast(f"{what}: {err}")
            return
        self.toast(what)
        self.scene = self.run_.scene()

    def snapshot(self) -> Path:
        """Save the current picture (without window overlays) as a PNG."""
        path = save_png(surface_to_rgb(self.canvas), self._out_path("etswarm-snapshot", ".png"))
        self.result.snapshots.append(path)
        self.toast(f"snapshot saved: {path}")
        return path

    def toggle_recording(self) -> None:
        """Start recording the window, or stop and finalize the current recording."""
        if self._writer is None:
            self._writer = VideoWriter(self._out_path("etswarm-recording", ".mp4"), self.fps or 30)
            self.toast(f"recording to {self._writer.path}")
        else:
            self._stop_recording()

    def _stop_recording(self) -> None:
        if self._writer is None:
            return
        writer, self._writer = self._writer, None
        path = writer.close()
        if writer.frame_count:
            self.result.videos.append(path)
            self.toast(f"video saved: {path} ({writer.frame_count} frames)")

    # ------------------------------------------------------------------ events
    def handle_event(self, event) -> None:  # type: ignore[no-untyped-def]
        """React to one pygame event."""
        if event.type == pygame.QUIT:
            self._running = False
            self.result.quit_by_user = True
        elif event.type == pygame.KEYDOWN:
            self._on_key(event)
        elif event.type == pygame.KEYUP:
            if event.key in (pygame.K_LSHIFT, pygame.K_RSHIFT):
                self._shift_held = False
        elif event.type == pygame.MOUSEWHEEL:
            factor = 1.2 ** float(event.y)
            self.view.zoom_at(factor, pygame.mouse.get_pos())
        elif event.type == pygame.MOUSEBUTTONDOWN:
            self._on_press(event)
        elif event.type == pygame.MOUSEMOTION:
            if self._panning:
                self.view.pan_px(*event.rel)
            if self._drag_start is not None:
                self._drag_now = event.pos
        elif event.type == pygame.MOUSEBUTTONUP:
            self._on_release(event)

    def _shift(self) -> bool:
        return self._shift_held or bool(pygame.key.get_mods() & pygame.KMOD_SHIFT)

    def _on_key(self, event) -> None:  # type: ignore[no-untyped-def]
        key = event.key
        v = self.view
        step_px = 60
        if key in (pygame.K_LSHIFT, pygame.K_RSHIFT):
            self._shift_held = True
        elif key in (pygame.K_q, pygame.K_ESCAPE):
            self._running = False
            self.result.quit_by_user = True
        elif key == pygame.K_SPACE:
            self.paused = not self.paused
        elif key == pygame.K_PERIOD:
            if not self.run_.finished:
                self.run_.advance(int(self.run_.ticks_per_second))
                self.scene = self.run_.scene()
            self.paused = True
        elif key in (pygame.K_COMMA, pygame.K_HOME) and callable(getattr(self.run_, "seek", None)):
            # replays only: back one recorded frame (,) or to the start (Home)
            frame = 0 if key == pygame.K_HOME else max(int(getattr(self.run_, "frame", 0)) - 1, 0)
            self.run_.seek(frame)  # type: ignore[attr-defined]
            self.scene = self.run_.scene()
            self.paused = True
        elif key in (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS):
            self.speed = min(self.speed * 2, 1e6)
            self.toast(f"target speed x{self.speed:g}")
        elif key in (pygame.K_MINUS, pygame.K_KP_MINUS):
            self.speed = max(self.speed / 2, 1 / 64)
            self.toast(f"target speed x{self.speed:g}")
        elif key == pygame.K_LEFT:
            v.pan_px(step_px, 0)
        elif key == pygame.K_RIGHT:
            v.pan_px(-step_px, 0)
        elif key == pygame.K_UP:
            v.pan_px(0, step_px)
        elif key == pygame.K_DOWN:
            v.pan_px(0, -step_px)
        elif key == pygame.K_f:
            v.fit(self.scene)
        elif key == pygame.K_l:
            v.show_links = not v.show_links
        elif key == pygame.K_t:
            v.show_trails = not v.show_trails
        elif key == pygame.K_n:
            v.show_labels = not v.show_labels
        elif key == pygame.K_g:
            v.show_legend = not v.show_legend
        elif key == pygame.K_i:
            v.show_status = not v.show_status
        elif key == pygame.K_h:
            self.show_help = not self.show_help
        elif key == pygame.K_r:
            self.toggle_recording()
        elif key == pygame.K_s:
            self.snapshot()

    def _on_press(self, event) -> None:  # type: ignore[no-untyped-def]
        if event.button == 1:
            self._drag_start = event.pos
            self._drag_now = event.pos
            self._drag_shift = self._shift()
        elif event.button == 2:
            self._panning = True
        elif event.button == 3:
            i = self.pick_robot(event.pos)
            if i is not None:
                ids = self.scene.robot_ids()
                self._damage(f"killed robot #{int(ids[i])}", lambda: self.run_.damage_kill([i]))

    def _on_release(self, event) -> None:  # type: ignore[no-untyped-def]
        if event.button == 2:
            self._panning = False
            return
        if event.button != 1 or self._drag_start is None:
            return
        start, end = self._drag_start, event.pos
        shift = self._drag_shift or self._shift()
        self._drag_start = self._drag_now = None
        if math.dist(start, end) < CLICK_SLOP_PX:
            self.view.selected = self.pick_robot(end)
            return
        p0 = tuple(float(c) for c in self.view.screen_to_world(start))
        p1 = tuple(float(c) for c in self.view.screen_to_world(end))
        if shift:
            self._damage(
                f"removed rectangle ({p0[0]:.0f},{p0[1]:.0f})-({p1[0]:.0f},{p1[1]:.0f}) mm",
                lambda: self.run_.damage_remove_rect(p0, p1),  # type: ignore[arg-type]
            )
        else:
            self._damage(
                f"split along ({p0[0]:.0f},{p0[1]:.0f})-({p1[0]:.0f},{p1[1]:.0f}) mm",
                lambda: self.run_.damage_split(p0, p1),  # type: ignore[arg-type]
            )

    # ------------------------------------------------------------------ simulation
    def _advance(self) -> None:
        now = time.perf_counter()
        wall = max(now - self._last_wall, 1e-6)
        self._last_wall = now
        if self.paused or self.run_.finished:
            self._tick_debt = 0.0
            return
        tps = int(self.run_.ticks_per_second)
        frame_s = 1.0 / self.fps if self.fps > 0 else wall
        self._tick_debt += self.speed * tps * frame_s
        ticks = int(self._tick_debt)
        if ticks <= 0:
            return
        self._tick_debt -= ticks
        # advance in chunks and give up the rest when the frame's time budget is spent,
        # so a slow simulation lowers the speed instead of freezing the window
        budget = 0.8 * frame_s
        chunk = max(1, math.ceil(ticks / 4))
        done = 0
        t0 = time.perf_counter()
        while done < ticks and not self.run_.finished:
            k = min(chunk, ticks - done)
            self.run_.advance(k)
            done += k
            if time.perf_counter() - t0 > budget:
                break
        self._tick_debt = min(self._tick_debt, float(tps))
        measured = done / tps / wall
        if self._measured_speed is None:
            self._measured_speed = measured
        else:
            self._measured_speed = 0.9 * self._measured_speed + 0.1 * measured
        self.scene = self.run_.scene()

    # ------------------------------------------------------------------ drawing
    def _draw_panel(self) -> None:
        i = self.view.selected
        if i is None or i >= self.scene.n:
            return
        try:
            info = self.run_.robot_info(i)
        except Exception as err:  # a broken info call must not kill the window
            info = {"error": f"{type(err).__name__}: {err}"}
        w, h = self.screen.get_size()
        x0 = w - PANEL_WIDTH
        box = pygame.Surface((PANEL_WIDTH, h), pygame.SRCALPHA)
        box.fill((*palette.PANEL, 240))
        self.screen.blit(box, (x0, 0))
        pygame.draw.line(self.screen, palette.PANEL_BORDER, (x0, 0), (x0, h))
        y = 10
        ids = self.scene.robot_ids()
        head = text_surface(f"robot #{int(ids[i])}", 24, palette.TEXT, bold=True)
        self.screen.blit(head, (x0 + 12, y))
        y += 30
        for key, value in info.items():
            if y > h - 20:
                break
            if isinstance(value, list) and value and all(isinstance(r, dict) for r in value):
                self.screen.blit(text_surface(f"{key}:", 18, palette.TEXT, bold=True), (x0 + 12, y))
                y += 20
                y = self._draw_table(value, x0 + 12, y, h)
                continue
            line = text_surface(f"{key}: {value}", 18, palette.TEXT)
            self.screen.blit(line, (x0 + 12, y))
            y += 20

    def _draw_table(self, rows: list[dict], x: int, y: int, h: int) -> int:
        cols = list(dict.fromkeys(k for r in rows for k in r))
        cells = [[str(c) for c in cols]] + [[_cell(r.get(c, "")) for c in cols] for r in rows]
        widths = [
            max(text_surface(row[j], 16, palette.TEXT).get_width() for row in cells) + 10
            for j in range(len(cols))
        ]
        for k, row in enumerate(cells):
            if y > h - 18:
                break
            cx = x
            for j, text in enumerate(row):
                self.screen.blit(text_surface(text, 16, palette.TEXT, bold=(k == 0)), (cx, y))
                cx += widths[j]
            y += 17
        return y + 4

    def _draw_overlays(self) -> None:
        w, _h = self.screen.get_size()
        right = w - (PANEL_WIDTH if self.view.selected is not None else 0) - 10
        lines = []
        if self.run_.finished:
            lines.append(("finished", palette.TEXT))
        elif self.paused:
            lines.append(("PAUSED", palette.SELECTION))
        lines.append((f"target x{self.speed:g}", palette.TEXT))
        if self._writer is not None:
            lines.append((f"REC {self._writer.frame_count / (self.fps or 30):.0f} s", (213, 0, 0)))
        y = 10
        for text, colour in lines:
            s = text_surface(text, 20, colour, bold=True)
            self.screen.blit(s, (right - s.get_width(), y))
            y += 22
        now = time.perf_counter()
        self._toasts = [(t, m) for t, m in self._toasts if t > now]
        for _, message in self._toasts:
            s = text_surface(message, 18, palette.TEXT)
            self.screen.blit(s, (right - s.get_width(), y))
            y += 20
        start, now_px = self._drag_start, self._drag_now
        if start is not None and now_px is not None and math.dist(start, now_px) >= CLICK_SLOP_PX:
            if self._drag_shift or self._shift():
                (x0, y0), (x1, y1) = start, now_px
                rect = pygame.Rect(min(x0, x1), min(y0, y1), abs(x1 - x0), abs(y1 - y0))
                pygame.draw.rect(self.screen, palette.SELECTION, rect, 2)
            else:
                pygame.draw.line(self.screen, palette.SELECTION, start, now_px, 3)
        if self.show_help:
            sw = max(text_surface(t, 18, palette.TEXT).get_width() for t in HELP_LINES) + 24
            sh = 20 * len(HELP_LINES) + 16
            x0 = (w - sw) // 2
            box = pygame.Surface((sw, sh), pygame.SRCALPHA)
            box.fill((*palette.PANEL, 245))
            self.screen.blit(box, (x0, 60))
            pygame.draw.rect(self.screen, palette.PANEL_BORDER, (x0, 60, sw, sh), 1)
            for k, t in enumerate(HELP_LINES):
                self.screen.blit(text_surface(t, 18, palette.TEXT), (x0 + 12, 68 + 20 * k))

    def draw(self) -> None:
        """Render the scene and the window's overlays onto the screen."""
        scene = self.scene
        if self._measured_speed is not None and not self.paused:
            scene = dataclasses.replace(scene, speedup=self._measured_speed)
        render_onto(self.canvas, scene, self.view)
        self.screen.blit(self.canvas, (0, 0))
        self._draw_panel()
        self._draw_overlays()

    # ------------------------------------------------------------------ loop
    def frame(self) -> bool:
        """One frame: events, simulation, drawing. False once the viewer should close."""
        for event in pygame.event.get():
            self.handle_event(event)
            if not self._running:
                return False
        self._advance()
        self.draw()
        pygame.display.flip()
        if self._writer is not None:
            self._writer.write(surface_to_rgb(self.screen))
        self.result.frames += 1
        if self.fps > 0:
            self.clock.tick(self.fps)
        return self._running

    def run(
        self,
        max_frames: int | None = None,
        frame_hook: Callable[[Viewer, int], None] | None = None,
    ) -> ViewerResult:
        """Loop until quit (or ``max_frames``); finalizes any recording; closes the window.

        ``frame_hook(viewer, k)`` runs after frame ``k`` is shown (a test posts events
        there). Ctrl-C closes cleanly and keeps a recording in progress.
        """
        try:
            k = 0
            while max_frames is None or k < max_frames:
                if not self.frame():
                    break
                if frame_hook is not None:
                    frame_hook(self, k)
                k += 1
        except KeyboardInterrupt:
            self.result.quit_by_user = True
        finally:
            self._stop_recording()
            self.last_frame = surface_to_rgb(self.screen)
            pygame.display.quit()
        return self.result


def _cell(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.1f}"
    if isinstance(value, tuple | list):
        return ",".join(_cell(v) for v in value)
    return str(value)


def run_viewer(
    live_run: LiveRun,
    *,
    size: tuple[int, int] = (1200, 800),
    fps: float = 30.0,
    speed: float = 10.0,
    start_paused: bool = False,
    output_dir: str | Path = ".",
    view: ViewState | None = None,
    caption: str = "etswarm",
    max_frames: int | None = None,
    frame_hook: Callable[[Viewer, int], None] | None = None,
) -> ViewerResult:
    """Open a window on ``live_run`` and drive it until the user quits.

    See :class:`Viewer` for the arguments and the module docstring for the controls.
    """
    viewer = Viewer(
        live_run,
        size=size,
        fps=fps,
        speed=speed,
        start_paused=start_paused,
        output_dir=output_dir,
        view=view,
        caption=caption,
    )
    return viewer.run(max_frames=max_frames, frame_hook=frame_hook)
