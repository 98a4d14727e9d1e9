"""The agent: an articulated humanoid written as MJCF, in four looks (two men, two women).

Local frame of the agent: it faces +x, its left is +y, up is +z. Hinge signs follow
the right-hand rule, so a negative hip or shoulder pitch swings the limb forward and a
positive knee / negative elbow angle bends it naturally. Finger hinges close the hand
toward the palm for positive angles on both sides.

Every geom is named ``agent:<part>``: the scene segments all of them as the character.
Besides the body hinges (`BODY_HINGES`), each hand has three finger hinges driven by the
pose's grip value, and a skirt hinge follows the thighs (`poses.write_qpos` sets both).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from homesim.errors import HomesimError

RGB = tuple[float, float, float]


@dataclass(frozen=True)
class Outfit:
    """Clothes: a top (with its sleeves), trousers or a skirt, shoes, and an accent
    (a tie, a belt or a collar; None for none)."""

    top: RGB
    sleeves: str  # "long" (to the wrist), "short" (to the elbow) or "none"
    bottom: RGB
    skirt: bool
    shoes: RGB
    accent: RGB | None = None
    accent_kind: str = ""  # "tie" or "belt"


@dataclass(frozen=True)
class Hair:
    """Hair style (``bald``, ``short``, ``long`` or ``bun``), its colour, and a beard."""

    style: str
    colour: RGB
    beard: bool = False


@dataclass(frozen=True)
class AgentShape:
    """Body measurements (metres), build and look of one agent."""

    name: str
    sex: str  # "male" or "female"
    height: float
    shoulder: float  # half the shoulder width (shoulder joint to the middle)
    hip: float  # half the distance between the hip joints
    waist: float  # half the waist width
    build: float  # limb and torso thickness, 1 = average man
    skin: RGB
    outfit: Outfit
    hair: Hair

    @property
    def scale(self) -> float:
        """Size of the head, hands and feet relative to a 1.75 m person."""
        return self.height / 1.75

    @property
    def thigh(self) -> float:
        return 0.245 * self.height

    @property
    def shin(self) -> float:
        return 0.25 * self.height

    @property
    def torso(self) -> float:
        return 0.29 * self.height

    @property
    def upper_arm(self) -> float:
        return 0.18 * self.height

    @property
    def forearm(self) -> float:
        return 0.15 * self.height

    @property
    def ankle(self) -> float:
        return 0.04 * self.height

    @property
    def pelvis_height(self) -> float:
        """Height of the pelvis above the floor when standing straight."""
        return self.thigh + self.shin + self.ankle

    @property
    def top_of_head(self) -> float:
        """Height of the top of the head when standing straight."""
        return self.pelvis_height + _PELVIS_TO_TORSO + self.torso + _skull(self)[2] + \
            _skull(self)[5]


AGENTS: dict[str, AgentShape] = {
    s.name: s for s in (
        # Blue-grey suit, white collar and dark tie; bald; dark skin.
        AgentShape("male1", "male", 1.80, 0.195, 0.095, 0.150, 1.0, (0.42, 0.27, 0.19),
                   Outfit((0.30, 0.42, 0.56), "long", (0.28, 0.39, 0.52), False,
                          (0.07, 0.07, 0.08), (0.16, 0.19, 0.26), "tie"),
                   Hair("bald", (0.10, 0.07, 0.06))),
        # Sleeveless mint top, black knee-length skirt, sandals; long dark hair.
        AgentShape("female1", "female", 1.66, 0.170, 0.090, 0.115, 0.86, (0.86, 0.66, 0.52),
                   Outfit((0.52, 0.80, 0.64), "none", (0.07, 0.07, 0.08), True,
                          (0.78, 0.64, 0.50)),
                   Hair("long", (0.12, 0.07, 0.05))),
        # Raspberry henley with elbow sleeves, black trousers; short dark hair, beard.
        AgentShape("male2", "male", 1.84, 0.205, 0.100, 0.145, 1.06, (0.93, 0.75, 0.63),
                   Outfit((0.72, 0.28, 0.44), "short", (0.09, 0.09, 0.11), False,
                          (0.20, 0.18, 0.17)),
                   Hair("short", (0.22, 0.20, 0.19), beard=True)),
        # Red sleeveless dress with a black belt, red shoes; dark hair in a bun.
        AgentShape("female2", "female", 1.71, 0.172, 0.092, 0.112, 0.88, (0.90, 0.72, 0.60),
                   Outfit((0.80, 0.13, 0.16), "none", (0.80, 0.13, 0.16), True,
                          (0.70, 0.10, 0.10), (0.06, 0.05, 0.05), "belt"),
                   Hair("bun", (0.09, 0.06, 0.05))),
    )
}
"""The paper's four agents: two men and two women of distinct build, clothes and hair."""

