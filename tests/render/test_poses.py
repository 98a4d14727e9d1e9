import math

import numpy as np

from homesim.render.agent import AGENTS
from homesim.render.poses import blend, root_quat, sitting, standing, walk_cycle


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
