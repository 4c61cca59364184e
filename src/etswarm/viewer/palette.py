"""Fixed colours: one colour-blind-safe colour per ET state (Okabe & Ito, 2008).

The eight Okabe–Ito colours are told apart under the common colour-vision
deficiencies. Queued is orange as in the paper's figures; Danger is the reddish
vermillion; Leader is black so the one robot that matters during regeneration stands
out. Robots without an ET state are light grey; killed robots dark grey with a cross.
"""

from __future__ import annotations

from etswarm.algorithm.states import State

RGB = tuple[int, int, int]

#: Okabe–Ito colours by name.
OKABE_ITO: dict[str, RGB] = {
    "orange": (230, 159, 0),
    "sky_blue": (86, 180, 233),
    "bluish_green": (0, 158, 115),
    "yellow": (240, 228, 66),
    "blue": (0, 114, 178),
    "vermillion": (213, 94, 0),
    "reddish_purple": (204, 121, 167),
    "black": (0, 0, 0),
}

#: Fill colour of each ET state.
STATE_COLOURS: dict[int, RGB] = {
    State.QUEUED: OKABE_ITO["orange"],
    State.SEARCH: OKABE_ITO["blue"],
    State.INACTIVE: OKABE_ITO["sky_blue"],
    State.ACTIVE: OKABE_ITO["yellow"],
    State.QUASI: OKABE_ITO["reddish_purple"],
    State.STABLE: OKABE_ITO["bluish_green"],
    State.DANGER: OKABE_ITO["vermillion"],
    State.LEADER: OKABE_ITO["black"],
}

#: Fill of robots without an ET state (code 255).
NEUTRAL: RGB = (170, 170, 170)
#: Fill of killed robots (present but not alive).
DEAD: RGB = (90, 90, 90)

BACKGROUND: RGB = (255, 255, 255)
TARGET_SITE: RGB = (226, 226, 226)
LINK: RGB = (178, 178, 178)
OUTLINE: RGB = (40, 40, 40)
TEXT: RGB = (20, 20, 20)
PANEL: RGB = (245, 245, 245)
PANEL_BORDER: RGB = (160, 160, 160)
SELECTION: RGB = (213, 94, 0)


def state_colour(code: int) -> RGB:
    """The fill colour of state ``code`` (neutral grey for 255 or unknown codes)."""
    return STATE_COLOURS.get(int(code), NEUTRAL)


def contrasting(rgb: RGB) -> RGB:
    """Black or white, whichever reads better on ``rgb`` (relative luminance rule)."""
    r, g, b = rgb
    luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b
    return (0, 0, 0) if luminance > 110 else (255, 255, 255)


def blend(rgb: RGB, other: RGB, t: float) -> RGB:
    """``rgb`` moved a fraction ``t`` (0..1) of the way to ``other``."""
    return tuple(round(a + (b - a) * t) for a, b in zip(rgb, other, strict=True))  # type: ignore[return-value]