JOINTS: tuple[str, ...] = (
    "pelvis", "neck", "head", "l_shoulder", "l_elbow", "l_wrist", "r_shoulder", "r_elbow",
    "r_wrist", "l_hip", "l_knee", "l_ankle", "r_hip", "r_knee", "r_ankle", "spine",
)
"""Names of the keypoints written as 2D/3D ground truth (MJCF sites ``j:<name>``)."""

BODY_HINGES: tuple[str, ...] = (
    "spine_pitch", "spine_yaw", "neck_yaw", "neck_pitch",
    "l_sh_pitch", "l_sh_roll", "l_sh_yaw", "l_elbow",
    "r_sh_pitch", "r_sh_roll", "r_sh_yaw", "r_elbow",
    "l_hip_pitch", "l_hip_roll", "l_knee", "r_hip_pitch", "r_hip_roll", "r_knee",
    "l_wrist_twist", "l_wrist_flex", "l_wrist_dev", "r_wrist_twist", "r_wrist_flex",
    "r_wrist_dev",
)
"""The hinges a pose sets by name (`Pose.joints`), radians."""

WRIST_RANGE: dict[str, tuple[float, float]] = {
    "wrist_twist": (-1.2, 1.2), "wrist_flex": (-0.9, 1.0), "wrist_dev": (-0.5, 0.5),
}
"""Wrist hinge ranges (radians): twist about the forearm (the forearm is round, so a twist
there looks like the forearm's own), flexion toward the palm, deviation in the palm's
plane."""

FINGER_CLOSED: dict[str, tuple[float, float]] = {
    "fingers": (0.25, 1.45), "fingertips": (0.30, 1.35), "thumb": (0.20, 0.95),
}
"""Finger hinge angles (radians) of an open (grip 0) and a closed (grip 1) hand."""

HAND_HINGES: tuple[str, ...] = tuple(f"{s}_{f}" for s in ("l", "r") for f in FINGER_CLOSED)

HINGES: tuple[str, ...] = BODY_HINGES + HAND_HINGES + ("skirt",)
"""Every hinge of the agent (MJCF joint ``a:<name>``), radians."""

_PELVIS_TO_TORSO = 0.05
"""The torso (spine) joint sits this far above the hip joints."""


def agent_shape(name: str) -> AgentShape:
    """An agent by name (``male1``, ``female1``, ``male2``, ``female2``)."""
    try:
        return AGENTS[name]
    except KeyError:
        raise HomesimError(f"unknown agent {name!r}; choose one of {', '.join(AGENTS)}") \
            from None


# ------------------------------------------------------------------------ MJCF pieces
def _rgb(c: RGB) -> str:
    return f"{c[0]:.3f} {c[1]:.3f} {c[2]:.3f} 1"


def _f(*v: float) -> str:
    return " ".join(f"{x:.4f}" for x in v)


def _geom(name: str, kind: str, size: tuple[float, ...], rgb: RGB, pos=None,
          fromto=None) -> str:
    where = f'fromto="{_f(*fromto)}"' if fromto is not None else f'pos="{_f(*(pos or (0, 0, 0)))}"'
    return (f'<geom name="agent:{name}" type="{kind}" {where} size="{_f(*size)}" '
            f'rgba="{_rgb(rgb)}"/>')


def _hinge(name: str, axis: str, lo: float, hi: float) -> str:
    return f'<joint name="a:{name}" type="hinge" axis="{axis}" range="{lo} {hi}"/>'


