"""Agent poses: the root (pelvis position, heading, tilt), the hinge angles and the grips.

A `Pose` is plain data; `write_qpos` puts it into MuJoCo's qpos. Presets give standing,
sitting, lying and carrying; `walk_cycle` gives the legs and arms for a phase of the gait.
Each hand has a grip (0 open, 1 closed on what it holds); whoever decides what is held
sets it (`gripping`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field, replace

import numpy as np

from homesim.render.agent import BODY_HINGES, FINGER_CLOSED, AgentShape


@dataclass(frozen=True)
class Pose:
    """Where the agent is and how its joints are bent (radians, metres)."""

    x: float
    y: float
    z: float  # pelvis height above the floor
    yaw: float  # heading: 0 faces +x
    tilt: float = 0.0  # whole-body pitch: -pi/2 lies on the back
    joints: dict[str, float] = field(default_factory=dict)
    l_grip: float = 0.0  # left hand: 0 open, 1 closed, -1 flat (`FLAT`)
    r_grip: float = 0.0  # right hand

    @property
    def xy(self) -> np.ndarray:
        return np.array([self.x, self.y])

    def with_joints(self, **angles: float) -> Pose:
        return replace(self, joints={**self.joints, **angles})

    def grip(self, side: str) -> float:
        """How closed a hand is (``"l"`` or ``"r"``): 0 open, 1 a fist."""
        return self.l_grip if side == "l" else self.r_grip

    def with_grip(self, side: str, value: float) -> Pose:
        value = min(max(float(value), FLAT), 1.0)
        return replace(self, l_grip=value) if side == "l" else replace(self, r_grip=value)


def gripping(pose: Pose, sides: Iterable[str]) -> Pose:
    """`pose` with the hands of `sides` (those holding something) closed."""
    for side in sides:
        pose = pose.with_grip(side, 1.0)
    return pose


def standing(shape: AgentShape, xy, yaw: float) -> Pose:
    """Standing relaxed: knees and elbows a little bent, arms slightly away from the body."""
    # Thighs forward as much as the knees bend: shins and feet stay upright and flat.
    return Pose(float(xy[0]), float(xy[1]), shape.pelvis_height - 0.001, yaw, 0.0, {
        "l_sh_roll": 0.10, "r_sh_roll": -0.10, "l_elbow": -0.22, "r_elbow": -0.22,
        "l_sh_pitch": -0.04, "r_sh_pitch": -0.04, "l_knee": 0.06, "r_knee": 0.06,
        "l_hip_pitch": -0.06, "r_hip_pitch": -0.06})


def sitting(shape: AgentShape, xy, yaw: float, seat: float) -> Pose:
    """Sitting on a seat `seat` metres high, leaning back a little, feet forward of the
    knees, hands resting on the thighs."""
    z = seat + 0.06 * shape.height / 1.75
    return Pose(float(xy[0]), float(xy[1]), z, yaw, 0.0, {
        "l_hip_pitch": -1.42, "r_hip_pitch": -1.42, "l_knee": 1.22, "r_knee": 1.22,
        "l_hip_roll": 0.05, "r_hip_roll": -0.05,
        "l_sh_pitch": -0.45, "r_sh_pitch": -0.45, "l_elbow": -0.60, "r_elbow": -0.60,
        "l_sh_roll": 0.0, "r_sh_roll": 0.0, "l_sh_yaw": -0.15, "r_sh_yaw": 0.15,
        "spine_pitch": -0.08, "neck_pitch": 0.10})


def lying(shape: AgentShape, xy, yaw: float, bed_top: float) -> Pose:
    """Lying on the back on a surface `bed_top` metres high (head toward -heading)."""
    return Pose(float(xy[0]), float(xy[1]), bed_top + 0.12, yaw, -math.pi / 2, {
        "l_knee": 0.25, "r_knee": 0.25, "l_hip_pitch": -0.12, "r_hip_pitch": -0.12,
        "l_sh_roll": 0.22, "r_sh_roll": -0.22, "l_elbow": -0.35, "r_elbow": -0.35,
        "neck_pitch": 0.3})


FLAT = -1.0
"""The grip of a hand laid flat, its fingers straight (a palm pressed on a face); grips
between 0 and -1 straighten an open hand's bend."""
CARRY = {"sh_pitch": -0.25, "sh_roll": 0.15, "elbow": -1.35, "sh_yaw": 0.2}
"""Arm angles (per side, roll mirrored) while holding an object in front of the body."""


def carrying(pose: Pose, side: str) -> Pose:
    return spared(pose, side, CARRY)


SPARE: tuple[dict[str, float], ...] = (
    {"sh_pitch": -0.35, "sh_roll": 0.05, "elbow": -1.6, "sh_yaw": 0.45},
    {"sh_pitch": -0.6, "sh_roll": 0.0, "elbow": -2.2, "sh_yaw": 0.3},
    {"sh_pitch": 0.05, "sh_roll": 0.0, "elbow": -0.5, "sh_yaw": 0.0},
)
"""Arm angles (per side, roll and yaw mirrored as `CARRY`'s) a free arm may take out of
the way of a wall or furniture beside the agent: the forearm across the belly, the hand
before the chest, hanging close to the body."""


