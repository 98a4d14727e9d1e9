"""Bodies and close-ups on real programs in built-in and generated homes (issue 43).

The programs and homes are fixed by seed in `_look_sets.py` (chosen before any tuning):
`--set dev` (looked at while tuning), `--set fresh` or `--set fresh2` (only measured). Each
program is run as `homesim render` runs it (`homesim.run_program`: prepared, grounded,
executed; then animated with grounding's standing spots and its close-ups planned). Printed
per home and in total:

(a) interpenetration: agent body parts (head, torso, forearm...: agent bodies) more than
    3 cm inside any object's geom (its oriented box as posed; `homesim.render.clearance`)
    at every effect frame (the frame a hand arrives: grab, put, switch, swing) and
    through every Sit and Lie (from getting down onto the seat or bed to the end of the
    step: `Timeline.rests`; the walk there is not counted), leaving out a hand inside
    what it holds or acts on then (goal 0);
(b) close-ups: interaction steps whose object covers >= 0.5 % of the frame at the effect
    and where the agent's body covers <= 40 % of it, drawn from the camera the recording
    uses then (the step's close-up, else the room camera the director picks), and whether
    the hand shows (goal >= 95 % on the fresh set); a step on a part of the body (wash the
    teeth) counts its tool, or, with none, only the body rule;
(c) the largest distance between the wrist joint and a grabbed object's box when it is
    taken (goal <= 2 cm).

No timing here (geometry and framing). Set MUJOCO_GL=osmesa on a machine without a GPU.

    python benchmarks/look.py --set dev [--programs 20] [--homes scene1 gen-0]
                              [--no-closeups] [--width 320 --height 240] [--seed 0]
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict

import numpy as np

import homesim
from _look_sets import HOMES, program_sets
from homesim.render.api import animate
from homesim.render.clearance import Clearance
from homesim.render.director import Director
from homesim.render.interact import box_gap
from homesim.render.layout import Box, to_mujoco
from homesim.render.recorder import SceneState, aimed_score, focus_per_frame, shot_camera
from homesim.render.renderer import Renderer
from homesim.render.shots import _arm_bodies

DEPTH = 0.03
COVER = 0.005
BODY_MAX = 0.40
WRIST = 0.02


def held_per_frame(tl) -> list[dict[str, set[int]]]:
    """Per frame, per hand, the nodes it holds (from the timeline's takes and puts)."""
    out: list[dict[str, set[int]]] = [defaultdict(set) for _ in range(len(tl))]
    events = sorted([(a.frame, 0, a) for a in tl.attaches]
                    + [(r.frame, 1, r) for r in tl.releases], key=lambda e: (e[0], e[1]))
    holding: dict[int, tuple[str, int]] = {}
    for frame, kind, ev in events:
        if kind == 0:
            holding[ev.node] = (ev.side, frame + 1)
        elif ev.node in holding:
            side, first = holding.pop(ev.node)
            for f in range(first, ev.frame + 1):
                out[f][side].add(ev.node)
    for node, (side, first) in holding.items():
        for f in range(first, len(tl)):
            out[f][side].add(node)
    return out


def interpenetration(scene, tl, steps) -> list[tuple[int, str, str, float]]:
    """(step, part, object class, depth) of every body part deeper than `DEPTH` inside an
    object at an effect frame or during Sit / Lie."""
    clear = Clearance(scene)
    state = SceneState(scene, tl, aim_cameras=False)
    held = held_per_frame(tl)
    frames: dict[int, tuple[int, dict[str, set[int]]]] = {}
    starts = [a for a, _ in tl.step_frames]
    for a, b in _rests(tl, steps):  # getting down onto the seat or bed, and staying there
        step = int(np.searchsorted(starts, a, side="right")) - 1
        for f in range(a, b + 1):
            frames.setdefault(f, (step, {s: set(n) for s, n in held[f].items()}))
    for it in tl.interactions:
        allowed = {s: set(n) for s, n in held[it.peak].items()}
        allowed.setdefault(it.side, set()).update(it.nodes)
        frames[it.peak] = (it.step, allowed)
    out = []
    names = {p.node_id: p.class_name for p in scene.layout.parts}
    for f, (step, allowed) in sorted(frames.items()):
        d = state.apply(f)
        for p in clear.penetrations(d, allowed, DEPTH):
            out.append((step, p.part, names.get(p.node, str(p.node)), p.depth))
    return out


def _rests(tl, steps) -> list[tuple[int, int]]:
    """The timeline's sit and lie frames; for code before `Timeline.rests` (issue 43),
    each Sit or Lie step from the frame its pelvis starts to go down."""
    if hasattr(tl, "rests"):
        return tl.rests
    from homesim.program.actions import ACTIONS

    out = []
    for i, (a, b) in enumerate(tl.step_frames):
        if ACTIONS[steps[i].action.key].motion in ("sit", "lie"):
            z = np.array([q[2] for q in tl.qpos[a:b + 1]])
            down = np.flatnonzero(z < z[0] - 0.05)
            out.append((a + int(down[0]) if len(down) else b, b))
    return out


def closeups(scene, tl, steps, graph, width: int, height: int) -> list[dict]:
    """Per interaction: object share, body share and whether the hand shows at the effect,
    from the camera the recording uses then."""
    out = []
    state = SceneState(scene, tl)
    focus = focus_per_frame(tl)
    body = scene.model.body("agent").id
    with Renderer(scene, width, height) as r:
        for it in tl.interactions:
            d = state.apply(it.peak)
            cam = shot_camera(scene, tl, it.peak)
            shot = cam is not None
            if cam is None:
                cam = Director(scene).choose(d.xpos[body].copy(), None, lambda c, f=focus[
                    it.peak]: aimed_score(state, r, scene, c, f))
                d = state.apply(it.peak)
            ids, _ = r.ids_depth(d, cam)
            nodes = np.where(ids >= 0, scene.geom_node[np.maximum(ids, 0)], 0)
            obj = it.nodes[0]
            drawn = bool(np.any(scene.geom_node == obj))
            share = float(np.count_nonzero(nodes == obj)) / ids.size if drawn else None
            agent = float(np.count_nonzero(nodes == scene.character_id)) / ids.size
            out.append({"step": steps[it.step].action.key, "object": graph.node(obj).class_name,
                        "share": share, "body": agent, "shot": shot,
                        "hand": _hand_seen(scene, r, d, cam, ids, it.side)})
    return out


def _hand_seen(scene, renderer, d, cam, ids, side) -> bool:
    from homesim.render.flow import project, world_to_cam
    from homesim.render.recorder import camera_intrinsics

    h, w = ids.shape
    k = camera_intrinsics(scene, cam, w, h)
    uv, z = project(d.site_xpos[scene.hand_sites[side]][None], k,
                    world_to_cam(d.cam_xpos[cam], d.cam_xmat[cam]))
    u, v = np.round(uv[0]).astype(int)
    if z[0] <= 0 or not (0 <= u < w and 0 <= v < h):
        return False
    # the hand's site lies inside the palm: a pixel of the hand (or what it holds) there
    window = ids[max(v - 2, 0):v + 3, max(u - 2, 0):u + 3]
    arm = _arm_bodies(scene, side)
    return bool(np.any([int(scene.model.geom_bodyid[g]) in arm for g in window[window >= 0]]))


def wrist_gaps(scene, tl, graph) -> list[tuple[float, str]]:
    """(wrist-to-box distance, what) of each object taken, when it is taken."""
    state = SceneState(scene, tl, aim_cameras=False)
    out = []
    for a in tl.attaches:
        d = state.apply(a.frame)
        box = to_mujoco(graph.node(a.node))
        if a.node in scene.mocap:
            box = Box(tl.mocap[a.frame][scene.mocap[a.node]], box.half)
        what = (f"{graph.node(a.node).class_name} (palm {a.gap * 100:.1f} cm, box "
                f"{np.round(2 * box.half * 100).astype(int).tolist()} cm)")
        out.append((box_gap(box, d.site(f"j:{a.side}_wrist").xpos), what))
    return out


def measure(text: str, home: str, args) -> dict | None:
    ran = homesim.run_program(text, home, seed=args.seed, trace=True)
    if not ran.executable or ran.grounding is None or ran.graph is None:
        return None
    steps = ran.result.program.steps
    anim = animate(ran, width=args.width, height=args.height, fps=15, seed=args.seed)
    scene, tl = anim.scene, anim.timeline
    out = {"pen": interpenetration(scene, tl, steps), "wrist": wrist_gaps(scene, tl, ran.graph),
           "close": []}
    if not args.no_closeups:
        out["close"] = closeups(scene, tl, steps, ran.graph, args.width, args.height)
    return out


def _by_part(pen: list[tuple]) -> dict[tuple, float]:
    """(program, step, part, object class) -> the deepest of its frames."""
    out: dict[tuple, float] = {}
    for k, step, part, cls, depth in pen:
        out[(k, step, part, cls)] = max(out.get((k, step, part, cls), 0.0), depth)
    return out


def _good(c: dict) -> bool:
    return (c["share"] is None or c["share"] >= COVER) and c["body"] <= BODY_MAX


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", choices=tuple(HOMES), default="dev")
    ap.add_argument("--programs", type=int, default=20)
    ap.add_argument("--homes", nargs="+", default=None)
    ap.add_argument("--no-closeups", action="store_true")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--show", type=int, default=12, help="offenders listed per home")
    ap.add_argument("--only", type=int, nargs="+", default=None,
                    help="only these programs (indices into the fetched programs)")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    args = ap.parse_args()
    programs = program_sets()[args.set][:args.programs]
    if args.only:
        programs = [(k, t) for k, t in programs if k in args.only]
    homes = args.homes or HOMES[args.set]
    pen, close, wrist, ran, failed = [], [], [], 0, 0
    for home in homes:
        h_pen, h_close, h_wrist, h_ran, h_far = [], [], [], 0, []
        for k, text in programs:
            m = measure(text, home, args)
            if m is None:
                failed += 1
                continue
            h_ran += 1
            h_pen += [(k, *p) for p in m["pen"]]
            h_close += [dict(c, program=k) for c in m["close"]]
            h_wrist += [w for w, _ in m["wrist"]]
            h_far += [f"#{k} {what}: {w * 100:.1f} cm" for w, what in m["wrist"] if w > WRIST]
        good = sum(_good(c) for c in h_close)
        parts = _by_part(h_pen)
        print(f"{home}: programs run {h_ran}/{len(programs)}; parts > 3 cm inside objects "
              f"{len(parts)} ({len(h_pen)} part-frames); close-ups good {good}/{len(h_close)}; "
              f"largest wrist gap {max(h_wrist, default=0) * 100:.2f} cm", flush=True)
        for (k, step, part, cls), depth in list(parts.items())[:args.show]:
            print(f"    #{k} step {step + 1}: {part} {depth * 100:.1f} cm inside {cls}")
        for far in h_far:
            print(f"    wrist: {far}")
        for c in h_close:
            if not _good(c):
                share = "-" if c["share"] is None else f"{c['share'] * 100:.2f} %"
                print(f"    #{c['program']} {c['step']} {c['object']}: object {share}, body "
                      f"{c['body'] * 100:.0f} %, hand {'seen' if c['hand'] else 'hidden'}"
                      f"{'' if c['shot'] else ', no close-up'}")
        pen += h_pen
        close += h_close
        wrist += h_wrist
        ran += h_ran
    w = np.array(wrist) if wrist else np.zeros(1)
    print(f"\nset {args.set}: {len(programs)} programs x {len(homes)} homes, {ran} runs "
          f"({failed} not executable)")
    print(f"(a) body parts > 3 cm inside objects at effect frames and in Sit/Lie: "
          f"{len(_by_part(pen))} parts of steps, {len(pen)} part-frames (goal 0)"
          + (f"; deepest {max(p[4] for p in pen) * 100:.1f} cm" if pen else ""))
    if close:
        good = np.mean([_good(c) for c in close]) * 100
        obj = np.mean([c["share"] is None or c["share"] >= COVER for c in close]) * 100
        body = np.mean([c["body"] <= BODY_MAX for c in close]) * 100
        hand = np.mean([c["hand"] for c in close]) * 100
        shots = np.mean([c["shot"] for c in close]) * 100
        print(f"(b) interaction steps {len(close)}: object >= 0.5 % and body <= 40 %: "
              f"{good:.1f} % (goal >= 95 %); object >= 0.5 %: {obj:.1f} %; body <= 40 %: "
              f"{body:.1f} %; hand seen {hand:.1f} %; filmed by a close-up {shots:.1f} %")
    print(f"(c) grabs {len(wrist)}: largest wrist-to-object distance {w.max() * 100:.2f} cm "
          f"(goal <= 2 cm), over 2 cm: {int((w > WRIST).sum())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
