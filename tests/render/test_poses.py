import math

import numpy as np
import pytest

from homesim.render.agent import AGENTS, HINGES
from homesim.render.poses import blend, root_quat, sitting, standing, walk_cycle, write_qpos


def _rotate(q, v):
    w, x, y, z = q
    r = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return r @ v


def test_root_quaternion_heading_and_lying():
    np.testing.assert_allclose(_rotate(root_quat(math.pi / 2, 0.0), [1, 0, 0]), [0, 1, 0],
                               atol=1e-12)
    # Lying on the back: the body's up axis points backwards (-heading).
    np.testing.assert_allclose(_rotate(root_quat(0.0, -math.pi / 2), [0, 0, 1]), [-1, 0, 0],
                               atol=1e-12)


def test_blend_ends_on_its_poses_and_turns_the_short_way():
    shape = AGENTS["male1"]
    a = standing(shape, (0, 0), 3.0)
    b = sitting(shape, (1, 0), -3.0, 0.45)
    assert blend(a, b, 0.0) == a.__class__(a.x, a.y, a.z, a.yaw, a.tilt,
                                           {k: a.joints.get(k, 0.0) for k in blend(a, b, 0).joints})
    end = blend(a, b, 1.0)
    assert abs(end.x - 1) < 1e-12 and abs(end.z - b.z) < 1e-12
    mid = blend(a, b, 0.5)
    assert abs(abs(mid.yaw) - math.pi) < 0.05  # through pi, not through 0


def test_walk_cycle_swings_the_legs_in_opposition():
    base = standing(AGENTS["female1"], (0, 0), 0.0)
    p = walk_cycle(base, math.pi / 2)
    assert p.joints["l_hip_pitch"] == -p.joints["r_hip_pitch"] != 0
    run = walk_cycle(base, math.pi / 2, run=True)
    assert abs(run.joints["l_hip_pitch"]) > abs(p.joints["l_hip_pitch"])


def _qpos_of(pose):
    """qpos of a pose with the hinges in `HINGES` order after the free joint."""
    addr = {n: 7 + i for i, n in enumerate(HINGES)}
    qpos = np.zeros(7 + len(HINGES))
    write_qpos(qpos, pose, addr)
    return {n: qpos[a] for n, a in addr.items()}


def test_grip_is_per_hand_blends_and_drives_the_fingers():
    from homesim.render.agent import FINGER_CLOSED
    from homesim.render.poses import gripping

    base = standing(AGENTS["male2"], (0, 0), 0.0)
    held = gripping(base, {"r": 21})
    assert (held.grip("r"), held.grip("l")) == (1.0, 0.0)
    assert blend(base, held, 0.5).grip("r") == pytest.approx(0.5)
    assert base.with_grip("l", 3.0).grip("l") == 1.0  # clipped
    q = _qpos_of(held)
    for finger, (open_, closed) in FINGER_CLOSED.items():
        assert q[f"r_{finger}"] == closed and q[f"l_{finger}"] == open_ < closed


def test_a_flat_hand_has_straight_fingers():
    """A hand pressed flat on a face (grip `FLAT`) has its fingers straight, not the open
    hand's bend that put the fingertips 3 cm into a wall behind a switch."""
    from homesim.render.agent import FINGER_CLOSED
    from homesim.render.poses import FLAT

    flat = standing(AGENTS["male2"], (0, 0), 0.0).with_grip("l", FLAT)
    assert flat.grip("l") == FLAT and flat.with_grip("l", -5.0).grip("l") == FLAT
    q = _qpos_of(flat)
    for finger, (open_, _) in FINGER_CLOSED.items():
        assert q[f"l_{finger}"] == 0.0 and q[f"r_{finger}"] == open_ > 0.0


def test_skirt_follows_the_thighs_when_sitting_not_when_walking():
    shape = AGENTS["female1"]
    seat = sitting(shape, (0, 0), 0.0, 0.45)
    walk = walk_cycle(standing(shape, (0, 0), 0.0), 1.0)
    assert _qpos_of(seat)["skirt"] == pytest.approx(seat.joints["l_hip_pitch"])
    assert _qpos_of(walk)["skirt"] == pytest.approx(0.0, abs=1e-12)


def test_walk_cycle_bends_softly():
    base = standing(AGENTS["male1"], (0, 0), 0.0)
    phases = np.linspace(0, 2 * math.pi, 73)
    knees = [walk_cycle(base, p).joints["l_knee"] for p in phases]
    assert min(knees) > 0.0 and 0.7 < max(knees) < 1.1  # never locked straight, no 90 deg
    elbows = [walk_cycle(base, p).joints["r_elbow"] for p in phases]
    assert all(-0.6 < e < -0.2 for e in elbows)


def test_a_spared_arm_mirrors_roll_and_yaw_and_carrying_is_one_of_them():
    from homesim.render.poses import CARRY, SPARE, carrying, spared

    base = standing(AGENTS["male1"], (0, 0), 0.0)
    for angles in SPARE:
        left, right = spared(base, "l", angles), spared(base, "r", angles)
        assert left.joints["l_elbow"] == right.joints["r_elbow"] == angles["elbow"]
        assert left.joints["l_sh_roll"] == -right.joints["r_sh_roll"]
        assert left.joints["l_sh_yaw"] == -right.joints["r_sh_yaw"]
        assert left.joints["r_elbow"] == base.joints["r_elbow"]  # the other arm as it was
    assert carrying(base, "r") == spared(base, "r", CARRY)
