import numpy as np
import pytest

import homesim
from homesim.render.agent import AGENTS
from homesim.render.animate import Animator
from homesim.render.gl import mujoco
from homesim.render.layout import to_mujoco
from homesim.render.scene import build_scene

pytestmark = pytest.mark.render

PROGRAM = """[Walk] <cup> (21)
[Grab] <cup> (21)
[Walk] <tv> (22)
[SwitchOn] <tv> (22)
[Walk] <fridge> (23)
[Open] <fridge> (23)
[PutIn] <cup> (21) <fridge> (23)
[Close] <fridge> (23)
"""


@pytest.fixture(scope="module")
def animated():
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    g = EnvironmentGraph.from_dict(box_home_dict())
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(PROGRAM), g, trace=True, reference=True)
    timeline = Animator(scene, g, AGENTS["male1"], fps=10, seed=0).run(result)
    return g, scene, timeline


def _in_hand(scene, timeline, frame, node=21, side="r"):
    """An object's centre in the frame of the hand's body (constant while it is held)."""
    d = mujoco.MjData(scene.model)
    d.qpos[:] = timeline.qpos[frame]
    d.mocap_pos[:] = timeline.mocap[frame]
    mujoco.mj_kinematics(scene.model, d)
    site = scene.hand_sites[side]
    rot = d.xmat[scene.model.site_bodyid[site]].reshape(3, 3)
    return rot.T @ (timeline.mocap[frame][scene.mocap[node]] - d.site_xpos[site])


def test_steps_cover_the_timeline_in_order(animated):
    _, _, tl = animated
    spans = tl.step_frames
    assert len(spans) == 8
    assert all(a <= b for a, b in spans)
    assert all(spans[i][1] + 1 == spans[i + 1][0] for i in range(len(spans) - 1))
    assert spans[-1][1] == len(tl) - 1


def test_grabbed_cup_stays_in_the_right_hand_while_walking(animated):
    _, scene, tl = animated
    grab_end = tl.step_frames[1][1]
    put_start = tl.step_frames[6][0]
    grip = _in_hand(scene, tl, grab_end)
    assert np.linalg.norm(grip) < 0.15  # held close to the hand
    for f in range(grab_end, put_start, 3):
        np.testing.assert_allclose(_in_hand(scene, tl, f), grip, atol=1e-6)
    walked = np.linalg.norm(tl.qpos[put_start][:2] - tl.qpos[grab_end][:2])
    assert walked > 1.0


def test_cup_ends_inside_the_fridge_and_the_door_swings(animated):
    g, scene, tl = animated
    fridge = to_mujoco(g.node(23))
    cup = tl.mocap[-1][scene.mocap[21]]
    assert np.all(np.abs(cup - fridge.center) <= fridge.half)
    hinge = scene.hinge_qpos[23]
    assert tl.qpos[tl.step_frames[5][0] - 1][hinge] == 0.0
    assert abs(tl.qpos[tl.step_frames[5][1]][hinge] - scene.hinge_open[23]) < 1e-9
    assert tl.qpos[-1][hinge] == 0.0  # closed again


def test_tv_screen_turns_on_at_switch_on(animated):
    _, _, tl = animated
    a, b = tl.step_frames[3]
    assert 22 not in tl.screens[a]
    assert 22 in tl.screens[b] and 22 in tl.screens[-1]


def test_agent_never_walks_through_the_table(animated):
    g, _, tl = animated
    table = to_mujoco(g.node(20))
    for q in tl.qpos:
        assert not np.all(np.abs(q[:2] - table.center[:2]) < table.half[:2])


def test_same_seed_same_timeline(animated):
    g, scene, tl = animated
    result = homesim.execute(homesim.parse_program(PROGRAM), g, trace=True, reference=True)
    again = Animator(scene, g, AGENTS["male1"], fps=10, seed=0).run(result)
    assert len(again) == len(tl)
    np.testing.assert_array_equal(np.array(again.qpos), np.array(tl.qpos))
    np.testing.assert_array_equal(np.array(again.mocap), np.array(tl.mocap))


