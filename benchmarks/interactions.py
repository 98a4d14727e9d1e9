"""Interactions that touch, and cameras that show them, on real programs (issue 13).

Each real program with a Grab (the fetched ActivityPrograms, `homesim data fetch`) is run
as `homesim render` runs it: prepared and grounded in a built-in home (scene1..scene5 in
turn), executed, animated with grounding's standing spots (`homesim.render.animate`).
Printed:

(a) the largest distance between the wrist joint (the ``j:{side}_wrist`` keypoint, the
    heel of the hand) and the grabbed object's box at the frame it is taken (goal <= 2 cm;
    the palm lies on the object, `homesim.render.interact.palm_grasp`; the object does not
    move before: it rides from where the hand touched it), the palm's contact point's
    distance then, and the largest distance a put object moves when let go;
(b) the share of interaction steps (hands on an object: reach, use_held and let_go
    motions) whose object covers >= 0.5 % of the frame at the step's effect (the frame
    the hand arrives), drawn from the close-up the recording uses then (goal >= 90 %; a
    step that no candidate close-up shows has none and counts as not covered);
(c) for Drink / Eat: the largest distance between the held object's box and the mouth.

There is no timing here (figures of geometry and framing, not of speed); the issue's
own figures before this work: the hand 16 cm from scene 3's cup when it was taken, the
cup jumping 22 cm into it.

    python benchmarks/interactions.py [--programs 20] [--seed 0] [--width 320 --height 240]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

import homesim
from _real_programs import ungrounded_texts
from homesim.render.api import animate
from homesim.render.interact import box_gap
from homesim.render.layout import Box, to_mujoco
from homesim.render.recorder import SceneState, shot_camera
from homesim.render.renderer import Renderer

HOMES = ("scene1", "scene2", "scene3", "scene4", "scene5")
COVER = 0.005
MOUTH_ACTIONS = ("DRINK", "EAT")


def grab_programs(count: int, seed: int):
    """(text, home, Run) of the first `count` real programs with a Grab that run."""
    out = []
    for k, text in enumerate(ungrounded_texts()):
        if "[Grab]" not in text:
            continue
        home = HOMES[len(out) % len(HOMES)]
        ran = homesim.run_program(text, home, seed=seed, trace=True)
        if ran.executable and ran.grounding is not None:
            out.append((k, text, home, ran))
        if len(out) == count:
            break
    return out


def attach_box(graph, scene, tl, attach) -> Box:
    """The grabbed object's box at the frame it is taken (a movable object where it is
    then)."""
    box = to_mujoco(graph.node(attach.node))
    if attach.node in scene.mocap:
        box = Box(tl.mocap[attach.frame][scene.mocap[attach.node]], box.half)
    return box


def mouth_gap(scene, d, obj: int, half: np.ndarray, height: float) -> float:
    """Distance from the mouth (front of the head, a little below its centre) to the box
    of a held object."""
    head = d.site("j:head").xpos
    fwd = d.xmat[scene.model.body("a:head").id].reshape(3, 3)[:, 0]
    r = 0.065 * height
    mouth = head + 0.9 * r * fwd - np.array([0, 0, 0.45 * r])
    return box_gap(Box(d.mocap_pos[scene.mocap[obj]].copy(), half), mouth)


def measure(ran, home: str, seed: int, width: int, height: int) -> dict:
    g = ran.graph
    animation = animate(ran, width=width, height=height, fps=15, seed=seed)
    scene, tl, name = animation.scene, animation.timeline, animation.agent
    from homesim.render.agent import AGENTS

    out = {"attach": [a.gap for a in tl.attaches], "release": [r.gap for r in tl.releases],
           "cover": [], "mouth": [], "rooms_ok": 0, "shots": 0, "wrist": [], "missed": []}
    state = SceneState(scene, tl)
    for a in tl.attaches:  # the wrist joint (the hand's grip point lies beyond it)
        d = state.apply(a.frame)
        out["wrist"].append(box_gap(attach_box(g, scene, tl, a), d.site(f"j:{a.side}_wrist").xpos))
    steps = ran.grounding.program.steps
    with Renderer(scene, width, height) as r:
        for it in tl.interactions:
            d = state.apply(it.peak)
            cam = shot_camera(scene, tl, it.peak)
            key = steps[it.step].action.key
            if cam is None:  # no close-up shows it: counted as not covered
                out["cover"].append(0.0)
                out["missed"].append(f"{key} {g.node(it.nodes[0]).class_name} no close-up")
                continue
            out["shots"] += 1
            out["rooms_ok"] += scene.cameras[cam].room_id == it.room
            ids, _ = r.ids_depth(d, cam)
            nodes = scene.geom_node[ids[ids >= 0]]
            out["cover"].append(float(np.count_nonzero(nodes == it.nodes[0])) / ids.size)
            if out["cover"][-1] < COVER:
                out["missed"].append(f"{key} {g.node(it.nodes[0]).class_name} "
                                     f"{out['cover'][-1] * 100:.2f} %")
            if key in MOUTH_ACTIONS and it.nodes[0] in scene.mocap:
                half = to_mujoco(g.node(it.nodes[0])).half
                out["mouth"].append(mouth_gap(scene, d, it.nodes[0], half,
                                              AGENTS[name].height))
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--programs", type=int, default=20)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    args = ap.parse_args()
    attach, release, cover, mouth, wrist, rooms, shots = [], [], [], [], [], 0, 0
    for k, _text, home, ran in grab_programs(args.programs, args.seed):
        m = measure(ran, home, args.seed, args.width, args.height)
        attach += m["attach"]
        wrist += m["wrist"]
        release += m["release"]
        cover += m["cover"]
        mouth += m["mouth"]
        rooms += m["rooms_ok"]
        shots += m["shots"]
        print(f"real program #{k} in {home}: grabs {len(m['attach'])}, largest wrist-object "
              f"gap {max(m['wrist'], default=0) * 100:.1f} cm (palm "
              f"{max(m['attach'], default=0) * 100:.1f} cm); interactions "
              f"{len(m['cover'])}, covered >= 0.5 %: "
              f"{sum(c >= COVER for c in m['cover'])}"
              + (f" (under: {'; '.join(m['missed'])})" if m["missed"] else ""), flush=True)
    a = np.array(attach)
    w = np.array(wrist)
    c = np.array(cover)
    print(f"\n(a) grabs: {len(w)}; largest wrist-to-object distance at attach "
          f"{w.max() * 100:.2f} cm (goal <= 2 cm; median {np.median(w) * 100:.2f} cm); "
          f"over 2 cm: {int((w > 0.02).sum())}; the palm's contact point then: largest "
          f"{a.max() * 100:.2f} cm, median {np.median(a) * 100:.2f} cm")
    if release:
        print(f"    puts: {len(release)}; largest move of a put object when let go "
              f"{max(release) * 100:.2f} cm")
    print(f"(b) interaction steps: {len(c)}; object covers >= 0.5 % of the frame at the "
          f"effect: {(c >= COVER).mean() * 100:.1f} % (goal >= 90 %); median cover "
          f"{np.median(c) * 100:.2f} %; close-ups {shots} (in the step's room: {rooms}); "
          f"steps no candidate close-up showed (filmed by the room camera, counted as not "
          f"covered): {len(c) - shots}")
    if mouth:
        print(f"(c) drink/eat: {len(mouth)}; largest object-to-mouth distance "
              f"{max(mouth) * 100:.1f} cm")
    return 0


if __name__ == "__main__":
    sys.exit(main())
