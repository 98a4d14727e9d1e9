"""Do the close-ups of switching a screen on or off show the screen? (render upkeep)

Real programs that switch a television or a computer screen on or off (the fetched
ActivityPrograms, `homesim data fetch`) are run as `homesim render` runs them: prepared
and grounded in a built-in home (scene1..scene5 in turn), executed and animated with
grounding's standing spots. For every hands-on step whose object has a screen, the frame
of the effect is drawn from the camera the recording uses then, and the share of the image
the *screen* covers is measured (the panel that lights up; the back of the set does not
count), beside the share the whole object covers.

Printed per step and in total: the share of screen steps whose screen covers >= 0.5 % of
the frame (the interactions benchmark's "covered"), the median screen share, and the
median object share. No timing here.

    python benchmarks/screen_closeups.py [--programs 30] [--seed 0]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

import homesim
from _real_programs import ungrounded_texts
from homesim.render.api import animate
from homesim.render.recorder import SceneState, shot_camera
from homesim.render.renderer import Renderer

HOMES = ("scene1", "scene2", "scene3", "scene4", "scene5")
COVER = 0.005
SCREENS = ("television", "computer", "cpuscreen", "tv", "laptop")
SWITCHES = ("[SwitchOn]", "[SwitchOff]")


def screen_programs(count: int, seed: int):
    """(index, home, Run) of the first `count` real programs that switch a screen and run."""
    out = []
    for k, text in enumerate(ungrounded_texts()):
        lines = [ln for ln in text.splitlines() if ln.startswith(SWITCHES)]
        if not any(f"<{s}>" in ln for ln in lines for s in SCREENS):
            continue
        home = HOMES[len(out) % len(HOMES)]
        ran = homesim.run_program(text, home, seed=seed, trace=True)
        if ran.executable and ran.grounding is not None:
            out.append((k, home, ran))
        if len(out) == count:
            break
    return out


def measure(ran, seed: int, width: int, height: int) -> list[tuple[str, float, float]]:
    """(step, screen share, object share) of each hands-on step on a node with a screen."""
    animation = animate(ran, width=width, height=height, fps=15, seed=seed)
    scene, tl = animation.scene, animation.timeline
    state = SceneState(scene, tl)
    steps = ran.grounding.program.steps
    out = []
    with Renderer(scene, width, height) as r:
        for it in tl.interactions:
            screen = scene.screen_geom.get(it.nodes[0])
            if screen is None:
                continue
            d = state.apply(it.peak)
            cam = shot_camera(scene, tl, it.peak)
            label = str(steps[it.step])
            if cam is None:
                out.append((f"{label} (no close-up)", 0.0, 0.0))
                continue
            ids, _ = r.ids_depth(d, cam)
            nodes = np.where(ids >= 0, scene.geom_node[np.maximum(ids, 0)], -1)
            out.append((label, float(np.count_nonzero(ids == screen)) / ids.size,
                        float(np.count_nonzero(nodes == it.nodes[0])) / ids.size))
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--programs", type=int, default=30)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    args = ap.parse_args()
    rows = []
    for k, home, ran in screen_programs(args.programs, args.seed):
        for label, screen, whole in measure(ran, args.seed, args.width, args.height):
            rows.append((screen, whole))
            print(f"real program #{k} in {home}: {label}: screen {screen * 100:.2f} %, "
                  f"object {whole * 100:.2f} %", flush=True)
    s = np.array([r[0] for r in rows])
    o = np.array([r[1] for r in rows])
    print(f"\nscreen steps: {len(s)}; screen covers >= 0.5 % of the frame at the effect: "
          f"{(s >= COVER).mean() * 100:.1f} %; median screen share {np.median(s) * 100:.2f} %;"
          f" object covers >= 0.5 %: {(o >= COVER).mean() * 100:.1f} %, median "
          f"{np.median(o) * 100:.2f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
