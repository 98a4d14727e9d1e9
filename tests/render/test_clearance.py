"""The body against the furniture: the clearance measure, and animations that keep the
body out of what the hands do not act on."""

from __future__ import annotations

import numpy as np
import pytest

import homesim
from homesim.render.agent import AGENTS
from homesim.render.animate import Animator
from homesim.render.clearance import Clearance
from homesim.render.gl import mujoco
from homesim.render.poses import standing, write_qpos
from homesim.render.scene import build_scene
from homesim.world.graph import EnvironmentGraph

from .conftest import box_home_dict

pytestmark = pytest.mark.render


@pytest.fixture(scope="module")
def scene():
    g = EnvironmentGraph.from_dict(box_home_dict())
    return g, build_scene(g, AGENTS["male1"], max_size=(64, 48))


def _posed(scene, pose):
    data = mujoco.MjData(scene.model)
    write_qpos(data.qpos, pose, scene.joint_qpos)
    mujoco.mj_kinematics(scene.model, data)
    return data


def test_a_body_standing_in_the_table_is_found_and_a_hand_may_be_in_what_it_acts_on(scene):
    _, sc = scene
    clear = Clearance(sc)
    # standing in the table: the thighs pass through its top (4 cm thick)
    inside = _posed(sc, standing(AGENTS["male1"], np.array([1.0, -1.0]), 0.0))
    found = clear.penetrations(inside, {}, 0.005)
    assert 20 in {p.node for p in found}
    assert {"l_thigh", "r_thigh"} <= {p.part for p in found if p.node == 20}
    away = _posed(sc, standing(AGENTS["male1"], np.array([-1.0, -1.4]), 0.0))
    assert clear.penetrations(away, {}, 0.015) == []  # the soles touch the floor
    reaching = _posed(sc, standing(AGENTS["male1"], np.array([1.0, -1.0]), 0.0).with_joints(
        r_sh_pitch=-1.2, r_elbow=-0.3))
    hands = {p.part for p in clear.penetrations(reaching, {}, 0.0)} & clear.hand_parts["r"]
    allowed = clear.penetrations(reaching, {"r": {20}}, 0.0)
    assert not hands & {p.part for p in allowed}


def test_at_every_effect_no_body_part_is_3_cm_inside_what_it_does_not_act_on(scene):
    g, sc = scene
    program = """[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Walk] <tv> (22)\n[SwitchOn] <tv> (22)
[Walk] <fridge> (23)\n[Open] <fridge> (23)\n[PutIn] <cup> (21) <fridge> (23)
[Close] <fridge> (23)\n"""
    result = homesim.execute(homesim.parse_program(program), g, trace=True, reference=True)
    tl = Animator(sc, g, AGENTS["male1"], fps=10, seed=0).run(result)
    clear = Clearance(sc)
    data = mujoco.MjData(sc.model)
    assert len(tl.interactions) == 5
    for it in tl.interactions:
        data.qpos[:] = tl.qpos[it.peak]
        data.mocap_pos[:] = tl.mocap[it.peak]
        mujoco.mj_kinematics(sc.model, data)
        hands = {"r": {*it.nodes, 21}, "l": {*it.nodes, 21}}  # the cup rides in a hand
        assert clear.penetrations(data, hands, 0.03) == [], it