def test_sitting_on_the_sofa_in_scene1(shared_data):
    from homesim.examples import load_example
    from homesim.render.layout import SEAT_HEIGHT

    g = homesim.load_home("scene1")
    scene = build_scene(g, AGENTS["male2"], max_size=(64, 48))
    result = homesim.execute(load_example("watch_tv"), g, trace=True)
    tl = Animator(scene, g, AGENTS["male2"], fps=5).run(result)
    sofa = to_mujoco(g.node(352))
    q = tl.qpos[tl.step_frames[3][1]]
    assert np.all(np.abs(q[:2] - sofa.center[:2]) <= sofa.half[:2])  # on the sofa
    assert SEAT_HEIGHT < q[2] < SEAT_HEIGHT + 0.2  # pelvis just above the seat
    assert q[scene.joint_qpos["l_knee"]] > 1.2  # knees bent


def _run(program: str, fps: int = 10):
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    g = EnvironmentGraph.from_dict(box_home_dict())
    scene = build_scene(g, AGENTS["female1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(program), g, trace=True,
                             reference=True)
    return scene, Animator(scene, g, AGENTS["female1"], fps=fps).run(result)


def test_second_object_goes_to_the_left_hand():
    scene, tl = _run("[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Grab] <apple> (24)\n"
                     "[Walk] <tv> (22)\n")
    assert [(a.node, a.side) for a in tl.attaches] == [(21, "r"), (24, "l")]
    for node, side in ((21, "r"), (24, "l")):
        grip = _in_hand(scene, tl, -1, node, side)
        np.testing.assert_allclose(_in_hand(scene, tl, -10, node, side), grip, atol=1e-6)


def test_running_is_faster_than_walking():
    _, walk = _run("[Walk] <tv> (22)\n")
    _, run = _run("[Run] <tv> (22)\n")
    assert len(run.qpos) < 0.75 * len(walk.qpos)


def test_lamp_lights_up_when_switched_on():
    _, tl = _run("[Walk] <tablelamp> (25)\n[SwitchOn] <tablelamp> (25)\n")
    a, b = tl.step_frames[1]
    assert 25 not in tl.lamps[a] and 25 in tl.lamps[b]


def test_agent_stands_where_grounding_chose(box_home):
    """One floor model: each interaction step ends with the agent on grounding's spot."""
    from homesim.ground import prepare_and_ground

    program = homesim.parse_program("[Walk] <cup> (1)\n[Grab] <cup> (1)\n[Walk] <tv> (1)\n"
                                    "[SwitchOn] <tv> (1)\n[Walk] <fridge> (1)\n"
                                    "[Open] <fridge> (1)\n")
    prepared, grounding = prepare_and_ground(program, box_home, seed=0)
    assert grounding.standing is not None
    g = prepared.graph
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(grounding.program, g, trace=True)
    plain = Animator(scene, g, AGENTS["male1"], fps=10).run(result)
    tl = Animator(scene, g, AGENTS["male1"], fps=10, standing=grounding.standing).run(result)
    moved = 0
    for i in (1, 3, 5):  # Grab, SwitchOn, Open
        spot = np.array(grounding.standing[i])
        end = tl.qpos[tl.step_frames[i][1]][:2]
        assert np.linalg.norm(end - spot) < 0.06, (i, end, spot)
        moved += np.linalg.norm(plain.qpos[plain.step_frames[i][1]][:2] - spot) > 0.06
    assert moved  # without the spots render stands elsewhere: the test can fail


def test_hand_touches_what_it_takes_even_from_a_far_spot(box_home):
    """Grounding's spot 1 m from the table: the agent steps closer, the hand reaches the
    cup's surface before the cup moves, and the cup does not jump when taken."""
    from homesim.render.interact import TOUCH

    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(PROGRAM), box_home, trace=True,
                             reference=True)
    far = (1.0 - 0.3 - 1.0, -1.0)  # 1 m from the table's -x edge (x = 0.7)
    tl = Animator(scene, box_home, AGENTS["male1"], fps=10,
                  standing={0: far, 1: far}).run(result)
    (grab,) = tl.attaches
    assert grab.node == 21 and grab.gap <= TOUCH
    cup = scene.mocap[21]
    start = tl.mocap[0][cup]
    assert all(np.array_equal(tl.mocap[f][cup], start) for f in range(grab.frame + 1))
    np.testing.assert_allclose(tl.mocap[grab.frame + 1][cup], start, atol=1e-9)  # no jump
    walked = tl.qpos[grab.frame][:2] - np.array(far)
    assert np.linalg.norm(walked) > 0.2  # it had to step closer


