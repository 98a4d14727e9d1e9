from dataclasses import replace

import numpy as np
import pytest

from homesim.render.ik import MAX_LEAN
from homesim.render.interact import (
    FLAT,
    HAND_ROOM,
    LEAN_BACK,
    TOUCH,
    ReachPlan,
    ReachPlanner,
    box_gap,
    hand_room_clear,
    palm_grasps,
    touch_grasps,
)
from homesim.render.layout import Box
from homesim.render.poses import Pose

pytestmark = pytest.mark.render


def test_box_gap_is_zero_inside_and_euclidean_outside():
    box = Box(np.zeros(3), np.array([0.1, 0.2, 0.3]))
    assert box_gap(box, np.array([0.05, -0.1, 0.2])) == 0.0
    assert box_gap(box, np.array([0.4, 0.6, 0.0])) == pytest.approx(0.5)


def test_a_tall_object_is_taken_by_the_face_on_the_hand_side():
    cup = Box(np.array([1.0, 0.0, 0.85]), np.array([0.04, 0.04, 0.05]))
    agent = np.array([0.5, 0.0])  # facing +x: the right is -y
    side, top, *_ = palm_grasps(cup, "r", agent)
    np.testing.assert_allclose(side.palm, [0.0, 1.0, 0.0])  # palm on the -y face, facing +y
    np.testing.assert_allclose(side.fingers, [1.0, 0.0, 0.0])  # fingers away from the agent
    assert side.point[1] == pytest.approx(-0.036)  # 4 mm inside the face
    assert cup.lo[0] < side.point[0] <= cup.center[0]  # the heel near the near edge
    left = palm_grasps(cup, "l", agent)[0]
    np.testing.assert_allclose(left.palm, [0.0, -1.0, 0.0])
    np.testing.assert_allclose(top.palm, [0.0, 0.0, -1.0])
    assert top.point[2] == pytest.approx(cup.hi[2] - 0.004)


def test_flat_and_floor_objects_are_taken_from_above_first():
    agent = np.array([0.0, 0.0])
    plate = Box(np.array([0.0, 0.6, 0.8]), np.array([0.12, 0.12, FLAT / 2]))
    box_on_floor = Box(np.array([0.0, 0.6, 0.1]), np.array([0.1, 0.1, 0.1]))
    for box in (plate, box_on_floor):
        first = palm_grasps(box, "r", agent)[0]
        np.testing.assert_allclose(first.palm, [0.0, 0.0, -1.0])
        np.testing.assert_allclose(first.fingers, [0.0, 1.0, 0.0], atol=1e-9)


def test_hand_room_asks_rays_out_of_the_taken_face():
    cup = Box(np.array([1.0, 0.0, 0.85]), np.array([0.04, 0.04, 0.05]))
    side = palm_grasps(cup, "r", np.array([0.5, 0.0]))[0]
    rays = []

    def wall_at_minus_y(start, direction, length):
        rays.append((start, direction, length))
        return start[1] + direction[1] * length > -0.06  # a wall at y = -0.06

    assert not hand_room_clear(side, wall_at_minus_y)
    assert all(np.allclose(d, [0.0, -1.0, 0.0]) and n == HAND_ROOM for _, d, n in rays)
    assert hand_room_clear(side, lambda *_: True)


def test_a_touch_lays_the_palm_on_the_face_toward_the_agent():
    panel = Box(np.array([1.0, 0.0, 1.3]), np.array([0.01, 0.15, 0.2]))  # on a wall at x=1
    face, *_ = touch_grasps(panel, np.array([0.4, 0.0]))
    np.testing.assert_allclose(face.palm, [1.0, 0.0, 0.0])  # into the panel, fingers up
    np.testing.assert_allclose(face.fingers, [0.0, 0.0, 1.0])
    assert face.point[0] < panel.center[0] and face.flat  # on the near face, the hand flat
    low = Box(np.array([1.0, 0.0, 0.3]), np.array([0.2, 0.2, 0.2]))  # a cat on the floor
    first, *_ = touch_grasps(low, np.array([0.4, 0.0]))
    np.testing.assert_allclose(first.palm, [0.0, 0.0, -1.0])  # the palm on its back


@pytest.mark.parametrize(("side", "first"), [("r", 1.0), ("l", -1.0)])
def test_a_small_switch_is_pressed_by_the_fingertips_beside_the_palm(side, first):
    """A light switch (12 x 10 cm) is pressed by the fingertips on its near part, the
    palm flat on the wall beside it and the fingers level toward the body's middle, so
    the hand does not cover it; fingers up over it is still tried afterwards."""
    from homesim.render.interact import FINGERTIPS

    switch = Box(np.array([1.0, 0.0, 1.3]), np.array([0.01, 0.05, 0.06]))  # on a wall at x=1
    grasps = touch_grasps(switch, np.array([0.4, 0.0]), side=side)
    press = grasps[0]
    np.testing.assert_allclose(press.palm, [1.0, 0.0, 0.0])
    np.testing.assert_allclose(press.fingers, [0.0, first, 0.0])  # the agent's left: +y
    assert press.flat and press.point[0] < switch.center[0]
    tips = press.point + FINGERTIPS * press.fingers  # their end
    assert abs(press.point[1]) > switch.half[1]  # the palm beside the switch
    covered = (tips[1] * first + switch.half[1]) / (2 * switch.half[1])
    assert 0.2 < covered < 0.4 and abs(tips[2] - switch.center[2]) < 1e-9
    assert any(np.allclose(g.fingers, [0.0, 0.0, 1.0]) for g in grasps[1:3])


