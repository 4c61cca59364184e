"""The one renderer: a :class:`Scene` seen through a :class:`ViewState` -> RGB pixels.

The live window, the video writer and the PNG snapshots all call :func:`render_onto`
(or :func:`render`, which wraps it), so they look the same. Drawing is on pygame
Surfaces, which need no window.

Speed: robots are blitted from cached anti-aliased "stamps" (one per fill colour,
heading bin and on-screen radius) in a single ``Surface.blits`` call; link pairs come
from a k-d tree. A 1000-robot frame takes a few milliseconds.
"""

from __future__ import annotations

import math
from collections import OrderedDict

import numpy as np

from etswarm.algorithm.states import STATE_NAMES, State
from etswarm.viewer import palette
from etswarm.viewer.links import comm_links
from etswarm.viewer.pg import pygame_headless_safe
from etswarm.viewer.scene import NO_STATE, Scene
from etswarm.viewer.view import ViewState

pygame = pygame_headless_safe()

#: Heading directions are drawn in this many bins (10° each).
HEADING_BINS = 36
_SUPERSAMPLE = 4
_DEAD_KEY = 256  # colour-table index of killed robots


def _rgb(row: np.ndarray) -> tuple[int, int, int]:
    return (int(row[0]), int(row[1]), int(row[2]))


#: (256 + 1, 3) fill colour per state code; the extra last row is "dead".
FILL_LUT = np.array([palette.state_colour(c) for c in range(256)] + [palette.DEAD], dtype=np.uint8)

#: Trail colour per fill key: the fill faded towards the background.
TRAIL_LUT = np.array(
    [palette.blend(_rgb(row), palette.BACKGROUND, 0.55) for row in FILL_LUT],
    dtype=np.uint8,
)


class _LRU(OrderedDict):
    """A small least-recently-used cache."""

    def __init__(self, capacity: int) -> None:
        super().__init__()
        self.capacity = capacity

    def get_or(self, key: object, make):  # type: ignore[no-untyped-def]
        if key in self:
            self.move_to_end(key)
            return self[key]
        value = make()
        self[key] = value
        if len(self) > self.capacity:
            self.popitem(last=False)
        return value


_stamps: _LRU = _LRU(4000)
_texts: _LRU = _LRU(4000)
_fonts: dict[tuple[int, bool], object] = {}


def font(size: int, bold: bool = False):  # type: ignore[no-untyped-def]
    """pygame's bundled font at ``size`` px (cached)."""
    key = (int(size), bold)
    if key not in _fonts:
        f = pygame.font.Font(None, int(size))
        f.set_bold(bold)
        _fonts[key] = f
    return _fonts[key]


def text_surface(text: str, size: int, colour: tuple[int, int, int], bold: bool = False):  # type: ignore[no-untyped-def]
    """A rendered, anti-aliased line of text (cached)."""
    return _texts.get_or(
        (text, size, colour, bold), lambda: font(size, bold).render(text, True, colour)
    )


# --------------------------------------------------------------------------- stamps


def _supersample(r_px: float) -> int:
    """Anti-aliasing factor for a stamp: 4x for small discs, less for big ones."""
    return _SUPERSAMPLE if r_px < 40 else (2 if r_px < 160 else 1)


def _radius_key(r_px: float) -> float:
    """On-screen radii are quantised so zooming does not fill the stamp cache."""
    return max(0.5, round(r_px * 4) / 4)