def _site(name: str, pos=(0.0, 0.0, 0.0)) -> str:
    """A site in group 4, which MuJoCo does not draw by default (not in any image)."""
    return f'<site name="{name}" pos="{_f(*pos)}" size="0.01" group="4"/>'


def _shade(c: RGB, f: float) -> RGB:
    return (min(c[0] * f, 1.0), min(c[1] * f, 1.0), min(c[2] * f, 1.0))


def _skull(s: AgentShape) -> tuple[float, float, float, float, float, float]:
    """Centre (x, z above the neck joint) and half sizes of the head ellipsoid:
    (x, y, z, half x, half y, half z); y is 0."""
    k = s.scale * (0.96 if s.sex == "female" else 1.0)
    half = (0.098 * k, 0.077 * k, 0.114 * k)
    top = s.height - s.pelvis_height - _PELVIS_TO_TORSO - s.torso
    return (0.008 * k, 0.0, top - half[2], *half)


def _front(half: tuple[float, float, float], dy: float, dz: float) -> float:
    """How far forward (x) an ellipsoid's surface is at offsets dy, dz from its centre."""
    r = 1.0 - (dy / half[1]) ** 2 - (dz / half[2]) ** 2
    return half[0] * math.sqrt(max(r, 0.0))


# ------------------------------------------------------------------------ head
def _face(s: AgentShape) -> list[str]:
    """Eyes, brows, nose, mouth and ears on the head ellipsoid."""
    cx, _, cz, *h = _skull(s)
    half = (h[0], h[1], h[2])
    k = s.scale
    lip = (s.skin[0] * 0.78, s.skin[1] * 0.50, s.skin[2] * 0.48)
    out = []
    for side, sign in (("l", 1.0), ("r", -1.0)):
        y, ez = sign * 0.032 * k, 0.018 * k
        x = cx + _front(half, y, ez)
        out.append(_geom(f"{side}_eye_white", "ellipsoid", (0.006 * k, 0.014 * k, 0.008 * k),
                         (0.93, 0.92, 0.90), pos=(x - 0.004 * k, y, cz + ez)))
        out.append(_geom(f"{side}_eye", "sphere", (0.0075 * k,), (0.12, 0.09, 0.07),
                         pos=(x - 0.002 * k, y, cz + ez)))
        bz = ez + 0.022 * k
        bx = cx + _front(half, y, bz) - 0.002 * k
        out.append(_geom(f"{side}_brow", "capsule", (0.004 * k,),
                         _shade(s.hair.colour, 0.9),
                         fromto=(bx, y - 0.016 * k, cz + bz,
                                 bx, y + 0.016 * k, cz + bz + 0.002 * k)))
        out.append(_geom(f"{side}_ear", "ellipsoid", (0.016 * k, 0.010 * k, 0.030 * k),
                         _shade(s.skin, 0.93), pos=(cx - 0.005 * k, sign * half[1] * 0.97, cz)))
    nz = -0.018 * k
    out.append(_geom("nose", "ellipsoid", (0.020 * k, 0.013 * k, 0.026 * k),
                     _shade(s.skin, 0.95), pos=(cx + _front(half, 0.0, nz) - 0.002 * k, 0.0,
                                                cz + nz)))
    mz = -0.058 * k
    mx = cx + _front(half, 0.0, mz) - 0.003 * k
    out.append(_geom("mouth", "capsule", (0.0055 * k,), lip,
                     fromto=(mx, -0.021 * k, mz + cz, mx, 0.021 * k, mz + cz)))
    return out


