"""Rendering throughput: frames/s at 640x480 with all ground truth, on the demo program.

Times the recording loop of `render_program` (colour video, depth, class and instance
segmentation, optical flow, 2D/3D joints, cameras, files written) after the scene is
built and the program animated, and, in the same run, the reference: MuJoCo's own
`mujoco.Renderer` drawing only RGB of the same frames from the same cameras.

Goals (issue 5): >= 10 frames/s on CPU (OSMesa); >= 300 frames/s on a GPU (EGL).

    python benchmarks/render.py [--frames 300] [--width 640 --height 480]
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
from pathlib import Path

import homesim
from homesim.examples import DEMO_HOME, load_example
from homesim.render.api import animate
from homesim.render.gl import BACKEND, mujoco
from homesim.render.groundtruth import RecordingWriter
from homesim.render.recorder import SceneState, record
from homesim.render.renderer import Renderer

GOALS = {"osmesa": 10.0, "egl": 300.0}


def gl_renderer_name() -> str:
    try:
        from OpenGL import GL

        return GL.glGetString(GL.GL_RENDERER).decode()
    except Exception:  # only a label for the report
        return "?"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--shadows", action="store_true",
                        help="also time the recording with the room light's shadows (OSMesa "
                             "records without them: one more pass over the scene per frame)")
    args = parser.parse_args()
    w, h = args.width, args.height
    load0 = os.getloadavg()[0]
    graph = homesim.load_home(DEMO_HOME)
    t0 = time.perf_counter()
    run = homesim.run_program(load_example("watch_tv"), graph, trace=True)
    animation = animate(run, width=w, height=h, fps=30, seed=0)
    scene, timeline = animation.scene, animation.timeline
    setup = time.perf_counter() - t0
    n = min(args.frames, len(timeline))
    timeline.qpos, timeline.mocap = timeline.qpos[:n], timeline.mocap[:n]
    timeline.lamps, timeline.screens = timeline.lamps[:n], timeline.screens[:n]

    def recording(shadows: bool | None) -> tuple[float, list[int]]:
        with tempfile.TemporaryDirectory() as tmp, Renderer(scene, w, h, shadows) as renderer:
            writer = RecordingWriter(Path(tmp) / "rec", w, h, 30)
            t0 = time.perf_counter()
            cameras = []
            for truth in record(scene, timeline, renderer):
                writer.add(truth)
                cameras.append(truth.camera)
            writer.close({"benchmark": True})
            return n / (time.perf_counter() - t0), cameras

    ours, cameras = recording(None)
    shadowed = recording(True)[0] if args.shadows else None
    gl_name = gl_renderer_name()

    # Reference: mujoco.Renderer, RGB only, same frames and cameras.
    state = SceneState(scene, timeline)
    ref_renderer = mujoco.Renderer(scene.model, h, w)
    t0 = time.perf_counter()
    for i in range(n):
        data = state.apply(i)
        ref_renderer.update_scene(data, cameras[i])
        ref_renderer.render()
    ref = n / (time.perf_counter() - t0)
    ref_renderer.close()

    goal = GOALS.get(BACKEND, GOALS["osmesa"])
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KiB on Linux
    print(f"machine: {os.cpu_count()} CPUs, load average {load0:.1f} before, "
          f"{os.getloadavg()[0]:.1f} after; peak RSS {rss:.0f} MiB (goal <= 1024); "
          f"scene: {scene.model.ngeom} geoms, {scene.model.ntex} textures, "
          f"{scene.model.nlight} lights")
    print(f"backend MUJOCO_GL={BACKEND} ({gl_name}); {w}x{h}; {n} frames of the demo "
          f"(setup: scene + animation {setup:.1f} s, not timed)")
    print(f"{'':<44} {'frames/s':>9}")
    print(f"{'homesim, all ground truth, files written':<44} {ours:>9.1f}")
    if shadowed is not None:
        print(f"{'... with the room light casting shadows':<44} {shadowed:>9.1f}")
    print(f"{'reference: mujoco.Renderer, RGB only':<44} {ref:>9.1f}")
    print(f"ratio to reference: {ours / ref:.2f}x; ratio to goal ({goal:g} frames/s): "
          f"{ours / goal:.2f}x -> {'MET' if ours >= goal else 'NOT MET'}")


if __name__ == "__main__":
    main()
