"""Read bitmaps from text (0/1 or ./#), PBM (P1, P4) and any image Pillow opens.

Every reader returns an (H, W) bool array, row 0 = top, True = inside the shape, or raises
:class:`EtswarmError` with one line naming the file and what is wrong.

Text: one row a line; ``1``/``#`` inside, ``0``/``.`` outside; blank lines, lines starting
with ``;`` and lines starting with ``#`` that hold anything besides pixel characters (such as
``# a comment``) are ignored. PBM: 1 (black) is inside. Images: dark pixels (grey < 128,
transparent counts as white) are inside; ``invert`` swaps inside and outside for every format.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from etswarm.errors import EtswarmError

#: Largest bitmap (pixels) read at all; larger images are refused before thresholding.
MAX_PIXELS = 1_000_000

_PIXEL_CHARS = {"0": False, ".": False, "1": True, "#": True}
_CONTROL_OK = {"\t", "\n", "\r"}


def read_bitmap(path: Path, label: str | None = None) -> np.ndarray:
    """Read ``path`` in whichever format it holds; ``label`` names it in errors (default path)."""
    name = label or str(path)
    try:
        data = Path(path).read_bytes()
    except FileNotFoundError:
        raise EtswarmError(f"{name}: no such file") from None
    except IsADirectoryError:
        raise EtswarmError(f"{name}: is a directory, not a bitmap file") from None
    except OSError as err:
        raise EtswarmError(f"{name}: cannot read file ({err.strerror or err})") from None
    return parse_bitmap_bytes(data, name)


def parse_bitmap_bytes(data: bytes, name: str) -> np.ndarray:
    """Parse file contents ``data``; ``name`` labels errors."""
    if not data.strip():
        raise EtswarmError(f"{name}: file is empty")
    head = data.lstrip()[:2]
    if head in (b"P1", b"P4"):
        return parse_pbm(data, name)
    text = _as_text(data)
    if text is not None:
        return parse_text(text, name)
    return read_image(data, name)


def _as_text(data: bytes) -> str | None:
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return None
    if any(ord(ch) < 32 and ch not in _CONTROL_OK for ch in text):
        return None
    return text


def _is_comment(line: str) -> bool:
    if line.startswith(";"):
        return True
    return line.startswith("#") and any(ch not in _PIXEL_CHARS for ch in line)


def parse_text(text: str, name: str) -> np.ndarray:
    """Parse a text bitmap (see module docstring)."""
    rows: list[list[bool]] = []
    width = 0
    first_line = 0
    for line_no, raw in enumerate(text.splitlines(), start=1):
        line = raw.rstrip()
        if not line or _is_comment(line):
            continue
        row_no = len(rows) + 1
        row = []
        for col, ch in enumerate(line, start=1):
            if ch not in _PIXEL_CHARS:
                raise EtswarmError(
                    f"{name}: row {row_no} (line {line_no}), column {col}: "
                    f"character {ch!r} is not one of 0 1 . #"
                )
            row.append(_PIXEL_CHARS[ch])
        if not rows:
            width, first_line = len(row), line_no
        elif len(row) != width:
            raise EtswarmError(
                f"{name}: row {row_no} (line {line_no}) has {len(row)} pixels but row 1 "
                f"(line {first_line}) has {width}; all rows must be equally long"
            )
        rows.append(row)
        if len(rows) * width > MAX_PIXELS:
            raise EtswarmError(f"{name}: more than {MAX_PIXELS} pixels")
    if not rows:
        raise EtswarmError(f"{name}: empty: no pixel rows, only blank or comment lines")
    return np.array(rows, dtype=bool)


def _pbm_header(data: bytes, name: str) -> tuple[bytes, int, int, int]:
    """Return (magic, width, height, offset of the first byte after the header)."""
    pos = 0
    tokens: list[bytes] = []
    n = len(data)
    while len(tokens) < 3:
        while pos < n and data[pos : pos + 1].isspace():
            pos += 1
        if pos < n and data[pos : pos + 1] == b"#":
            while pos < n and data[pos : pos + 1] not in (b"\n", b"\r"):
                pos += 1
            continue
        if pos >= n:
            raise EtswarmError(f"{name}: PBM header ends early (need magic, width, height)")
        start = pos
        while pos < n and not data[pos : pos + 1].isspace() and data[pos : pos + 1] != b"#":
            pos += 1
        tokens.append(data[start:pos])
    magic = tokens[0]
    try:
        width, height = int(tokens[1]), int(tokens[2])
    except ValueError:
        raise EtswarmError(
            f"{name}: PBM width/height {tokens[1]!r} {tokens[2]!r} are not integers"
        ) from None
    if width <= 0 or height <= 0:
        raise EtswarmError(f"{name}: PBM size {width}x{height} is empty")
    if width * height > MAX_PIXELS:
        raise EtswarmError(f"{name}: PBM size {width}x{height} exceeds {MAX_PIXELS} pixels")
    return magic, width, height, pos


def parse_pbm(data: bytes, name: str) -> np.ndarray:
    """Parse PBM P1 (ASCII) or P4 (packed binary); 1 = black = inside."""
    magic, width, height, pos = _pbm_header(data.lstrip(), name)
    body = data.lstrip()[pos:]
    if magic == b"P4":
        body = body[1:]  # exactly one whitespace byte follows the height
        row_bytes = (width + 7) // 8
        need = row_bytes * height
        if len(body) < need:
            raise EtswarmError(
                f"{name}: PBM P4 data has {len(body)} bytes, {width}x{height} needs {need}"
            )
        packed = np.frombuffer(body[:need], dtype=np.uint8).reshape(height, row_bytes)
        return np.unpackbits(packed, axis=1)[:, :width].astype(bool)
    pixels: list[bool] = []
    in_comment = False
    for offset, byte in enumerate(body):
        ch = chr(byte)
        if in_comment:
            in_comment = ch not in "\r\n"
            continue
        if ch == "#":
            in_comment = True
        elif ch in "01":
            pixels.append(ch == "1")
        elif not ch.isspace():
            raise EtswarmError(
                f"{name}: PBM P1 pixel data has character {ch!r} at byte "
                f"{pos + offset + 1}; only 0 and 1 are allowed"
            )
    if len(pixels) != width * height:
        raise EtswarmError(
            f"{name}: PBM P1 has {len(pixels)} pixels, {width}x{height} needs {width * height}"
        )
    return np.array(pixels, dtype=bool).reshape(height, width)


def read_image(data: bytes, name: str) -> np.ndarray:
    """Threshold an image Pillow can open: grey < 128 (dark) is inside, transparent is white."""
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(io.BytesIO(data)) as img:
            w, h = img.size
            if w * h > MAX_PIXELS:
                raise EtswarmError(f"{name}: image {w}x{h} exceeds {MAX_PIXELS} pixels")
            if w == 0 or h == 0:
                raise EtswarmError(f"{name}: image is empty ({w}x{h})")
            img.load()
            if img.mode in ("RGBA", "LA", "PA") or "transparency" in img.info:
                rgba = img.convert("RGBA")
                white = Image.new("RGBA", rgba.size, (255, 255, 255, 255))
                grey = Image.alpha_composite(white, rgba).convert("L")
            else:
                grey = img.convert("L")
            arr = np.asarray(grey, dtype=np.uint8)
    except EtswarmError:
        raise
    except (UnidentifiedImageError, OSError, ValueError, SyntaxError) as err:
        detail = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise EtswarmError(
            f"{name}: not a text bitmap, PBM or readable image ({detail})"
        ) from None
    return arr < 128