def _hair(s: AgentShape) -> list[str]:
    """Hair cap and style (long: down to the shoulders; bun: at the back), and a beard."""
    cx, _, cz, hx, hy, hz = _skull(s)
    c, k = s.hair.colour, s.scale
    out = []
    if s.hair.style != "bald":
        out.append(_geom("hair", "ellipsoid", (hx * 1.02, hy * 1.07, hz * 0.90), c,
                         pos=(cx - 0.016 * k, 0.0, cz + 0.028 * k)))
    if s.hair.style == "long":
        out.append(_geom("hair_back", "ellipsoid", (0.055 * k, hy * 1.10, 0.17 * k), c,
                         pos=(cx - 0.062 * k, 0.0, cz - 0.085 * k)))
        for side, y in (("l", 1.0), ("r", -1.0)):
            out.append(_geom(f"hair_{side}", "ellipsoid", (0.045 * k, 0.022 * k, 0.12 * k), c,
                             pos=(cx - 0.02 * k, y * hy * 0.92, cz - 0.045 * k)))
    elif s.hair.style == "bun":
        out.append(_geom("hair_bun", "sphere", (0.042 * k,), c,
                         pos=(cx - hx - 0.010 * k, 0.0, cz + 0.035 * k)))
    if s.hair.beard:
        out.append(_geom("beard", "ellipsoid", (0.075 * k, hy * 0.88, 0.058 * k),
                         _shade(c, 1.3), pos=(cx + 0.022 * k, 0.0, cz - 0.062 * k)))
    return out


def _head(s: AgentShape) -> str:
    cx, _, cz, hx, hy, hz = _skull(s)
    k = s.scale
    neck_r = (0.044 if s.sex == "male" else 0.036) * k * s.build ** 0.5
    parts = [
        _hinge("neck_yaw", "0 0 1", -1.3, 1.3), _hinge("neck_pitch", "0 1 0", -0.8, 0.9),
        _site("j:neck"), _site("j:head", (cx, 0.0, cz)),
        _geom("neck", "capsule", (neck_r,), s.skin, fromto=(0, 0, -0.03, 0.006, 0, cz - 0.06 * k)),
        _geom("head", "ellipsoid", (hx, hy, hz), s.skin, pos=(cx, 0.0, cz)),
        _geom("jaw", "ellipsoid", (hx * 0.78, hy * 0.80, hz * 0.55), s.skin,
              pos=(cx + 0.012 * k, 0.0, cz - 0.045 * k)),
        *_face(s), *_hair(s),
    ]
    return f'<body name="a:head" pos="0 0 {s.torso:.4f}">' + "".join(parts) + "</body>"


# ------------------------------------------------------------------------ torso
def _torso_geoms(s: AgentShape) -> list[str]:
    """Abdomen, chest, shoulder line, and the outfit's accent (tie or belt)."""
    t, b, k, o = s.torso, s.build, s.scale, s.outfit
    female = s.sex == "female"
    chest = ((0.100 if female else 0.096) * k * b, s.shoulder - 0.03 * k, 0.36 * t)
    belly = ((0.078 if female else 0.086) * k * b, s.waist, 0.42 * t)
    arm_r = _arm_radius(s)
    out = [
        _geom("abdomen", "ellipsoid", belly, o.top, pos=(0.0, 0.0, 0.32 * t)),
        _geom("torso", "ellipsoid", chest, o.top, pos=(0.0, 0.0, 0.62 * t)),
        _geom("chest", "capsule", (arm_r * 1.05,), o.top,
              fromto=(-0.01, s.shoulder - 0.02 * k, t - 0.05, -0.01, -s.shoulder + 0.02 * k,
                      t - 0.05)),
    ]
    if o.accent is not None and o.accent_kind == "tie":
        out += _tie(chest, belly, s)
    elif o.accent is not None and o.accent_kind == "belt":
        out.append(_geom("belt", "ellipsoid", (belly[0] * 1.02, s.waist * 1.02, 0.028 * k),
                         o.accent, pos=(0.0, 0.0, 0.16 * t)))
    return out


def _tie(chest: tuple[float, float, float], belly: tuple[float, float, float],
         s: AgentShape) -> list[str]:
    """A white collar and a tie lying on the front of the chest and belly."""
    t, k = s.torso, s.scale
    heights = (0.90 * t, 0.72 * t, 0.55 * t, 0.40 * t)
    xs = [max(_front(chest, 0.0, z - 0.62 * t), _front(belly, 0.0, z - 0.32 * t))
          for z in heights]
    accent = s.outfit.accent or (0.0, 0.0, 0.0)
    out = [_geom("collar", "ellipsoid", (0.022 * k, 0.042 * k, 0.045 * k), (0.93, 0.93, 0.95),
                 pos=(xs[0] - 0.008 * k, 0.0, heights[0]))]
    for i in range(len(heights) - 1):
        out.append(_geom(f"tie{i}", "capsule", (0.012 * k,), accent,
                         fromto=(xs[i] + 0.002 * k, 0.0, heights[i],
                                 xs[i + 1] + 0.002 * k, 0.0, heights[i + 1])))
    return out


