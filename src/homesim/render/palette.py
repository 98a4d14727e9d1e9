"""A fixed colour per object class, so the same class looks the same in every video: the
class table's ``color`` (`homesim.world.class_table`), else a stable hue from the name."""

from __future__ import annotations

import colorsys
import zlib

from homesim.world.class_table import class_row

RGBA = tuple[float, float, float, float]

_DIM = 0.92  # class colours are drawn a little darker than white so lamps stand out


def class_color(class_name: str) -> RGBA:
    """The colour of a class: its row's fixed colour, else a stable hue from the name's
    CRC32."""
    row = class_row(class_name)
    if row is not None and row.color is not None:
        r, g, b = row.color
        return (r, g, b, 1.0)
    h = zlib.crc32(class_name.encode("utf-8"))
    hue = (h % 360) / 360.0
    sat = 0.45 + ((h >> 9) % 40) / 100.0
    val = (0.55 + ((h >> 17) % 40) / 100.0) * _DIM
    r, g, b = colorsys.hsv_to_rgb(hue, sat, val)
    return (round(r, 3), round(g, 3), round(b, 3), 1.0)
