"""Import pygame quietly and headless-safe.

Drawing on a ``pygame.Surface`` needs no window, but SDL still wants a video driver
when a window is opened. With no display (no ``DISPLAY``/``WAYLAND_DISPLAY`` on Linux)
we select SDL's ``dummy`` driver before pygame initialises, so the same code runs on a
laptop, in CI and over SSH.
"""

from __future__ import annotations

import os
import sys
from types import ModuleType

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


def has_display() -> bool:
    """True when a graphical display is likely available to SDL."""
    if os.environ.get("SDL_VIDEODRIVER") in ("dummy", "offscreen"):
        return False
    if sys.platform.startswith("linux"):
        return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    return True


def pygame_headless_safe() -> ModuleType:
    """Return the pygame module with its font system ready; dummy video without a display."""
    if not has_display():
        os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    import pygame

    if not pygame.font.get_init():
        pygame.font.init()
    return pygame