def _pelvis_geoms(s: AgentShape) -> list[str]:
    k, o = s.scale, s.outfit
    if o.skirt:  # a dome on the skirt's top face
        return [_geom("pelvis", "ellipsoid", (_SKIRT_DEPTH * k, _skirt_width(s), 0.13 * k),
                      o.bottom, pos=(0.0, 0.0, _SKIRT_TOP))]
    width = s.hip + 0.060 * k * s.build
    return [_geom("pelvis", "ellipsoid", (0.098 * k * s.build, width, 0.11 * k), o.bottom,
                  pos=(-0.005, 0.0, 0.03))]


_SKIRT_DEPTH = 0.108
"""Half the depth of a skirt (front to back) of a 1.75 m agent, metres."""
_SKIRT_TOP = -0.02
"""Height of the skirt's top face relative to the hip joints, metres."""


def _skirt_width(s: AgentShape) -> float:
    return s.hip + 0.092 * s.scale


def _stadium(name: str, half_x: float, half_y: float, z: tuple[float, float],
             rgb: RGB) -> list[str]:
    """A prism with a stadium cross-section (a box between two vertical cylinders):
    `half_x` deep, `half_y` wide, from z[0] down to z[1]."""
    mid, half_z = 0.5 * (z[0] + z[1]), 0.5 * (z[0] - z[1])
    side = half_y - half_x
    return [_geom(name, "box", (half_x, side, half_z), rgb, pos=(0.0, 0.0, mid)),
            _geom(f"{name}_l", "cylinder", (half_x, half_z), rgb, pos=(0.0, side, mid)),
            _geom(f"{name}_r", "cylinder", (half_x, half_z), rgb, pos=(0.0, -side, mid))]


def _skirt(s: AgentShape) -> str:
    """The skirt hangs from the pelvis and swings with the thighs (hinge ``a:skirt``);
    agents in trousers have the hinge with nothing on it."""
    inert = '<inertial pos="0 0 0" mass="0.1" diaginertia="0.001 0.001 0.001"/>'
    geoms: list[str] = []
    if s.outfit.skirt:
        k, th, c = s.scale, s.thigh, s.outfit.bottom
        flared = s.outfit.accent_kind == "belt"
        width, depth = _skirt_width(s), _SKIRT_DEPTH * k
        geoms = _stadium("skirt", depth, width, (_SKIRT_TOP, -0.62 * th), c)
        hem = 0.012 * k if flared else 0.0
        geoms += _stadium("skirt_hem", depth + hem, width + hem,
                          (-0.62 * th, -(0.80 if flared else 0.84) * th), _shade(c, 0.92))
    return (f'<body name="a:skirt" pos="0 0 0">{inert}'
            f'{_hinge("skirt", "0 1 0", -2.0, 1.0)}{"".join(geoms)}</body>')


# ------------------------------------------------------------------------ limbs
def _arm_radius(s: AgentShape) -> float:
    return (0.046 if s.sex == "male" else 0.041) * s.scale * s.build ** 0.5


PALM_HEEL = 0.025
"""Metres (for a 1.75 m person) from the wrist to the palm's contact point (``{side}_palm``),
on the palm's surface near its heel: a palm grasp puts this point against the object."""