def spared(pose: Pose, side: str, angles: dict[str, float]) -> Pose:
    """`pose` with the `side` arm at `angles` (one of `SPARE`, or `CARRY`)."""
    sign = 1.0 if side == "l" else -1.0
    return pose.with_joints(**{
        f"{side}_sh_pitch": angles["sh_pitch"], f"{side}_sh_roll": sign * angles["sh_roll"],
        f"{side}_elbow": angles["elbow"], f"{side}_sh_yaw": -sign * angles["sh_yaw"]})


def _swing_knee(phase: float) -> float:
    """Knee flexion over a gait cycle, 0..1: a smooth bump in the swing (just after
    the foot leaves the floor) and a small one as the foot lands."""
    swing = max(0.0, -math.sin(phase - 0.6)) ** 1.5
    landing = 0.15 * max(0.0, math.sin(phase - 0.6)) ** 2
    return swing + landing


def walk_cycle(base: Pose, phase: float, run: bool = False) -> Pose:
    """Legs and arms at gait `phase` (radians; one cycle is two steps)."""
    amp = 0.75 if run else 0.36
    s = math.sin(phase)
    knee = 1.3 if run else 0.85
    arm = (0.7 if run else 0.32) * s
    elbow = -1.4 if run else -0.35
    bob = (0.03 if run else 0.014) * abs(math.cos(phase))
    return replace(base, z=base.z - bob, joints={
        **base.joints,
        "l_hip_pitch": -amp * s, "r_hip_pitch": amp * s,
        "l_knee": 0.08 + knee * _swing_knee(phase),
        "r_knee": 0.08 + knee * _swing_knee(phase + math.pi),
        "l_sh_pitch": arm, "r_sh_pitch": -arm,
        "l_elbow": elbow - 0.12 * max(s, 0.0), "r_elbow": elbow - 0.12 * max(-s, 0.0),
        "spine_yaw": (0.10 if run else 0.06) * s,  # shoulders turn against the hips
        "spine_pitch": 0.15 if run else 0.04})


def _angle_lerp(a: float, b: float, t: float) -> float:
    d = (b - a + math.pi) % (2 * math.pi) - math.pi
    return a + d * t


def blend(a: Pose, b: Pose, t: float) -> Pose:
    """Pose between `a` (t=0) and `b` (t=1), smoothed at both ends."""
    t = 0.5 - 0.5 * math.cos(math.pi * min(max(t, 0.0), 1.0))
    names = set(a.joints) | set(b.joints)
    joints = {n: (1 - t) * a.joints.get(n, 0.0) + t * b.joints.get(n, 0.0) for n in names}
    return Pose((1 - t) * a.x + t * b.x, (1 - t) * a.y + t * b.y, (1 - t) * a.z + t * b.z,
                _angle_lerp(a.yaw, b.yaw, t), (1 - t) * a.tilt + t * b.tilt, joints,
                (1 - t) * a.l_grip + t * b.l_grip, (1 - t) * a.r_grip + t * b.r_grip)


def root_quat(yaw: float, tilt: float) -> np.ndarray:
    """MuJoCo (w, x, y, z) quaternion: heading `yaw` about z, then `tilt` about local y."""
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    ct, st = math.cos(tilt / 2), math.sin(tilt / 2)
    # q = qz(yaw) * qy(tilt)
    return np.array([cy * ct, -sy * st, cy * st, sy * ct])


SKIRT_RANGE = (-1.6, 0.4)
"""The skirt hinge follows the mean of the hip pitches within this range (radians)."""


def write_qpos(qpos: np.ndarray, pose: Pose, joint_qpos: dict[str, int]) -> None:
    """Write a pose into qpos (the agent's free joint is at address 0): the body hinges
    by name, the finger hinges from each hand's grip, the skirt from the thighs."""
    qpos[0:3] = (pose.x, pose.y, pose.z)
    qpos[3:7] = root_quat(pose.yaw, pose.tilt)
    joints = pose.joints
    for name in BODY_HINGES:
        qpos[joint_qpos[name]] = joints.get(name, 0.0)
    for side in ("l", "r"):
        g = pose.grip(side)
        for finger, (open_, closed) in FINGER_CLOSED.items():
            qpos[joint_qpos[f"{side}_{finger}"]] = open_ + g * (closed - open_ if g > 0 else open_)
    hips = 0.5 * (joints.get("l_hip_pitch", 0.0) + joints.get("r_hip_pitch", 0.0))
    qpos[joint_qpos["skirt"]] = min(max(hips, SKIRT_RANGE[0]), SKIRT_RANGE[1])
