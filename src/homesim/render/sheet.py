"""Contact sheets: key frames in a grid, each labelled with its step."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from homesim.files import atomic_write


def contact_sheet(frames: list[tuple[str, np.ndarray]], path: str | Path,
                  columns: int = 3, title: str | None = None) -> Path:
    """Write labelled frames (label, RGB array) as one PNG; returns its path."""
    if not frames:
        raise ValueError("no frames for the contact sheet")
    h, w = frames[0][1].shape[:2]
    cols = min(columns, len(frames))
    rows = math.ceil(len(frames) / cols)
    band = 18
    top = 22 if title else 0
    sheet = Image.new("RGB", (cols * w, top + rows * (h + band)), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default()
    if title:
        draw.text((6, 4), title, fill=(0, 0, 0), font=font)
    for k, (label, img) in enumerate(frames):
        r, c = divmod(k, cols)
        x, y = c * w, top + r * (h + band)
        sheet.paste(Image.fromarray(img), (x, y + band))
        draw.text((x + 4, y + 3), label[: max(8, w // 6)], fill=(0, 0, 0), font=font)
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    with atomic_write(out, "wb") as f:
        sheet.save(f, format="PNG")
    return out