def test_a_spot_far_from_where_the_object_is_now_is_not_used(box_home):
    """Grounding's spots come from where things stood at the start: a spot 2.3 m from the
    cup (`SPOT_REACH` 1 m) is left, the agent walks to the cup itself; a near one is
    kept."""
    from homesim.render.animate import SPOT_REACH

    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(PROGRAM), box_home, trace=True,
                             reference=True)
    cup = to_mujoco(box_home.node(21))
    for spot, kept in (((-1.5, 0.0), False), ((0.2, -1.0), True)):
        tl = Animator(scene, box_home, AGENTS["male1"], fps=10,
                      standing={0: spot, 1: spot}).run(result)
        end = tl.qpos[tl.step_frames[0][1]][:2]
        assert (np.linalg.norm(end - np.array(spot)) < 0.06) == kept, (spot, end)
        assert np.linalg.norm(end - cup.center[:2]) < SPOT_REACH + 0.4


def test_drink_brings_the_cup_to_the_mouth(box_home):
    scene = build_scene(box_home, AGENTS["female1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(
        "[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Drink] <cup> (21)\n"), box_home, trace=True,
        reference=True)
    tl = Animator(scene, box_home, AGENTS["female1"], fps=10).run(result)
    drink = tl.interactions[-1]
    assert drink.step == 2
    d = mujoco.MjData(scene.model)
    d.qpos[:] = tl.qpos[drink.peak]
    mujoco.mj_kinematics(scene.model, d)
    head = d.site("j:head").xpos
    cup = tl.mocap[drink.peak][scene.mocap[21]]
    assert np.linalg.norm(cup - head) < 0.2
    assert cup[2] > head[2] - 0.2  # up at the face, not at the chest


def test_fridge_door_swings_with_the_hand_on_its_handle(animated):
    _, scene, tl = animated
    opening = next(it for it in tl.interactions if it.step == 5)
    hinge = scene.hinge_qpos[23]
    angles = [tl.qpos[f][hinge] for f in range(opening.start, opening.peak + 1)]
    assert angles[0] == 0.0 and abs(angles[-1] - scene.hinge_open[23]) < 1e-9
    assert len({round(a, 3) for a in angles}) > 5  # it swings over several frames


def _wrist_in_body(scene, q, side):
    d = mujoco.MjData(scene.model)
    d.qpos[:] = q
    mujoco.mj_kinematics(scene.model, d)
    root = scene.model.body("agent").id
    rot = d.xmat[root].reshape(3, 3)
    return rot.T @ (d.site(f"j:{side}_wrist").xpos - d.xpos[root])


def test_palm_grasp_brings_the_wrist_to_the_object_and_the_arm_never_snaps(animated):
    """The palm lies on the cup (the wrist joint within 2 cm of its box when it is taken)
    and the arm moves smoothly from the reach to carrying it and on to the put."""
    from homesim.render.interact import box_gap
    from homesim.render.layout import Box

    g, scene, tl = animated
    (grab,) = tl.attaches
    d = mujoco.MjData(scene.model)
    d.qpos[:] = tl.qpos[grab.frame]
    mujoco.mj_kinematics(scene.model, d)
    cup = Box(tl.mocap[grab.frame][scene.mocap[21]], to_mujoco(g.node(21)).half)
    assert box_gap(cup, d.site("j:r_wrist").xpos) <= 0.02
    assert box_gap(cup, d.site("r_palm").xpos) <= 0.01
    start, end = tl.step_frames[1][0], tl.step_frames[6][1]
    wrist = [_wrist_in_body(scene, tl.qpos[f], "r") for f in range(start, end + 1)]
    moves = np.linalg.norm(np.diff(wrist, axis=0), axis=1)
    # a snap is one frame's move far above both neighbours' (carrying used to snap in:
    # 0.38 m in one frame between still ones)
    spikes = moves[1:-1] - np.maximum(moves[:-2], moves[2:])
    assert spikes.max() < 0.06, spikes.max()