def test_a_faucet_reaching_into_the_wall_is_touched_on_what_stands_out():
    """A faucet's box 3 cm into the wall behind it (scene 3): the part outside the wall is
    what the hand touches; a box clear of walls, or one wholly in the wall, is kept."""
    from homesim.render.interact import out_of_walls

    walls = (np.array([[4.93, -4.0, 0.0]]), np.array([[5.03, 0.0, 2.5]]))
    faucet = Box.from_bounds(np.array([4.862, -3.26, 0.96]), np.array([4.962, -3.16, 1.06]))
    out = out_of_walls(faucet, walls)
    np.testing.assert_allclose(out.hi, [4.93, -3.16, 1.06])
    np.testing.assert_allclose(out.lo, faucet.lo)
    assert all(g.point[0] < 4.93 for g in touch_grasps(out, np.array([4.3, -3.2])))
    clear = Box.from_bounds(np.array([4.0, -3.26, 0.96]), np.array([4.1, -3.16, 1.06]))
    assert out_of_walls(clear, walls) is clear
    buried = Box.from_bounds(np.array([4.94, -3.26, 0.96]), np.array([5.0, -3.16, 1.06]))
    assert out_of_walls(buried, walls) is buried


class _LeaningPlanner(ReachPlanner):
    """A planner whose body enters something (a wall before the head) when the spine
    bends more than 0.5 rad, and whose reaches bend as far as they may and fall short."""

    def __init__(self, touches_upright: bool):
        self.max_lean, self.touches_upright, self.tried = MAX_LEAN, touches_upright, []

    def inside(self, pose: Pose) -> float:
        return 0.05 if pose.joints["spine_pitch"] > 0.5 else 0.0

    def reach_from(self, xy, side, point, grip=None, grasp_of=None) -> ReachPlan:
        self.tried.append(self.max_lean)
        pose = Pose(0.0, 0.0, 0.96, 0.0, joints={"spine_pitch": self.max_lean})
        gap = 0.0 if self.touches_upright else 0.3
        return ReachPlan(pose, gap, self.inside(pose) if gap <= TOUCH else 0.0)


@pytest.mark.parametrize("touches", [False, True])
def test_a_reach_whose_body_enters_something_bows_less(touches):
    """A reach bowing 1.1 rad for a thing out of reach put the head 5 cm into the wall
    behind a desk (gen-2): it is tried again bent `LEAN_BACK` less at a time until the
    body is clear; one that touches only gives way to one that still touches."""
    planner = _LeaningPlanner(touches)
    deep = Pose(0.0, 0.0, 0.96, 0.0, joints={"spine_pitch": MAX_LEAN})
    start = ReachPlan(deep, 0.0 if touches else 0.3, 0.05 if touches else 0.0)
    plan = planner.upright(start, "r", np.array([1.0, 0.0, 1.0]))
    assert plan.pose.joints["spine_pitch"] <= 0.5 and plan.inside == 0.0
    assert planner.tried[0] == pytest.approx(MAX_LEAN - LEAN_BACK)
    assert plan.touches == touches
    clear = ReachPlan(replace(deep, joints={"spine_pitch": 0.3}), 0.3)
    assert planner.upright(clear, "r", np.array([1.0, 0.0, 1.0])) is clear


class _WallAtTheLeftHand(ReachPlanner):
    """A planner whose body enters a wall while the left arm hangs at the side (gen-4's
    bathroom: the free hand in the wall beside the sink as the right one takes the
    faucet): deep unless the left elbow is bent."""

    def __init__(self, spare):
        self.spare, self.tried = spare, []

    def inside(self, pose: Pose) -> float:
        self.tried.append(pose)
        return 0.0 if pose.joints.get("l_elbow", 0.0) < -1.0 else 0.045


@pytest.mark.parametrize("spare", ["l", None])
def test_the_spare_arm_comes_out_of_the_wall_beside_the_agent(spare):
    """A reach whose body passes into something tries the free arm (holding nothing) out
    of the way (`SPARE`): before the belly; with no spare arm (the other hand holds
    something, or it is the one reaching) the pose is kept."""
    from homesim.render.poses import SPARE

    planner = _WallAtTheLeftHand(spare)
    hanging = Pose(0.0, 0.0, 0.96, 0.0, joints={"l_elbow": -0.22, "r_elbow": -1.0})
    pose, depth = planner.spare_arm(hanging, "r", 0.045)
    if spare is None:
        assert pose is hanging and depth == 0.045 and not planner.tried
        return
    assert depth == 0.0 and pose.joints["l_elbow"] == SPARE[0]["elbow"]
    assert pose.joints["r_elbow"] == -1.0  # the reaching arm as the IK left it
    assert planner.spare_arm(hanging, "l", 0.045) == (hanging, 0.045)  # not the reaching one