def _disc_stamp(fill_key: int, r_px: float, heading_bin: int, ring: bool = False):  # type: ignore[no-untyped-def]
    """An anti-aliased disc of colour ``FILL_LUT[fill_key]`` with a heading tick."""

    def make():  # type: ignore[no-untyped-def]
        ss = _supersample(r_px)
        size = math.ceil(2 * r_px) + 2
        big = pygame.Surface((size * ss, size * ss), pygame.SRCALPHA)
        c = size * ss / 2
        r = r_px * ss
        fill = _rgb(FILL_LUT[fill_key])
        pygame.draw.circle(big, fill, (c, c), r)
        if r_px >= 3:
            pygame.draw.circle(big, palette.OUTLINE, (c, c), r, width=max(1, int(ss * 0.9)))
        mark = palette.contrasting(fill)
        width = max(ss, int(r * 0.16))
        if fill_key == _DEAD_KEY and r_px >= 2:
            k = r * 0.5
            pygame.draw.line(big, (255, 255, 255), (c - k, c - k), (c + k, c + k), width)
            pygame.draw.line(big, (255, 255, 255), (c - k, c + k), (c + k, c - k), width)
        elif heading_bin >= 0 and r_px >= 2:
            a = (heading_bin + 0.5) * 2 * math.pi / HEADING_BINS
            dx, dy = math.cos(a), -math.sin(a)
            pygame.draw.line(
                big,
                mark,
                (c + dx * r * 0.55, c + dy * r * 0.55),
                (c + dx * r * 0.92, c + dy * r * 0.92),
                width,
            )
        if ring:
            pygame.draw.circle(big, palette.SELECTION, (c, c), r, width=max(ss, int(r * 0.2)))
        return pygame.transform.smoothscale(big, (size, size))

    return _stamps.get_or(("disc", fill_key, r_px, heading_bin, ring), make)


def _site_stamp(r_px: float):  # type: ignore[no-untyped-def]
    def make():  # type: ignore[no-untyped-def]
        ss = _supersample(r_px)
        size = math.ceil(2 * r_px) + 2
        big = pygame.Surface((size * ss, size * ss), pygame.SRCALPHA)
        pygame.draw.circle(big, palette.TARGET_SITE, (size * ss / 2, size * ss / 2), r_px * ss)
        return pygame.transform.smoothscale(big, (size, size))

    return _stamps.get_or(("site", r_px), make)


# --------------------------------------------------------------------------- layers


def _visible(px: np.ndarray, margin: float, view: ViewState) -> np.ndarray:
    return (
        (px[:, 0] > -margin)
        & (px[:, 0] < view.width + margin)
        & (px[:, 1] > -margin)
        & (px[:, 1] < view.height + margin)
    )


def _fill_keys(scene: Scene) -> np.ndarray:
    keys = scene.state.astype(np.int64)
    keys[~scene.alive] = _DEAD_KEY
    return keys


def _draw_targets(surf, scene: Scene, view: ViewState) -> None:  # type: ignore[no-untyped-def]
    if len(scene.target_sites) == 0:
        return
    r_px = _radius_key(scene.body_radius_mm * view.zoom)
    px = view.world_to_screen(scene.target_sites)
    px = px[_visible(px, r_px + 2, view)]
    stamp = _site_stamp(r_px)
    half = stamp.get_width() / 2
    surf.blits([(stamp, (round(x - half), round(y - half))) for x, y in px], False)