def test_a_front_never_swings_through_the_agent(box_home):
    """Sent to stand in the middle of the fridge door's sweep, the agent steps aside
    before it opens the door (the door used to pass through it: 0 m)."""
    from homesim.render.animate import BODY_CLEAR

    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(PROGRAM), box_home, trace=True,
                             reference=True)
    h = scene.layout.part(23).hinge
    half = scene.hinge_open[23] / 2
    c, s = np.cos(half), np.sin(half)
    p = h.panel.center[:2]
    middle = tuple(h.pivot[:2] + np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]]))
    tl = Animator(scene, box_home, AGENTS["male1"], fps=10,
                  standing={4: middle, 5: middle}).run(result)
    hinge = scene.hinge_qpos[23]

    def clearance(q):
        a = q[hinge]
        rel = q[:2] - h.pivot[:2]
        local = np.array([np.cos(a) * rel[0] + np.sin(a) * rel[1],
                          -np.sin(a) * rel[0] + np.cos(a) * rel[1]])
        return np.linalg.norm(np.maximum(np.abs(local - p) - h.panel.half[:2], 0.0))

    swinging = [f for f in range(1, len(tl)) if tl.qpos[f][hinge] != tl.qpos[f - 1][hinge]]
    assert len(swinging) > 10  # it opens and closes
    assert min(clearance(tl.qpos[f]) for f in swinging) >= BODY_CLEAR - 1e-6


def test_a_step_on_a_body_part_brings_the_held_tool_to_the_mouth():
    from homesim.render.animate import HEAD_RADIUS
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    d = box_home_dict()  # teeth as preparation adds them: a body part without a box
    d["nodes"].append({"id": 900, "class_name": "teeth", "category": "Props",
                       "properties": ["BODY_PART"]})
    d["edges"].append({"from_id": 900, "relation_type": "INSIDE", "to_id": 1})
    g = EnvironmentGraph.from_dict(d)
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    program = "[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Wash] <teeth> (900)"
    result = homesim.execute(homesim.parse_program(program), g, trace=True, reference=True)
    tl = Animator(scene, g, AGENTS["male1"], fps=10, seed=0).run(result)
    it = tl.interactions[-1]
    assert it.step == 2 and it.nodes == (21, 900)  # the tool first, then the body part
    data = mujoco.MjData(scene.model)
    data.qpos[:] = tl.qpos[it.peak]
    data.mocap_pos[:] = tl.mocap[it.peak]
    mujoco.mj_kinematics(scene.model, data)
    head = data.site("j:head").xpos
    cup = tl.mocap[it.peak][scene.mocap[21]]
    assert np.linalg.norm(cup - head) < 4 * HEAD_RADIUS * AGENTS["male1"].height


