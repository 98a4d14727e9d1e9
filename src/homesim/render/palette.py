"""Colours: a home's theme (`Theme`), and a fixed colour per object class for the rest.

A theme, drawn from the seed, gives a home one look, as the Unity homes have one (scene 1
dark floors with red accents, scene 4 green): a wood for furniture and one for floors,
a neutral fabric for sofas and beds and a second for chairs, one accent colour (cushions,
rugs, curtains, towels; sometimes a room's walls), a wall paint; electronics are near
black, appliances and porcelain off-white. The class table's family
(`homesim.world.class_table`) says which of these colours an object takes; classes of a
family differ a little (a stable jitter per class and seed). Classes outside the themed
families keep their row's fixed colour (an apple) or a muted hue from their name.
"""

from __future__ import annotations

import colorsys
import zlib
from dataclasses import dataclass

import numpy as np

from homesim.world.class_table import class_row

RGBA = tuple[float, float, float, float]
RGB = tuple[float, float, float]

_DIM = 0.92  # class colours are drawn a little darker than white so lamps stand out

WOODS: tuple[RGB, ...] = ((0.78, 0.58, 0.38), (0.56, 0.37, 0.22), (0.86, 0.72, 0.52),
                          (0.45, 0.30, 0.20), (0.32, 0.21, 0.14), (0.70, 0.47, 0.30))
"""Oak, walnut, birch, teak, wenge, cherry."""
FABRICS: tuple[RGB, ...] = ((0.55, 0.53, 0.50), (0.36, 0.36, 0.38), (0.74, 0.70, 0.62),
                            (0.22, 0.22, 0.24), (0.85, 0.83, 0.78), (0.30, 0.35, 0.45),
                            (0.45, 0.42, 0.33))
"""Grey, charcoal, beige, near black, cream, slate blue, olive: calm colours for sofas and
beds."""
ACCENTS: tuple[RGB, ...] = ((0.62, 0.10, 0.12), (0.12, 0.45, 0.28), (0.10, 0.42, 0.45),
                            (0.78, 0.58, 0.14), (0.16, 0.28, 0.58), (0.72, 0.34, 0.20),
                            (0.45, 0.20, 0.42))
"""Red, green, teal, mustard, blue, terracotta, plum."""
PAINTS: tuple[RGB, ...] = ((0.90, 0.87, 0.80), (0.82, 0.84, 0.84), (0.88, 0.82, 0.74),
                           (0.80, 0.83, 0.76), (0.93, 0.92, 0.90), (0.70, 0.70, 0.68),
                           (0.86, 0.78, 0.74))
"""Warm white, light grey, sand, sage, white, stone grey, blush."""
THEMED = frozenset({"fabric", "accent", "wood", "dark", "white", "metal", "ceramic", "lamp",
                    "plastic", "decor", "paper"})
"""Families the theme colours."""


def _jitter(rgb: RGB, key: str, hue: float = 0.03, value: float = 0.08) -> RGB:
    """`rgb` nudged in hue and value by a stable amount per `key`."""
    h0 = zlib.crc32(key.encode("utf-8"))
    h, s, v = colorsys.rgb_to_hsv(*rgb)
    h = (h + hue * (((h0 % 1000) / 500.0) - 1.0)) % 1.0
    v = float(np.clip(v * (1.0 + value * ((((h0 >> 10) % 1000) / 500.0) - 1.0)), 0.0, 1.0))
    r, g, b = colorsys.hsv_to_rgb(h, s, v)
    return (round(r, 3), round(g, 3), round(b, 3))