def raster_segments(
    surf,
    a: np.ndarray,
    b: np.ndarray,
    lut: np.ndarray,
    keys: np.ndarray | None = None,
    width: int = 1,
) -> None:  # type: ignore[no-untyped-def]
    """Draw many 1-px (or 2-px) line segments at once with numpy.

    Args:
        surf: the pygame Surface drawn on.
        a, b: (S, 2) float segment end points in pixels.
        lut: (K, 3) uint8 colour table, or (3,) one colour for all segments.
        keys: (S,) int row of ``lut`` for each segment (with a (K, 3) table).
        width: 1 or 2 pixels.
    """
    if len(a) == 0:
        return
    w, h = surf.get_size()
    a = a.astype(np.float32)
    d = b.astype(np.float32) - a
    steps = np.minimum(np.ceil(np.abs(d).max(axis=1)).astype(np.int64), 2 * (w + h)) + 1
    seg = np.repeat(np.arange(len(a)), steps)
    first = np.cumsum(steps) - steps
    t = (np.arange(seg.size) - first[seg]).astype(np.float32) / np.maximum(
        steps[seg] - 1, 1
    ).astype(np.float32)
    x = np.rint(a[seg, 0] + t * d[seg, 0]).astype(np.int64)
    y = np.rint(a[seg, 1] + t * d[seg, 1]).astype(np.int64)
    lut = np.asarray(lut, dtype=np.uint8)
    if lut.ndim == 2:
        assert keys is not None
        mapped = np.array([surf.map_rgb(tuple(int(c) for c in row)) for row in lut], np.int64)
        value: np.ndarray | int = mapped[keys][seg]
    else:
        value = surf.map_rgb(tuple(int(c) for c in lut))
    if surf.get_bytesize() != 4:  # 2D pixel access needs 32-bit pixels
        tmp = pygame.Surface(surf.get_size(), 0, 32)
        tmp.blit(surf, (0, 0))
        raster_segments(tmp, a, b, lut, keys, width)
        surf.blit(tmp, (0, 0))
        return
    pixels = pygame.surfarray.pixels2d(surf)
    try:
        for ox, oy in ((0, 0), (1, 0), (0, 1))[: 1 if width < 2 else 3]:
            xx, yy = x + ox, y + oy
            ok = (xx >= 0) & (xx < w) & (yy >= 0) & (yy < h)
            pixels[xx[ok], yy[ok]] = value[ok] if isinstance(value, np.ndarray) else value
    finally:
        del pixels


def _draw_links(surf, scene: Scene, view: ViewState, px: np.ndarray) -> None:  # type: ignore[no-untyped-def]
    pairs = comm_links(scene.pos, scene.present & scene.alive, scene.comm_range_mm)
    if len(pairs) == 0:
        return
    a, b = px[pairs[:, 0]], px[pairs[:, 1]]
    keep = _visible(a, view.width, view) | _visible(b, view.width, view)
    width = 2 if view.zoom >= 3 else 1
    raster_segments(surf, a[keep], b[keep], np.array(palette.LINK, np.uint8), width=width)


def _draw_trails(surf, scene: Scene, view: ViewState, fill_keys: np.ndarray) -> None:  # type: ignore[no-untyped-def]
    hist, present = view.trails.history()
    if len(hist) < 2 or hist.shape[1] != scene.n:
        return
    px = view.world_to_screen(hist)  # (K, N, 2)
    # a jump of more than five bodies between samples is a teleport (damage), not a path
    step = np.linalg.norm(np.diff(hist, axis=0), axis=2)  # (K-1, N)
    ok = (step <= 5 * scene.body_radius_mm) & present[:-1] & present[1:] & scene.present
    ok &= step * view.zoom > 0.05
    k, i = np.nonzero(ok)
    if k.size == 0:
        return
    raster_segments(
        surf, px[k, i], px[k + 1, i], TRAIL_LUT, fill_keys[i], 2 if view.zoom >= 2 else 1
    )