def test_water_rides_in_the_hand_and_is_gone_once_poured_into_a_held_cup():
    """Water is taken though not GRABBABLE (as the simulator lets it): it is drawn as a
    carried object, goes to the cup with the hand, and once poured is no longer drawn."""
    from homesim.render.props import POURED_AWAY
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    d = box_home_dict()
    d["nodes"].append({"id": 900, "class_name": "water", "category": "Props",
                       "properties": ["DRINKABLE", "POURABLE"],
                       "bounding_box": {"center": [0.85, 0.92, -0.85], "size": [0.07, 0.24, 0.07]}})
    d["edges"] += [{"from_id": 900, "relation_type": "INSIDE", "to_id": 1},
                   {"from_id": 900, "relation_type": "ON", "to_id": 20}]
    g = EnvironmentGraph.from_dict(d)
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    assert 900 in scene.mocap
    program = ("[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Grab] <water> (900)\n"
               "[Pour] <water> (900) <cup> (21)\n")
    result = homesim.execute(homesim.parse_program(program), g, trace=True, reference=True)
    assert result.executable
    tl = Animator(scene, g, AGENTS["male1"], fps=10, seed=0).run(result)
    grab, pour = tl.interactions[1], tl.interactions[2]
    at = [tl.mocap[f][scene.mocap[900]] for f in (0, grab.peak, pour.peak, pour.peak + 1)]
    cup = tl.mocap[pour.peak][scene.mocap[21]]
    assert np.linalg.norm(at[2] - at[1]) > 0.05  # carried to the cup
    assert np.linalg.norm(at[2] - cup) < 0.4
    assert at[3][2] == POURED_AWAY and tl.mocap[-1][scene.mocap[900]][2] == POURED_AWAY


def test_a_grab_is_filmed_in_the_room_where_the_object_lay():
    """The agent may stand in the next room's floor box when it takes something (a desk
    against the wall between): the grab happens in the room where the object lay, not
    the agent's (its close-up came from the wrong room's cameras, or none)."""
    from homesim.render.layout import Box
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    g = EnvironmentGraph.from_dict(box_home_dict())
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    program = "[Walk] <cup> (21)\n[Grab] <cup> (21)\n"
    result = homesim.execute(homesim.parse_program(program), g, trace=True, reference=True)
    anim = Animator(scene, g, AGENTS["male1"], fps=10, seed=0)
    tl = anim.run(result)
    (grab,) = tl.interactions
    assert grab.room == 1
    # a second room whose floor box holds where the agent stands, not the cup
    scene.layout.room_floors[99] = Box(np.r_[anim.pose.xy, 0.0], np.array([0.05, 0.05, 0.0]))
    anim.note_interaction((21,), "r", grab.start, grab.peak)
    assert tl.interactions[-1].room == 1
    anim.note_interaction((21,), "r", grab.peak + 1, grab.peak + 1)  # carried: the agent's
    assert tl.interactions[-1].room == 99


def test_put_back_goes_where_it_was_taken_from():
    """PutObjBack (or a put on what it was taken from) sets the object down where it lay,
    not somewhere across the table (inside a bookshelf, somewhere the body had to enter)."""
    scene, tl = _run("[Walk] <cup> (21)\n[Grab] <cup> (21)\n[PutObjBack] <cup> (21)\n")
    start, end = (tl.mocap[f][scene.mocap[21]] for f in (0, -1))
    assert tl.releases and np.allclose(start, end)
    moved = max(np.linalg.norm(m[scene.mocap[21]] - start) for m in tl.mocap)
    assert moved > 0.05  # it was carried meanwhile


def test_room_lamps_follow_their_rooms_light_switch(gl):
    """Switching a room's light off puts out its ceiling and wall lamps, frame by frame,
    and only those (scene1's bathroom switch)."""
    import homesim
    from homesim.render import animate
    from homesim.render.layout import render_kind

    run = homesim.run_program("[Walk] <lightswitch> (1)\n[SwitchOff] <lightswitch> (1)",
                              "scene1", trace=True)
    a = animate(run, width=32, height=24, fps=2, seed=0)
    graph, switch = run.graph, a.program.steps[1].args[0].node_id
    room = graph.room_of(switch)
    lamps = {p.node_id: graph.room_of(p.node_id) for p in a.scene.layout.parts
             if p.lamp and render_kind(p.class_name) == "room_lamp"}
    here = {n for n, r in lamps.items() if r == room}
    assert here and set(lamps) - here
    start, _ = a.timeline.step_frames[1]
    assert set(lamps) <= a.timeline.lamps[start]
    assert not here & a.timeline.lamps[-1] and set(lamps) - here <= a.timeline.lamps[-1]