def _hand(side: str, s: AgentShape) -> str:
    """The hand's body at the wrist: three wrist hinges (twist, flexion toward the palm,
    deviation in the palm's plane), a palm, a finger block in two segments and a thumb.
    Sites: ``{side}_hand`` inside the closed fist (held objects ride in its frame) and
    ``{side}_palm`` on the palm's surface near its heel (where a grasp touches)."""
    k, fa = s.scale, s.forearm
    inward = -1.0 if side == "l" else 1.0  # toward the body: the palm side
    axis = "-1 0 0" if side == "l" else "1 0 0"
    skin = s.skin
    fingers = _geom(f"{side}_fingers", "box", (0.038 * k, 0.012 * k, 0.024 * k), skin,
                    pos=(0.0, 0.0, -0.022 * k))
    tips = _geom(f"{side}_fingertips", "box", (0.035 * k, 0.010 * k, 0.021 * k), skin,
                 pos=(0.0, 0.0, -0.019 * k))
    thumb = _geom(f"{side}_thumb", "capsule", (0.011 * k,), skin,
                  fromto=(0.0, 0.0, 0.0, 0.010 * k, 0.0, -0.050 * k))
    lo, hi = 0.0, 1.7
    flex, dev = WRIST_RANGE["wrist_flex"], WRIST_RANGE["wrist_dev"]
    twist = WRIST_RANGE["wrist_twist"]
    return (
        f'<body name="a:{side}_hand" pos="0 0 {-fa:.4f}">'
        + _hinge(f"{side}_wrist_twist", "0 0 1", *twist)
        + _hinge(f"{side}_wrist_flex", axis, *flex)
        + _hinge(f"{side}_wrist_dev", "0 1 0", *dev)
        + _geom(f"{side}_hand", "ellipsoid", (0.044 * k, 0.019 * k, 0.050 * k), skin,
                pos=(0.0, 0.0, -0.045 * k))
        + _site(f"{side}_hand", (0.0, inward * 0.030 * k, -0.085 * k))
        + _site(f"{side}_palm", (0.0, inward * 0.0175 * k, -PALM_HEEL * k))
        + f'<body name="a:{side}_fingers" pos="0 0 {-0.088 * k:.4f}">'
        + _hinge(f"{side}_fingers", axis, lo, hi) + fingers
        + f'<body name="a:{side}_fingertips" pos="0 0 {-0.045 * k:.4f}">'
        + _hinge(f"{side}_fingertips", axis, lo, hi) + tips + "</body></body>"
        + f'<body name="a:{side}_thumb" pos="{0.034 * k:.4f} {inward * 0.010 * k:.4f} '
        f'{-0.030 * k:.4f}">'
        + _hinge(f"{side}_thumb", axis, lo, hi) + thumb + "</body></body>")


def _arm(side: str, s: AgentShape) -> str:
    y = s.shoulder if side == "l" else -s.shoulder
    ua, fa = s.upper_arm, s.forearm
    r = _arm_radius(s)
    sleeves = s.outfit.sleeves
    upper_c = s.skin if sleeves == "none" else s.outfit.top
    fore_c = s.outfit.top if sleeves == "long" else s.skin
    roll = ("-0.3 2.8" if side == "l" else "-2.8 0.3")
    sleeve_end = ""
    if sleeves == "short":  # a cuff just above the elbow
        sleeve_end = _geom(f"{side}_cuff", "capsule", (r * 1.12,), _shade(s.outfit.top, 0.9),
                           fromto=(0, 0, -0.72 * ua, 0, 0, -0.86 * ua))
    return f"""
      <body name="a:{side}_shoulder" pos="0 {y:.4f} {s.torso - 0.04:.4f}">
        {_hinge(f"{side}_sh_pitch", "0 1 0", -3.1, 1.2)}
        <joint name="a:{side}_sh_roll" type="hinge" axis="1 0 0" range="{roll}"/>
        {_hinge(f"{side}_sh_yaw", "0 0 1", -1.6, 1.6)}
        {_site(f"j:{side}_shoulder")}
        {_geom(f"{side}_upper_arm", "capsule", (r,), upper_c, fromto=(0, 0, 0, 0, 0, -ua))}
        {sleeve_end}
        <body name="a:{side}_forearm" pos="0 0 {-ua:.4f}">
          {_hinge(f"{side}_elbow", "0 1 0", -2.6, 0.0)}
          {_site(f"j:{side}_elbow")}
          {_geom(f"{side}_forearm", "capsule", (r * 0.82,), fore_c, fromto=(0, 0, 0, 0, 0, -fa))}
          {_site(f"j:{side}_wrist", (0.0, 0.0, -fa))}
          {_hand(side, s)}
        </body>
      </body>"""


