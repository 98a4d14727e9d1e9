"""Agent poses: the root (pelvis position, heading, tilt) and the hinge angles.

A `Pose` is plain data; `write_qpos` puts it into MuJoCo's qpos. Presets give standing,
sitting, lying and carrying; `walk_cycle` gives the legs and arms for a phase of the gait.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from homesim.render.agent import HINGES, AgentShape


@dataclass(frozen=True)
class Pose:
    """Where the agent is and how its joints are bent (radians, metres)."""

    x: float
    y: float
    z: float  # pelvis height above the floor
    yaw: float  # heading: 0 faces +x
    tilt: float = 0.0  # whole-body pitch: -pi/2 lies on the back
    joints: dict[str, float] = field(default_factory=dict)

    @property
    def xy(self) -> np.ndarray:
        return np.array([self.x, self.y])

    def with_joints(self, **angles: float) -> Pose:
        return replace(self, joints={**self.joints, **angles})


def standing(shape: AgentShape, xy, yaw: float) -> Pose:
    """Standing straight, arms hanging slightly away from the body."""
    return Pose(float(xy[0]), float(xy[1]), shape.pelvis_height, yaw, 0.0,
                {"l_sh_roll": 0.12, "r_sh_roll": -0.12, "l_elbow": -0.15, "r_elbow": -0.15})


def sitting(shape: AgentShape, xy, yaw: float, seat: float) -> Pose:
    """Sitting with thighs level on a seat `seat` metres high, hands on the thighs."""
    z = seat + 0.06 * shape.height / 1.75
    return Pose(float(xy[0]), float(xy[1]), z, yaw, 0.0, {
        "l_hip_pitch": -1.5, "r_hip_pitch": -1.5, "l_knee": 1.5, "r_knee": 1.5,
        "l_sh_pitch": -0.5, "r_sh_pitch": -0.5, "l_elbow": -0.9, "r_elbow": -0.9,
        "l_sh_roll": 0.1, "r_sh_roll": -0.1, "spine_pitch": -0.08})


def lying(shape: AgentShape, xy, yaw: float, bed_top: float) -> Pose:
    """Lying on the back on a surface `bed_top` metres high (head toward -heading)."""
    return Pose(float(xy[0]), float(xy[1]), bed_top + 0.12, yaw, -math.pi / 2, {
        "l_knee": 0.2, "r_knee": 0.2, "l_sh_roll": 0.2, "r_sh_roll": -0.2,
        "neck_pitch": 0.3})


CARRY = {"sh_pitch": -0.35, "sh_roll": 0.15, "elbow": -1.3, "sh_yaw": 0.2}
"""Arm angles (per side, roll mirrored) while holding an object in front of the body."""


def carrying(pose: Pose, side: str) -> Pose:
    sign = 1.0 if side == "l" else -1.0
    return pose.with_joints(**{
        f"{side}_sh_pitch": CARRY["sh_pitch"], f"{side}_sh_roll": sign * CARRY["sh_roll"],
        f"{side}_elbow": CARRY["elbow"], f"{side}_sh_yaw": -sign * CARRY["sh_yaw"]})


def walk_cycle(base: Pose, phase: float, run: bool = False) -> Pose:
    """Legs and arms at gait `phase` (radians; one cycle is two steps)."""
    amp = 0.75 if run else 0.45
    s = math.sin(phase)
    knee_l = (1.3 if run else 0.7) * max(0.0, -math.sin(phase - 0.6))
    knee_r = (1.3 if run else 0.7) * max(0.0, math.sin(phase - 0.6))
    arm = (0.7 if run else 0.35) * s
    elbow = -1.4 if run else -0.3
    bob = (0.03 if run else 0.015) * abs(math.cos(phase))
    return replace(base, z=base.z - bob, joints={
        **base.joints,
        "l_hip_pitch": -amp * s, "r_hip_pitch": amp * s, "l_knee": knee_l, "r_knee": knee_r,
        "l_sh_pitch": arm, "r_sh_pitch": -arm, "l_elbow": elbow, "r_elbow": elbow,
        "spine_pitch": 0.15 if run else 0.03})


def _angle_lerp(a: float, b: float, t: float) -> float:
    d = (b - a + math.pi) % (2 * math.pi) - math.pi
    return a + d * t


def blend(a: Pose, b: Pose, t: float) -> Pose:
    """Pose between `a` (t=0) and `b` (t=1), smoothed at both ends."""
    t = 0.5 - 0.5 * math.cos(math.pi * min(max(t, 0.0), 1.0))
    names = set(a.joints) | set(b.joints)
    joints = {n: (1 - t) * a.joints.get(n, 0.0) + t * b.joints.get(n, 0.0) for n in names}
    return Pose((1 - t) * a.x + t * b.x, (1 - t) * a.y + t * b.y, (1 - t) * a.z + t * b.z,
                _angle_lerp(a.yaw, b.yaw, t), (1 - t) * a.tilt + t * b.tilt, joints)


def root_quat(yaw: float, tilt: float) -> np.ndarray:
    """MuJoCo (w, x, y, z) quaternion: heading `yaw` about z, then `tilt` about local y."""
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    ct, st = math.cos(tilt / 2), math.sin(tilt / 2)
    # q = qz(yaw) * qy(tilt)
    return np.array([cy * ct, -sy * st, cy * st, sy * ct])


def write_qpos(qpos: np.ndarray, pose: Pose, joint_qpos: dict[str, int]) -> None:
    """Write a pose into qpos (the agent's free joint is at address 0)."""
    qpos[0:3] = (pose.x, pose.y, pose.z)
    qpos[3:7] = root_quat(pose.yaw, pose.tilt)
    for name in HINGES:
        qpos[joint_qpos[name]] = pose.joints.get(name, 0.0)