def test_a_spot_behind_a_wall_from_its_object_is_not_used(box_home):
    """Grounding's floor model has no walls: a spot 0.4 m from the TV but behind the wall
    it stands at (gen-2: the keyboard of a desk against the next room's wall, reached with
    the head in the wall) is left; the agent walks to the TV on this side."""
    scene = build_scene(box_home, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program("[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n"),
                             box_home, trace=True, reference=True)
    for spot, kept in (((2.2, 1.0), False), ((1.2, 1.0), True)):
        tl = Animator(scene, box_home, AGENTS["male1"], fps=10,
                      standing={0: spot, 1: spot}).run(result)
        end = tl.qpos[tl.step_frames[0][1]][:2]
        assert (np.linalg.norm(end - np.array(spot)) < 0.06) == kept, (spot, end)
        assert end[0] < 1.95  # the room's side of the wall (inner face x = 1.95)


SOFA = {"id": 40, "class_name": "sofa", "category": "Furniture",
        "properties": ["SITTABLE", "SURFACES"],
        "bounding_box": {"center": [-1.5, 0.4, 0.2], "size": [0.85, 0.8, 2.0]}}


def _sit_on_the_sofa(things: list[dict], edges: list[tuple[int, str, int]]):
    """The box home with `SOFA` and `things` in room 1 (and `edges` besides): the agent
    walks to the sofa and sits; no body part more than 3 cm inside anything from getting
    down to standing up. Returns the timeline and the seated rest's frames."""
    from homesim.render.clearance import Clearance
    from homesim.render.recorder import SceneState
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    d = box_home_dict()
    d["nodes"] += [SOFA, *things]
    d["edges"] += [{"from_id": n["id"], "relation_type": "INSIDE", "to_id": 1}
                   for n in [SOFA, *things]]
    d["edges"] += [{"from_id": a, "relation_type": r, "to_id": b} for a, r, b in edges]
    g = EnvironmentGraph.from_dict(d)
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program("[Walk] <sofa> (40)\n[Sit] <sofa> (40)\n"),
                             g, trace=True, reference=True)
    tl = Animator(scene, g, AGENTS["male1"], fps=10).run(result)
    state, clear = SceneState(scene, tl, aim_cameras=False), Clearance(scene)
    (rest,) = tl.rests
    assert not any(clear.penetrations(state.apply(f), {}, 0.03) for f in range(rest[0], rest[1] + 1))
    return tl, rest


def test_sitting_moves_along_the_sofa_away_from_a_pillow():
    """A pillow lies on the sofa where the agent comes to it: it sits beside the pillow,
    along the seat (`SIT_ALONG`), not in it (the thighs 4-7 cm in pillows in gen-0, -3, -4
    and scene 1), on the way down and once seated."""
    pillow = {"id": 41, "class_name": "pillow", "category": "Props", "properties": ["GRABBABLE"],
              "bounding_box": {"center": [-1.4, 0.55, -0.3], "size": [0.45, 0.2, 0.45]}}
    tl, _ = _sit_on_the_sofa([pillow], [(41, "ON", 40)])
    assert tl.qpos[-1][2] < 0.7  # on the seat, not on the pillow


def test_sitting_where_the_floor_before_the_seat_is_free():
    """A coffee table stands 12 cm before most of the sofa, the agent comes to the sofa
    beside it: it walks round to where the floor before the seat is free and sits there
    (`Animator._sit_place`), not sliding sideways across the seat getting down (gen-1:
    up to 1 m, 16 parts 9-11 cm in the sofa)."""
    table = {"id": 42, "class_name": "coffeetable", "category": "Furniture",
             "properties": ["SURFACES"],
             "bounding_box": {"center": [-0.7, 0.2, -0.2], "size": [0.5, 0.4, 1.2]}}
    tl, rest = _sit_on_the_sofa([table], [])
    seated = tl.qpos[rest[1]][:2]
    assert seated[1] > 0.4  # beside the table, not behind it
    assert abs(tl.qpos[rest[0]][1] - seated[1]) < 0.1  # got down from before it, not beside


