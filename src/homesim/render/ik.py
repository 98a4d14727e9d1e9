"""Reaching: a small damped-least-squares inverse-kinematics solver for one arm.

It moves the shoulder (3 hinges), the elbow and the spine (pitch and yaw) so that the hand
site reaches a world point, using MuJoCo's site Jacobian on a scratch `MjData`. For low
points the whole body can crouch first (`crouched`: hips and knees bent, pelvis lowered).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from homesim.render.agent import AgentShape
from homesim.render.gl import mujoco
from homesim.render.poses import Pose, write_qpos
from homesim.render.scene import SceneModel

DAMPING = 0.05
ITERATIONS = 80
TOLERANCE = 0.004
"""Metres: the solver stops once the hand is this close to its target."""


def arm_joints(side: str, lean: bool = True) -> tuple[str, ...]:
    """The joints a reach moves: the arm's, and the spine's when it may lean."""
    arm = (f"{side}_sh_pitch", f"{side}_sh_roll", f"{side}_sh_yaw", f"{side}_elbow")
    return (*arm, "spine_pitch", "spine_yaw") if lean else arm


def crouched(pose: Pose, shape: AgentShape, drop: float) -> Pose:
    """`pose` with the pelvis `drop` metres lower: thighs forward, shins back by the same
    angle, so the feet stay under the body."""
    if drop <= 0.0:
        return pose
    legs = shape.thigh + shape.shin
    a = math.acos(max(-1.0, 1.0 - 2.0 * drop / legs))
    return replace(pose, z=pose.z - drop).with_joints(
        l_hip_pitch=-a, r_hip_pitch=-a, l_knee=2 * a, r_knee=2 * a)


class ArmIK:
    """Solves reach poses for a scene's agent."""

    def __init__(self, scene: SceneModel):
        self.scene = scene
        self.model = scene.model
        self.data = mujoco.MjData(scene.model)
        m = self.model
        self._dof = {name: int(m.jnt_dofadr[m.joint(f"a:{name}").id])
                     for name in scene.joint_qpos}
        self._range = {name: tuple(m.jnt_range[m.joint(f"a:{name}").id])
                       for name in scene.joint_qpos}
        self._jacp = np.zeros((3, m.nv))

    def hand(self, pose: Pose, side: str) -> np.ndarray:
        """World position of a hand for a pose."""
        return self.hand_frame(pose, side)[0]

    def hand_frame(self, pose: Pose, side: str) -> tuple[np.ndarray, np.ndarray]:
        """World position of a hand and the 3x3 rotation of the body that carries it."""
        write_qpos(self.data.qpos, pose, self.scene.joint_qpos)
        mujoco.mj_kinematics(self.model, self.data)
        site = self.scene.hand_sites[side]
        body = self.model.site_bodyid[site]
        return (self.data.site_xpos[site].copy(),
                self.data.xmat[body].reshape(3, 3).copy())

    def site(self, pose: Pose, name: str) -> np.ndarray:
        """World position of a named site (``j:head``...) for a pose."""
        write_qpos(self.data.qpos, pose, self.scene.joint_qpos)
        mujoco.mj_kinematics(self.model, self.data)
        return self.data.site(name).xpos.copy()

    def reach(self, pose: Pose, side: str, target: np.ndarray,
              grip: np.ndarray | None = None, lean: bool = True) -> tuple[Pose, float]:
        """The pose with the `side` arm reaching `target`; and the distance left (metres).

        `grip`: reach with the point held at this offset in the hand's body frame (a held
        object's centre) instead of the hand itself. `lean`: the spine may bend too."""
        names = arm_joints(side, lean)
        q = {n: pose.joints.get(n, 0.0) for n in names}
        site = self.scene.hand_sites[side]
        body = int(self.model.site_bodyid[site])
        offset = np.zeros(3) if grip is None else np.asarray(grip, float)
        err = np.inf
        for _ in range(ITERATIONS):
            cur = pose.with_joints(**q)
            write_qpos(self.data.qpos, cur, self.scene.joint_qpos)
            mujoco.mj_kinematics(self.model, self.data)
            mujoco.mj_comPos(self.model, self.data)
            point = self.data.site_xpos[site] + self.data.xmat[body].reshape(3, 3) @ offset
            e = target - point
            err = float(np.linalg.norm(e))
            if err < TOLERANCE:
                break
            mujoco.mj_jac(self.model, self.data, self._jacp, None, point, body)
            jac = self._jacp[:, [self._dof[n] for n in names]]
            # dq = J^T (J J^T + damping^2 I)^-1 e
            dq = jac.T @ np.linalg.solve(jac @ jac.T + DAMPING**2 * np.eye(3), e)
            for n, d in zip(names, dq, strict=True):
                lo, hi = self._range[n]
                q[n] = float(np.clip(q[n] + np.clip(d, -0.3, 0.3), lo, hi))
        return pose.with_joints(**q), err

    def held_point(self, pose: Pose, side: str, grip: np.ndarray | None) -> np.ndarray:
        """World position of the point at `grip` in the hand's body frame (the hand site
        itself without one)."""
        hand, rot = self.hand_frame(pose, side)
        return hand if grip is None else hand + rot @ grip
