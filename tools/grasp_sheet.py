"""Close-ups of grasps: each grab of the first real programs with a Grab, at the frame the
object is taken, seen from beside the hand (issue 13, "interactions that touch").

    python tools/grasp_sheet.py [--programs 8] [--out docs/render/grasps.png] [--size 320]
                                [--only K ...]

Programs are run as `benchmarks/interactions.py` runs them (prepared and grounded in
scene1..scene5 in turn, seed 0). Every grab gives two views from a free camera 0.55 m from
the object (from the agent's side and from the hand's outer side), labelled with the
program, the class and the wrist joint's distance to the object's box. The per-grab figures
are printed too.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from homesim.render import contact_sheet
from homesim.render.api import animate
from homesim.render.gl import mujoco
from homesim.render.interact import box_gap
from homesim.render.layout import Box
from homesim.render.recorder import SceneState

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "render" / "grasps.png"
sys.path.insert(0, str(ROOT / "benchmarks"))
from interactions import attach_box, grab_programs  # noqa: E402  (the benchmark's own choice)


def views(scene, data, box: Box, wrist: np.ndarray, size: int) -> list[np.ndarray]:
    """Two close-ups of the object and the hand: from the agent's side, from outside."""
    root = data.qpos[:2]
    toward = math.degrees(math.atan2(box.center[1] - root[1], box.center[0] - root[0]))
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = 0.5 * (box.center + wrist)
    cam.distance = 0.55
    cam.elevation = -25.0
    opt = mujoco.MjvOption()
    out = []
    vis = scene.model.vis.global_
    vis.offwidth, vis.offheight = max(vis.offwidth, size), max(vis.offheight, size)
    with mujoco.Renderer(scene.model, size * 3 // 4, size) as r:
        for az in (toward + 150.0, toward - 90.0):
            cam.azimuth = az
            r.update_scene(data, cam, opt)
            out.append(r.render().copy())
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--programs", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--size", type=int, default=320)
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--only", type=int, nargs="*", help="real program indices to draw")
    args = ap.parse_args()
    frames = []
    for k, _, home, ran in grab_programs(args.programs, args.seed):
        if args.only and k not in args.only:
            continue
        g = ran.graph
        animation = animate(ran, width=64, height=48, fps=15, seed=args.seed)
        scene, tl = animation.scene, animation.timeline
        state = SceneState(scene, tl)
        for a in tl.attaches:
            d = state.apply(a.frame)
            box = attach_box(g, scene, tl, a)
            wrist = d.site(f"j:{a.side}_wrist").xpos.copy()
            gap = box_gap(box, wrist)
            cls = g.node(a.node).class_name
            print(f"#{k} {home} {cls} ({a.node}) {a.side}: palm {a.gap * 100:.1f} cm, "
                  f"wrist {gap * 100:.1f} cm, box half {np.round(box.half, 3)}", flush=True)
            for v in views(scene, d, box, wrist, args.size):
                frames.append((f"#{k} {home} {cls} wrist {gap * 100:.1f} cm", v))
    path = contact_sheet(frames, args.out, columns=4,
                         title="Grasps at the frame the object is taken (two views each)")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