def test_put_back_on_a_high_shelf_is_done_the_way_it_was_taken():
    """A phone taken from a 1.6 m shelf is put back with the palm as it took it (the
    arm's reach with the phone in the hand fell 28 cm short, the body leaning into the
    wall behind: gen-1), so it is let go where it lay."""
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    d = box_home_dict()
    d["nodes"] += [
        {"id": 43, "class_name": "cellphone", "category": "Electronics",
         "properties": ["GRABBABLE"],
         "bounding_box": {"center": [1.0, 1.6, 1.85], "size": [0.13, 0.01, 0.07]}},
        {"id": 44, "class_name": "bookshelf", "category": "Furniture",
         "properties": ["SURFACES"],
         "bounding_box": {"center": [1.0, 0.7975, 1.8], "size": [1.0, 1.595, 0.3]}}]
    d["edges"] += [{"from_id": 43, "relation_type": "INSIDE", "to_id": 1},
                   {"from_id": 44, "relation_type": "INSIDE", "to_id": 1},
                   {"from_id": 43, "relation_type": "ON", "to_id": 44}]
    g = EnvironmentGraph.from_dict(d)
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program(
        "[Walk] <cellphone> (43)\n[Grab] <cellphone> (43)\n[PutObjBack] <cellphone> (43)\n"),
        g, trace=True, reference=True)
    tl = Animator(scene, g, AGENTS["male1"], fps=10).run(result)
    (took,), (put,) = tl.attaches, tl.releases
    assert took.gap <= 0.01 and put.gap <= 0.01  # let go where the hand brought it


def test_a_carried_object_keeps_the_wrist_it_was_taken_with(animated):
    """The carry pose keeps the wrist's turn of the grasp (a glass taken from the side
    came back over the straightened wrist, the forearm 3 cm inside it: scene 1, #340)."""
    from homesim.render.ik import wrist_joints

    _, scene, tl = animated
    grab = tl.attaches[0]
    names = [scene.joint_qpos[j] for j in wrist_joints(grab.side)]
    taken = tl.qpos[grab.frame][names]
    assert np.any(np.abs(taken) > 1e-3)  # the grasp turned the wrist
    for f in range(grab.frame + 1, tl.step_frames[6][0], 5):  # carried to the fridge
        np.testing.assert_allclose(tl.qpos[f][names], taken, atol=1e-9)


def test_washing_the_hands_brings_the_other_hand_before_the_body():
    """Wash the hands: the free arm comes before the belly (not hanging into a wall beside
    the sink: gen-4's bathroom) and the other hand goes to it; then it hangs again."""
    from homesim.render.poses import SPARE
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict

    d = box_home_dict()
    d["nodes"].append({"id": 900, "class_name": "hands_both", "category": "Props",
                       "properties": ["BODY_PART"]})
    d["edges"] += [{"from_id": 900, "relation_type": "INSIDE", "to_id": 1},
                   {"from_id": 10, "relation_type": "CLOSE", "to_id": 900},
                   {"from_id": 900, "relation_type": "CLOSE", "to_id": 10}]
    g = EnvironmentGraph.from_dict(d)
    scene = build_scene(g, AGENTS["male1"], max_size=(64, 48))
    result = homesim.execute(homesim.parse_program("[Wash] <hands_both> (900)"), g,
                             trace=True, reference=True)
    tl = Animator(scene, g, AGENTS["male1"], fps=10, seed=0).run(result)
    it = tl.interactions[-1]
    assert it.side == "r" and it.nodes == (900,)
    elbow = scene.joint_qpos["l_elbow"]
    assert tl.qpos[it.peak][elbow] == pytest.approx(SPARE[0]["elbow"])
    assert tl.qpos[-1][elbow] == pytest.approx(tl.qpos[0][elbow])
    data = mujoco.MjData(scene.model)
    data.qpos[:] = tl.qpos[it.peak]
    mujoco.mj_kinematics(scene.model, data)
    left, right = data.site("l_palm").xpos, data.site("r_palm").xpos
    assert np.linalg.norm(left - right) < 0.12
