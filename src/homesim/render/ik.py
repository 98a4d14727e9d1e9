"""Reaching: a small damped-least-squares inverse-kinematics solver for one arm.

It moves the shoulder (3 hinges), the elbow and the spine pitch so that the hand site
reaches a world point, using MuJoCo's site Jacobian on a scratch `MjData`.
"""

from __future__ import annotations

import numpy as np

from homesim.render.gl import mujoco
from homesim.render.poses import Pose, write_qpos
from homesim.render.scene import SceneModel

DAMPING = 0.05
ITERATIONS = 40


def arm_joints(side: str) -> tuple[str, ...]:
    return (f"{side}_sh_pitch", f"{side}_sh_roll", f"{side}_sh_yaw", f"{side}_elbow",
            "spine_pitch")


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
        write_qpos(self.data.qpos, pose, self.scene.joint_qpos)
        mujoco.mj_kinematics(self.model, self.data)
        return self.data.site_xpos[self.scene.hand_sites[side]].copy()

    def reach(self, pose: Pose, side: str, target: np.ndarray) -> tuple[Pose, float]:
        """The pose with the `side` arm reaching `target`; and the distance left (metres)."""
        names = arm_joints(side)
        q = {n: pose.joints.get(n, 0.0) for n in names}
        site = self.scene.hand_sites[side]
        err = np.inf
        for _ in range(ITERATIONS):
            cur = pose.with_joints(**q)
            write_qpos(self.data.qpos, cur, self.scene.joint_qpos)
            mujoco.mj_kinematics(self.model, self.data)
            mujoco.mj_comPos(self.model, self.data)
            e = target - self.data.site_xpos[site]
            err = float(np.linalg.norm(e))
            if err < 0.01:
                break
            mujoco.mj_jacSite(self.model, self.data, self._jacp, None, site)
            jac = self._jacp[:, [self._dof[n] for n in names]]
            # dq = J^T (J J^T + damping^2 I)^-1 e
            dq = jac.T @ np.linalg.solve(jac @ jac.T + DAMPING**2 * np.eye(3), e)
            for n, d in zip(names, dq, strict=True):
                lo, hi = self._range[n]
                q[n] = float(np.clip(q[n] + np.clip(d, -0.3, 0.3), lo, hi))
        return pose.with_joints(**q), err