@dataclass(frozen=True)
class Theme:
    """A home's palette (see the module docstring); `Theme.of(seed)` draws one."""

    seed: int
    wood: RGB
    floor_wood: RGB
    fabric: RGB
    fabric2: RGB
    accent: RGB
    paint: RGB
    accent_walls: bool  # one room's walls take a light tint of the accent

    @staticmethod
    def of(seed: int) -> Theme:
        rng = np.random.default_rng([seed, 43])
        woods = rng.permutation(len(WOODS))
        fabrics = rng.permutation(len(FABRICS))
        return Theme(seed, WOODS[woods[0]], _floor_tone(WOODS[woods[1]], rng),
                     FABRICS[fabrics[0]], FABRICS[fabrics[1]],
                     ACCENTS[int(rng.integers(len(ACCENTS)))],
                     PAINTS[int(rng.integers(len(PAINTS)))], bool(rng.random() < 0.5))

    def colour(self, family: str, class_name: str) -> RGB | None:
        """The colour the theme gives a class of `family`, or None when it gives none."""
        key = f"{class_name}:{self.seed}"
        if family == "fabric":
            second = zlib.crc32(class_name.encode()) % 3 == 0  # some fabric things differ
            return _jitter(self.fabric2 if second else self.fabric, key)
        if family == "accent":
            return _jitter(self.accent, key, hue=0.02, value=0.15)
        if family == "wood":
            return _jitter(self.wood, key, hue=0.01, value=0.06)
        fixed = {"dark": (0.08, 0.08, 0.09), "white": (0.91, 0.90, 0.88),
                 "metal": (0.60, 0.61, 0.63), "lamp": (0.95, 0.90, 0.78),
                 "paper": (0.93, 0.92, 0.88)}.get(family)
        if fixed is not None:
            return _jitter(fixed, key, hue=0.0, value=0.05)
        if family == "ceramic":
            h = zlib.crc32(key.encode()) % 3
            return (0.93, 0.92, 0.89) if h else _tint(self.accent, 0.55)
        if family in ("plastic", "decor"):
            return _muted(class_name, self.seed)
        return None

    def wall_paint(self, room: int, rooms: list[int]) -> RGB:
        """A room's wall paint: the home's, or in one room a light tint of the accent."""
        if self.accent_walls and rooms and room == rooms[self.seed % len(rooms)]:
            return _tint(self.accent, 0.45)
        return self.paint


def _floor_tone(wood: RGB, rng: np.random.Generator) -> RGB:
    """Floors are darker or lighter than furniture: a wood tone scaled by 0.55-0.9."""
    f = float(rng.uniform(0.55, 0.9))
    r, g, b = (c * f for c in wood)
    return (r, g, b)


def _tint(rgb: RGB, toward_white: float) -> RGB:
    r, g, b = (c + (1.0 - c) * toward_white for c in rgb)
    return (round(r, 3), round(g, 3), round(b, 3))


def _muted(class_name: str, seed: int) -> RGB:
    """A calm colour per class and seed (hue from the name, low saturation)."""
    h = zlib.crc32(f"{class_name}:{seed}".encode())
    r, g, b = colorsys.hsv_to_rgb((h % 360) / 360.0, 0.25 + ((h >> 9) % 30) / 100.0,
                                  0.5 + ((h >> 17) % 35) / 100.0)
    return (round(r, 3), round(g, 3), round(b, 3))


def class_color(class_name: str) -> RGBA:
    """The colour of a class outside a theme: its row's fixed colour, else a muted hue
    from the name's CRC32."""
    row = class_row(class_name)
    if row is not None and row.color is not None:
        r, g, b = row.color
        return (r, g, b, 1.0)
    h = zlib.crc32(class_name.encode("utf-8"))
    hue = (h % 360) / 360.0
    sat = 0.3 + ((h >> 9) % 30) / 100.0
    val = (0.55 + ((h >> 17) % 35) / 100.0) * _DIM
    r, g, b = colorsys.hsv_to_rgb(hue, sat, val)
    return (round(r, 3), round(g, 3), round(b, 3), 1.0)


def themed_color(theme: Theme, class_name: str, fallback: RGBA) -> RGBA:
    """The colour a class takes in a home of `theme` (the fallback outside its families)."""
    row = class_row(class_name)
    if row is None or row.family not in THEMED or row.color is not None:
        return fallback
    rgb = theme.colour(row.family, class_name)
    return fallback if rgb is None else (*rgb, 1.0)


__all__ = ["RGBA", "Theme", "class_color", "themed_color"]
