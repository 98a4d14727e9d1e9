"""Reaching: a small damped-least-squares inverse-kinematics solver for one arm.

It moves the shoulder (3 hinges), the elbow and the spine (pitch and yaw) so that the hand
site reaches a world point, using MuJoCo's site Jacobian on a scratch `MjData`. For low
points the whole body can crouch first (`crouched`: hips and knees bent, pelvis lowered).
A grasp (`Grasp`) also turns the hand: the wrist's three hinges join in, and the palm's
contact site is brought to the point with the palm facing a given direction and the
fingers pointing along another (rotation rows of the Jacobian, weighted below the
position's).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace

import numpy as np

from homesim.render.agent import AgentShape
from homesim.render.gl import mujoco
from homesim.render.poses import FLAT, Pose, write_qpos
from homesim.render.scene import SceneModel

DAMPING = 0.05
ITERATIONS = 80
TOLERANCE = 0.004
"""Metres: the solver stops once the hand is this close to its target."""
ORIENT_WEIGHT = (0.25, 0.12)
"""Weights (metres per radian) of the palm's facing and the fingers' direction against the
position error in a grasp."""
ORIENT_TOLERANCE = 0.1
"""Radians: a grasp's orientation is good enough below this (position first)."""
MAX_LEAN = 1.1
"""Radians: the spine bends forward at most this much in a reach (about 63 degrees; lower
points are reached crouching). Reaching across a table needs about 1.1."""


@dataclass(frozen=True)
class Grasp:
    """How a hand takes an object: the palm's contact site (``{side}_palm``) at `point`,
    the palm facing `palm` and the fingers pointing along `fingers` (world unit vectors);
    `box` (lo, hi corners), when given, is the object's: the wrist must end near it."""

    point: np.ndarray
    palm: np.ndarray
    fingers: np.ndarray
    box: tuple[np.ndarray, np.ndarray] | None = None
    flat: bool = False  # the hand laid flat (`poses.FLAT`): pressing, not taking


def wrist_joints(side: str) -> tuple[str, ...]:
    return (f"{side}_wrist_twist", f"{side}_wrist_flex", f"{side}_wrist_dev")


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
        lo, hi = self._range["spine_pitch"]
        self._range["spine_pitch"] = (lo, min(hi, MAX_LEAN))
        self._solver = _agent_only(scene) or m
        self._solver_data = mujoco.MjData(self._solver)
        self._jacp = np.zeros((3, self._solver.nv))
        self._solved: dict[tuple, tuple[Pose, float]] = {}
        """Solves by their inputs: a reach planner tries the same reach again (a grasp
        from each standing point it weighs; a third of an episode's solves repeat)."""

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

    def head_frame(self, pose: Pose) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The head's centre and its forward and up directions (world) for a pose: a
        lying agent's face looks up."""
        write_qpos(self.data.qpos, pose, self.scene.joint_qpos)
        mujoco.mj_kinematics(self.model, self.data)
        rot = self.data.xmat[self.model.body("a:head").id].reshape(3, 3)
        return self.data.site("j:head").xpos.copy(), rot[:, 0].copy(), rot[:, 2].copy()

    def site(self, pose: Pose, name: str) -> np.ndarray:
        """World position of a named site (``j:head``...) for a pose."""
        write_qpos(self.data.qpos, pose, self.scene.joint_qpos)
        mujoco.mj_kinematics(self.model, self.data)
        return self.data.site(name).xpos.copy()

    def reach(self, pose: Pose, side: str, target: np.ndarray,
              grip: np.ndarray | None = None, lean: bool = True,
              max_lean: float = MAX_LEAN) -> tuple[Pose, float]:
        """The pose with the `side` arm reaching `target`; and the distance left (metres).

        `grip`: reach with the point held at this offset in the hand's body frame (a held
        object's centre) instead of the hand itself. `lean`: the spine may bend too, at
        most `max_lean` radians forward."""
        return self._cached(pose, side, np.asarray(target, float), grip, lean, None, max_lean)

    def grasp(self, pose: Pose, side: str, grasp: Grasp, lean: bool = True,
              max_lean: float = MAX_LEAN) -> tuple[Pose, float]:
        """The pose with the `side` hand taking hold as `grasp` says (the wrist turns the
        palm; a `flat` grasp lays the fingers straight); and the distance left between the
        palm's contact site and its point."""
        if grasp.flat:
            pose = pose.with_grip(side, FLAT)
        return self._cached(pose, side, np.asarray(grasp.point, float), None, lean, grasp,
                            max_lean)

    def _cached(self, pose: Pose, side: str, target: np.ndarray, grip: np.ndarray | None,
                lean: bool, grasp: Grasp | None, max_lean: float = MAX_LEAN
               ) -> tuple[Pose, float]:
        """`_solve`, or its answer for the same inputs given before (the same bytes)."""
        key = (_pose_key(pose), side, target.tobytes(), _array_key(grip), lean, max_lean,
               None if grasp is None else tuple(_array_key(np.asarray(v, float)) for v in (
                   grasp.point, grasp.palm, grasp.fingers)))
        hit = self._solved.get(key)
        if hit is None:
            hit = self._solved[key] = self._solve(pose, side, target, grip, lean, grasp,
                                                  max_lean)
        solved, err = hit
        return replace(solved, joints=dict(solved.joints)), err

    def _solve(self, pose: Pose, side: str, target: np.ndarray, grip: np.ndarray | None,
               lean: bool, grasp: Grasp | None, max_lean: float = MAX_LEAN
               ) -> tuple[Pose, float]:
        names = arm_joints(side, lean) + (wrist_joints(side) if grasp else ())
        values = np.array([float(pose.joints.get(n, 0.0)) for n in names])
        site = (self.scene.palm_sites if grasp else self.scene.hand_sites)[side]
        body = int(self.model.site_bodyid[site])
        offset = np.zeros(3) if grip is None else np.asarray(grip, float)
        model, data = self._solver, self._solver_data
        jacr = np.zeros((3, model.nv))
        cols = [self._dof[n] for n in names]
        addrs = np.array([self.scene.joint_qpos[n] for n in names])
        lo, hi = np.array([self._range[n] for n in names]).T
        if lean and max_lean < MAX_LEAN:
            k = names.index("spine_pitch")
            hi[k] = max(min(hi[k], max_lean), lo[k])
        eye = DAMPING**2 * np.eye(9 if grasp is not None else 3)
        # Only the solved joints change: the rest of the pose is written once.
        write_qpos(data.qpos, pose, self.scene.joint_qpos)
        qpos = data.qpos
        err = np.inf
        for _ in range(ITERATIONS * (2 if grasp else 1)):
            qpos[addrs] = values
            mujoco.mj_kinematics(model, data)
            mujoco.mj_comPos(model, data)
            rot = data.xmat[body].reshape(3, 3)
            point = data.site_xpos[site] + rot @ offset
            e = target - point
            err = float(np.linalg.norm(e))
            mujoco.mj_jac(model, data, self._jacp, jacr, point, body)
            jac = self._jacp[:, cols]
            if grasp is not None:
                turns = _turns(rot, side, grasp)
                if err < TOLERANCE and max(np.linalg.norm(t) for t in turns) < ORIENT_TOLERANCE:
                    break
                e = np.concatenate([e] + [w * t for w, t in zip(ORIENT_WEIGHT, turns,
                                                                  strict=True)])
                jac = np.vstack([jac] + [w * jacr[:, cols] for w in ORIENT_WEIGHT])
            elif err < TOLERANCE:
                break
            # dq = J^T (J J^T + damping^2 I)^-1 e
            dq = jac.T @ np.linalg.solve(jac @ jac.T + eye, e)
            # Steps of at most 0.3 rad, within the joints' ranges (one array operation).
            values = np.minimum(np.maximum(values + np.minimum(np.maximum(dq, -0.3), 0.3), lo),
                                hi)
        return pose.with_joints(**dict(zip(names, values.tolist(), strict=True))), err

    def held_point(self, pose: Pose, side: str, grip: np.ndarray | None) -> np.ndarray:
        """World position of the point at `grip` in the hand's body frame (the hand site
        itself without one)."""
        hand, rot = self.hand_frame(pose, side)
        return hand if grip is None else hand + rot @ grip