def _shoe(side: str, s: AgentShape) -> str:
    """A shoe (sandals for a skirt without accent: a sole and a strap on a bare foot)."""
    k, sh = s.scale, s.shin
    floor = -sh - s.ankle
    o = s.outfit
    sandal = o.skirt and o.accent is None
    upper = s.skin if sandal else o.shoes
    out = [
        _geom(f"{side}_foot", "capsule", (0.034 * k,), upper,
              fromto=(-0.035 * k, 0.0, floor + 0.040 * k, 0.135 * k, 0.0, floor + 0.030 * k)),
        _geom(f"{side}_sole", "box", (0.105 * k, 0.040 * k, 0.010 * k),
              _shade(o.shoes, 0.8), pos=(0.048 * k, 0.0, floor + 0.010 * k)),
    ]
    if sandal:
        out.append(_geom(f"{side}_strap", "capsule", (0.036 * k,), o.shoes,
                         fromto=(0.055 * k, 0.0, floor + 0.033 * k, 0.075 * k, 0.0,
                                 floor + 0.032 * k)))
    elif o.skirt:  # dark ankle socks
        out.append(_geom(f"{side}_sock", "capsule", (0.042 * k,), o.accent or o.shoes,
                         fromto=(0.0, 0.0, -sh + 0.02 * k, 0.0, 0.0, -sh - 0.02 * k)))
    return "".join(out)


def _leg(side: str, s: AgentShape) -> str:
    y = s.hip if side == "l" else -s.hip
    th, sh, k = s.thigh, s.shin, s.scale
    r = (0.074 if s.sex == "male" else 0.072) * k * s.build ** 0.5
    o = s.outfit
    leg_c = s.skin if o.skirt else o.bottom
    return f"""
    <body name="a:{side}_thigh" pos="0 {y:.4f} 0">
      {_hinge(f"{side}_hip_pitch", "0 1 0", -2.2, 0.8)}
      {_hinge(f"{side}_hip_roll", "1 0 0", -0.6, 0.6)}
      {_site(f"j:{side}_hip")}
      {_geom(f"{side}_thigh", "capsule", (r,), leg_c, fromto=(0, 0, 0, 0, 0, -th))}
      <body name="a:{side}_shin" pos="0 0 {-th:.4f}">
        {_hinge(f"{side}_knee", "0 1 0", 0.0, 2.6)}
        {_site(f"j:{side}_knee")}
        {_geom(f"{side}_shin", "capsule", (r * 0.74,), leg_c, fromto=(0, 0, 0, 0, 0, -sh))}
        {_geom(f"{side}_calf", "ellipsoid", (r * 0.78, r * 0.76, 0.30 * sh), leg_c,
               pos=(-0.012 * k, 0.0, -0.30 * sh))}
        {_site(f"j:{side}_ankle", (0.0, 0.0, -sh))}
        {_shoe(side, s)}
      </body>
    </body>"""


def agent_mjcf(shape: AgentShape, pos: tuple[float, float] = (0.0, 0.0)) -> str:
    """The agent's MJCF ``<body>``: a free root at the pelvis, the hinges of `HINGES`,
    keypoint sites ``j:<name>`` (`JOINTS`) and a hand site per side."""
    s = shape
    torso = "".join([
        _hinge("spine_pitch", "0 1 0", -0.5, 1.4), _hinge("spine_yaw", "0 0 1", -0.8, 0.8),
        _site("j:spine", (0.0, 0.0, s.torso * 0.5)), *_torso_geoms(s), _head(s),
        _arm("l", s), _arm("r", s)])
    return f"""
  <body name="agent" pos="{pos[0]:.4f} {pos[1]:.4f} {s.pelvis_height:.4f}">
    <freejoint name="a:root"/>
    {_site("j:pelvis")}
    {"".join(_pelvis_geoms(s))}
    <body name="a:torso" pos="0 0 {_PELVIS_TO_TORSO}">{torso}
    </body>{_skirt(s)}{_leg("l", s)}{_leg("r", s)}
  </body>"""
