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
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy._core.umath import clip as _clip_ufunc  # type: ignore[attr-defined]
from numpy.linalg import _umath_linalg

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
        offset = None if grip is None else np.asarray(grip, float)
        model, data = self._solver, self._solver_data
        cols = [self._dof[n] for n in names]
        addrs = np.array([self.scene.joint_qpos[n] for n in names])
        lo, hi = np.array([self._range[n] for n in names]).T
        if lean and max_lean < MAX_LEAN:
            k = names.index("spine_pitch")
            hi[k] = max(min(hi[k], max_lean), lo[k])
        # Only the solved joints change: the rest of the pose is written once.
        write_qpos(data.qpos, pose, self.scene.joint_qpos)
        qpos = data.qpos
        step = _Step(model, data, body, site, offset, target, cols, side, grasp)
        limit = ITERATIONS * (2 if grasp else 1)
        tried: dict[bytes, int] = {}  # joint values -> the iteration that had them
        history: list[tuple[np.ndarray, float]] = []
        err = np.inf
        for i in range(limit):
            first = tried.setdefault(values.tobytes(), i)
            if first < i:  # the same values as then: the steps repeat from there on
                values, err = _cycle_end(history, first, i - first, limit)
                break
            qpos[addrs] = values
            err = step.error()
            if step.done(err):
                break
            history.append((values, err))
            # Steps of at most 0.3 rad, within the joints' ranges.
            values = _clip(values + _clip(step.dq(), -0.3, 0.3), lo, hi)
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


def _cycle_end(history: list[tuple[np.ndarray, float]], first: int, period: int,
               limit: int) -> tuple[np.ndarray, float]:
    """What `limit` iterations end with when the joint values of iteration `first` come
    back `period` iterations later (a step is a function of the values alone, so they
    cycle, never reaching the tolerance, to the end): the values after the last step
    and the error measured at it. `history`: each iteration's (values, error)."""
    values = history[first + (limit - first) % period][0]
    return values, history[first + (limit - 1 - first) % period][1]


class _Step:
    """One damped-least-squares step of `ArmIK._solve`: the error (position, and the
    palm's and fingers' turns of a grasp) and the joints' change, dq = J^T (J J^T +
    damping^2 I)^-1 e, into buffers made once per solve: the same arithmetic as
    stacking them anew each iteration (the same bytes), without its per-call overhead."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, body: int, site: int,
                 offset: np.ndarray | None, target: np.ndarray, cols: list[int], side: str,
                 grasp: Grasp | None):
        self.model, self.data, self.body, self.site = model, data, body, site
        self.offset, self.target, self.grasp = offset, target, grasp
        self.xmat, self.site_xpos = data.xmat, data.site_xpos  # views, read each step
        rows = 3 if grasp is None else 9
        self.jacs = np.zeros((6, model.nv))  # position rows, then rotation rows
        self.jacp, self.jacr = self.jacs[:3], self.jacs[3:]
        # The Jacobian's rows: position, then the rotation's weighted once per turn (as
        # indices into `jacs` flattened).
        self.pick = (np.array([0, 1, 2, 3, 4, 5, 3, 4, 5][:rows])[:, None] * model.nv
                     + np.array(cols)[None, :])
        w1, w2 = ORIENT_WEIGHT
        self.weights = np.array([1.0, 1.0, 1.0, w1, w1, w1, w2, w2, w2])[:, None]
        # Fortran order, as `jacp[:, cols]` and its stack are: BLAS adds in that order.
        self.jac, self.e = np.zeros((rows, len(cols)), order="F"), np.zeros(rows)
        self.e3 = self.e[:3]  # the position's rows
        self.eye = DAMPING**2 * np.eye(rows)
        self.sign = -1.0 if side == "l" else 1.0  # the palm faces the body: +-y
        self.wanted: tuple[list[float], list[float]] = (
            ([], []) if grasp is None else (np.asarray(grasp.palm, float).tolist(),
                                            np.asarray(grasp.fingers, float).tolist()))

    def error(self) -> float:
        """Pose the solver's data at its qpos; the hand's distance from its target."""
        model, data = self.model, self.data
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        point = self.site_xpos[self.site]
        if self.offset is not None:
            point = point + self.xmat[self.body].reshape(3, 3) @ self.offset
        np.subtract(self.target, point, out=self.e3)
        mujoco.mj_jac(model, data, self.jacp, self.jacr, point, self.body)
        return _norm(self.e3)

    def done(self, err: float) -> bool:
        """Whether the hand is there (and turned as the grasp wants); else the error's
        turn rows and the Jacobian are filled for `dq`."""
        if self.grasp is None:
            self.jac[:] = self.jacs.take(self.pick)
            return err < TOLERANCE
        r = self.xmat[self.body].tolist()  # the 3x3 rotation, row by row
        s = self.sign
        palm, fingers = self.wanted
        turns = (_cross((s * r[1], s * r[4], s * r[7]), palm),
                 _cross((-r[2], -r[5], -r[8]), fingers))
        if err < TOLERANCE and max(_norm(np.array(t)) for t in turns) < ORIENT_TOLERANCE:
            return True
        w1, w2 = ORIENT_WEIGHT
        self.e[3:] = [w1 * turns[0][0], w1 * turns[0][1], w1 * turns[0][2],
                      w2 * turns[1][0], w2 * turns[1][1], w2 * turns[1][2]]
        np.multiply(self.jacs.take(self.pick), self.weights, out=self.jac)
        return False

    def dq(self) -> np.ndarray:
        jac = self.jac
        return jac.T @ _solve_linear(jac @ jac.T + self.eye, self.e)


def _norm(v: np.ndarray) -> float:
    """`np.linalg.norm` of a vector, the same arithmetic (the square root of its dot
    product with itself) without the dispatch."""
    return math.sqrt(float(v.dot(v)))


def _clip(x: np.ndarray, lo: float | np.ndarray, hi: float | np.ndarray) -> np.ndarray:
    """`np.minimum(np.maximum(x, lo), hi)`: NumPy's clip ufunc, the same comparisons in
    one call (without `np.clip`'s wrapper)."""
    return _clip_ufunc(x, lo, hi)


def _solve_linear(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """`np.linalg.solve(a, b)` for a float64 matrix and vector: the same LAPACK routine
    (its gufunc), without the checks and error-state switching around it (the damped
    matrix is never singular)."""
    return _umath_linalg.solve1(a, b, signature="dd->d")


def _cross(a: Sequence[float], b: Sequence[float]) -> tuple[float, float, float]:
    """a x b of two 3-vectors (the products and differences of `np.cross`, in Python
    floats: this runs ~10^5 times an episode)."""
    a0, a1, a2 = a
    b0, b1, b2 = b
    return (a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0)