def _pose_key(pose: Pose) -> tuple:
    """Everything of a pose that `write_qpos` writes, as a key."""
    return (pose.x, pose.y, pose.z, pose.yaw, pose.tilt, pose.l_grip, pose.r_grip,
            tuple(sorted(pose.joints.items())))


def _array_key(a: np.ndarray | None) -> bytes | None:
    return None if a is None else np.asarray(a, float).tobytes()


def _agent_only(scene: SceneModel) -> mujoco.MjModel | None:
    """The agent alone, compiled from the scene's MJCF without the home: the same bodies,
    joints, sites and addresses (the agent is the world body's first child), so the
    solver's kinematics are the scene's at a fraction of the cost (no home geoms to
    place). None when the scene has no MJCF or the ids would differ."""
    xml, files = scene.mjcf
    if not xml:
        return None
    root = ET.fromstring(xml)
    world = root.find("worldbody")
    if world is None:
        return None
    for child in list(world):
        if child.get("name") != "agent":
            world.remove(child)
    model = mujoco.MjModel.from_xml_string(ET.tostring(root, encoding="unicode"), files)
    full = scene.model
    same = (model.nq <= full.nq and model.nbody <= full.nbody and model.nsite <= full.nsite
            and all(model.joint(f"a:{n}").qposadr[0] == a for n, a in scene.joint_qpos.items())
            and all(model.site(i).name == full.site(i).name for i in range(model.nsite))
            and all(model.body(i).name == full.body(i).name for i in range(model.nbody)))
    return model if same else None


def _turns(rot: np.ndarray, side: str, grasp: Grasp) -> tuple[np.ndarray, np.ndarray]:
    """Rotation vectors (axis times sine of the angle) taking the palm's normal onto
    `grasp.palm` and the fingers' direction onto `grasp.fingers`."""
    palm = rot[:, 1] * (-1.0 if side == "l" else 1.0)  # the palm faces the body: +-y
    fingers = -rot[:, 2]
    return _cross(palm, grasp.palm), _cross(fingers, grasp.fingers)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b of two 3-vectors (the products and differences of `np.cross`, without its
    per-call overhead: this runs ~10^5 times an episode)."""
    a0, a1, a2 = a.tolist()
    b0, b1, b2 = b.tolist()
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])