def _draw_robots(
    surf, scene: Scene, view: ViewState, px: np.ndarray, fill_keys: np.ndarray
) -> None:  # type: ignore[no-untyped-def]
    r_px = _radius_key(scene.body_radius_mm * view.zoom)
    shown = scene.present & _visible(px, r_px + 2, view)
    idx = np.flatnonzero(shown)
    if idx.size == 0:
        return
    bins = (
        np.floor(np.mod(scene.heading[idx], 2 * math.pi) / (2 * math.pi) * HEADING_BINS)
    ).astype(np.int64) % HEADING_BINS
    combo = fill_keys[idx] * HEADING_BINS + bins
    if view.selected is not None and 0 <= view.selected < scene.n:
        combo[idx == view.selected] = -1 - combo[idx == view.selected]  # ringed stamp
    stamps = {}
    for c in np.unique(combo).tolist():
        ring = c < 0
        k = -1 - c if ring else c
        stamps[c] = _disc_stamp(k // HEADING_BINS, r_px, k % HEADING_BINS, ring)
    size = math.ceil(2 * r_px) + 2
    corners = np.rint(px[idx] - size / 2).astype(np.int64).tolist()
    surf.blits([(stamps[c], xy) for c, xy in zip(combo.tolist(), corners, strict=True)], False)


def _draw_labels(
    surf, scene: Scene, view: ViewState, px: np.ndarray, fill_keys: np.ndarray
) -> None:  # type: ignore[no-untyped-def]
    r_px = scene.body_radius_mm * view.zoom
    if r_px < view.label_min_radius_px:
        return
    size = int(np.clip(r_px * 0.72, 13, 24))
    ids = scene.robot_ids()
    shown = np.flatnonzero(scene.present & _visible(px, r_px, view))
    for i in shown.tolist():
        colour = palette.contrasting(_rgb(FILL_LUT[fill_keys[i]]))
        lines = [f"#{int(ids[i])}"]
        if scene.has_tag[i]:
            lines.append(f"{int(scene.tag[i, 0])},{int(scene.tag[i, 1])}")
            lines.append(f"ts{int(scene.ts[i])}")
        surfaces = [text_surface(t, size, colour) for t in lines]
        total = sum(s.get_height() for s in surfaces) - 2 * (len(surfaces) - 1)
        y = px[i, 1] - total / 2
        for s in surfaces:
            surf.blit(s, (int(px[i, 0] - s.get_width() / 2), int(y)))
            y += s.get_height() - 2


def _panel(surf, rect, alpha: int = 225) -> None:  # type: ignore[no-untyped-def]
    box = pygame.Surface((rect[2], rect[3]), pygame.SRCALPHA)
    box.fill((*palette.PANEL, alpha))
    surf.blit(box, (rect[0], rect[1]))
    pygame.draw.rect(surf, palette.PANEL_BORDER, rect, 1)


def _legend_rows(scene: Scene) -> list[tuple[tuple[int, int, int], str, int]]:
    counts = scene.state_counts()
    et_present = any(counts[int(s)] for s in State)
    rows = []
    if et_present or counts[NO_STATE] == 0:
        rows = [(palette.state_colour(s), STATE_NAMES[s], counts[int(s)]) for s in State]
    if counts[NO_STATE]:
        rows.append((palette.NEUTRAL, "No ET state", counts[NO_STATE]))
    dead = int((scene.present & ~scene.alive).sum())
    if dead:
        rows.append((palette.DEAD, "Dead", dead))
    return rows


def _draw_legend(surf, scene: Scene, view: ViewState) -> None:  # type: ignore[no-untyped-def]
    rows = _legend_rows(scene)
    size = 18
    line_h = 20
    label_w = max(text_surface(name, size, palette.TEXT).get_width() for _, name, _ in rows)
    count_w = max(text_surface(str(c), size, palette.TEXT).get_width() for *_, c in rows)
    width = 10 + 14 + 8 + label_w + 12 + count_w + 10
    height = 8 + line_h * len(rows) + 4
    top = 8 + (26 if scene.title else 0)
    _panel(surf, (8, top, width, height))
    y = top + 8
    for colour, name, count in rows:
        pygame.draw.circle(surf, colour, (8 + 10 + 7, y + 8), 7)
        pygame.draw.circle(surf, palette.OUTLINE, (8 + 10 + 7, y + 8), 7, 1)
        surf.blit(text_surface(name, size, palette.TEXT), (8 + 10 + 14 + 8, y + 2))
        cs = text_surface(str(count), size, palette.TEXT)
        surf.blit(cs, (8 + width - 10 - cs.get_width(), y + 2))
        y += line_h


def format_sim_time(seconds: float) -> str:
    """Simulated time as ``h:mm:ss``."""
    s = max(0, int(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}"


def status_text(scene: Scene) -> str:
    """The status line's first row as plain text (time, speed, robots)."""
    parts = [f"t {format_sim_time(scene.sim_time_s)}"]
    if scene.speedup is not None:
        parts.append(
            f"×{scene.speedup:.3g} real time"
            if scene.speedup < 1000
            else f"×{scene.speedup:.0f} real time"
        )
    present = int(scene.present.sum())
    dead = int((scene.present & ~scene.alive).sum())
    parts.append(f"{present} robots" + (f" ({dead} dead)" if dead else ""))
    return "   ".join(parts)


def _draw_status(surf, scene: Scene, view: ViewState) -> None:  # type: ignore[no-untyped-def]
    size = 19
    height = 48
    top = view.height - height
    _panel(surf, (0, top, view.width, height), alpha=235)
    x = 10
    y = top + 6
    head = text_surface(status_text(scene), size, palette.TEXT, bold=True)
    surf.blit(head, (x, y))
    x += head.get_width() + 18
    for colour, _name, count in _legend_rows(scene):
        if x > view.width - 40:
            break
        pygame.draw.rect(surf, colour, (x, y + 1, 12, 12))
        pygame.draw.rect(surf, palette.OUTLINE, (x, y + 1, 12, 12), 1)
        cs = text_surface(str(count), size, palette.TEXT)
        surf.blit(cs, (x + 16, y))
        x += 16 + cs.get_width() + 12
    if scene.events:
        text = "  |  ".join(scene.events[-3:])
        ev = text_surface(text, 17, (70, 70, 70))
        if ev.get_width() > view.width - 20:
            while (
                len(text) > 4
                and text_surface("…" + text, 17, (70, 70, 70)).get_width() > view.width - 20
            ):
                text = text[max(1, len(text) // 12) :]
            ev = text_surface("…" + text, 17, (70, 70, 70))
        surf.blit(ev, (10, top + 27))


def _draw_title(surf, scene: Scene, view: ViewState) -> None:  # type: ignore[no-untyped-def]
    if not scene.title:
        return
    t = text_surface(scene.title, 22, palette.TEXT, bold=True)
    surf.blit(t, ((view.width - t.get_width()) // 2, 8))


# --------------------------------------------------------------------------- entry points


def render_onto(surf, scene: Scene, view: ViewState) -> None:  # type: ignore[no-untyped-def]
    """Draw ``scene`` on the pygame Surface ``surf`` (at least ``view`` size).

    Feeds ``view.trails`` with the scene (a scene with an unchanged time adds nothing).
    """
    view.trails.push(scene)
    surf.fill(palette.BACKGROUND)
    px = view.world_to_screen(scene.pos) if scene.n else np.zeros((0, 2))
    fill_keys = _fill_keys(scene)
    if view.show_targets:
        _draw_targets(surf, scene, view)
    if view.show_links:
        _draw_links(surf, scene, view, px)
    if view.show_trails:
        _draw_trails(surf, scene, view, fill_keys)
    _draw_robots(surf, scene, view, px, fill_keys)
    if view.show_labels:
        _draw_labels(surf, scene, view, px, fill_keys)
    _draw_title(surf, scene, view)
    if view.show_legend:
        _draw_legend(surf, scene, view)
    if view.show_status:
        _draw_status(surf, scene, view)


def surface_to_rgb(surf) -> np.ndarray:  # type: ignore[no-untyped-def]
    """(H, W, 3) uint8 copy of a Surface's pixels."""
    w, h = surf.get_size()
    return np.frombuffer(pygame.image.tobytes(surf, "RGB"), dtype=np.uint8).reshape(h, w, 3).copy()


def render(scene: Scene, view: ViewState) -> np.ndarray:
    """Render ``scene`` as seen by ``view``: (view.height, view.width, 3) uint8 RGB."""
    surf = pygame.Surface((view.width, view.height), 0, 32)
    render_onto(surf, scene, view)
    return surface_to_rgb(surf)
