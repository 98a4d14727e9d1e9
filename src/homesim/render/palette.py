"""A fixed colour per object class, so the same class looks the same in every video."""

from __future__ import annotations

import colorsys
import zlib

RGBA = tuple[float, float, float, float]

_FIXED: dict[str, tuple[float, float, float]] = {
    "wall": (0.86, 0.83, 0.76),
    "floor": (0.55, 0.42, 0.30),
    "ceiling": (0.95, 0.95, 0.93),
    "door": (0.55, 0.35, 0.20),
    "doorjamb": (0.45, 0.30, 0.18),
    "window": (0.70, 0.85, 0.95),
    "sofa": (0.25, 0.35, 0.60),
    "tv": (0.08, 0.08, 0.08),
    "computer": (0.15, 0.15, 0.15),
    "fridge": (0.90, 0.90, 0.92),
    "cabinet": (0.62, 0.45, 0.28),
    "kitchencabinet": (0.62, 0.45, 0.28),
    "closet": (0.58, 0.42, 0.27),
    "bed": (0.80, 0.75, 0.85),
    "chair": (0.50, 0.30, 0.20),
    "desk": (0.55, 0.38, 0.22),
    "kitchentable": (0.60, 0.42, 0.25),
    "coffeetable": (0.55, 0.38, 0.22),
    "rug": (0.65, 0.25, 0.25),
    "ceilinglamp": (0.95, 0.92, 0.70),
    "tablelamp": (0.95, 0.85, 0.55),
    "lightswitch": (0.97, 0.97, 0.97),
    "character": (0.90, 0.60, 0.45),
    "pillow": (0.88, 0.84, 0.74),
    "towel": (0.85, 0.88, 0.92),
    "plate": (0.95, 0.95, 0.93),
    "dishbowl": (0.93, 0.90, 0.84),
    "mug": (0.80, 0.22, 0.18),
    "toilet": (0.96, 0.96, 0.95),
    "bathtub": (0.96, 0.96, 0.95),
    "sink": (0.80, 0.81, 0.83),
    "curtains": (0.72, 0.62, 0.48),
    "apple": (0.75, 0.12, 0.10),
    "bananas": (0.95, 0.85, 0.25),
    "lime": (0.45, 0.75, 0.20),
    "orchid": (0.85, 0.55, 0.80),
}
_DIM = 0.92  # class colours are drawn a little darker than white so lamps stand out


def class_color(class_name: str) -> RGBA:
    """The colour of a class: a fixed entry, else a stable hue from the name's CRC32."""
    if class_name in _FIXED:
        r, g, b = _FIXED[class_name]
        return (r, g, b, 1.0)
    h = zlib.crc32(class_name.encode("utf-8"))
    hue = (h % 360) / 360.0
    sat = 0.45 + ((h >> 9) % 40) / 100.0
    val = (0.55 + ((h >> 17) % 40) / 100.0) * _DIM
    r, g, b = colorsys.hsv_to_rgb(hue, sat, val)
    return (round(r, 3), round(g, 3), round(b, 3), 1.0)
