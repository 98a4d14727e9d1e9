"""The public calls: render a program to a recording folder, or to key frames."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from homesim.errors import HomesimError, LimitError
from homesim.limits import MAX_VIDEO_PIXEL_FRAMES
from homesim.program.bindings import Bindings
from homesim.program.model import Program
from homesim.render.agent import AGENTS, agent_shape
from homesim.render.animate import Animator, Timeline
from homesim.render.groundtruth import RecordingWriter, StepSpan
from homesim.render.recorder import iter_still_frames, record
from homesim.render.renderer import Renderer
from homesim.render.scene import SceneModel, build_scene
from homesim.render.shots import plan_shots
from homesim.render.video import H264Writer, check_size
from homesim.sim.execute import execute
from homesim.world.graph import EnvironmentGraph

Progress = Callable[[int, int], None]
"""Called as ``progress(frames_done, frames_total)``."""


@dataclass(frozen=True)
class RenderResult:
    """What `render_program` wrote."""

    out_dir: Path
    num_frames: int
    width: int
    height: int
    fps: int
    agent: str
    steps: list[StepSpan]
    seconds: float  # wall time of the whole call

    @property
    def video(self) -> Path:
        return self.out_dir / "video.mp4"


def _check_length(frames: int, width: int, height: int,
                  limit: tuple[int, str] | None = None) -> None:
    """Refuse a recording over `MAX_VIDEO_PIXEL_FRAMES` (or `limit`: its value and name)
    before drawing anything."""
    most, name = limit or (MAX_VIDEO_PIXEL_FRAMES, "MAX_VIDEO_PIXEL_FRAMES")
    if frames * width * height > most:
        raise LimitError(f"{frames} frames at {width}x{height} is over the limit of "
                         f"{most:,} frames x pixels per video ({name}); lower the frame "
                         "rate or the image size", name)


def prepare(program: Program, graph: EnvironmentGraph, *, width: int, height: int, fps: int,
            seed: int, bindings: Bindings | None, agent: str | None,
            standing: Mapping[int, tuple[float, float]] | None = None, speed: float = 1.0
            ) -> tuple[SceneModel, Timeline, str]:
    """Execute, build the scene and animate: everything before drawing.

    `speed` scales how fast the agent moves (2.0: every motion takes half its time)."""
    if not speed > 0:
        raise HomesimError(f"speed must be positive, got {speed}")
    if not program.steps:
        raise HomesimError("the program has no steps to render")
    name = agent or list(AGENTS)[seed % len(AGENTS)]
    shape = agent_shape(name)
    # A program with plain ids (``<tv> (410)``) and no bindings names nodes by id, as
    # documented in `render_program`; grounded ones are checked by `execute`.
    reference = bindings is None and not program.is_grounded
    result = execute(program, graph, trace=True, bindings=bindings, reference=reference)
    scene = build_scene(graph, shape, seed=seed, max_size=(width, height))
    timeline = Animator(scene, graph, shape, fps=fps / speed, seed=seed,
                        standing=standing).run(result)
    shots = plan_shots(scene, timeline, (width, height))
    if shots:  # the same model with a close-up camera per interaction
        scene = build_scene(graph, shape, seed=seed, max_size=(width, height), shots=shots)
    return scene, timeline, name


def render_program(program: Program, graph: EnvironmentGraph, out_dir: str | Path, *,
                   width: int = 640, height: int = 480, fps: int = 30, seed: int = 0,
                   bindings: Bindings | None = None, progress: Progress | None = None,
                   agent: str | None = None, home: str | None = None,
                   standing: Mapping[int, tuple[float, float]] | None = None) -> RenderResult:
    """Animate a grounded program in a home with geometry and record it with ground truth.

    The program's objects name nodes of `graph` (``<tv> (1.410)``, or plain ``(410)``), or
    `bindings` maps (class, instance) to node ids. `home` names the home in ``meta.json``
    (a built-in home's name or the graph file). `standing` (step index -> (x, z), as
    `Grounding.standing`) gives where the agent stands for each step; without it render
    picks spots next to the objects on its own. Writes the folder layout described in
    `homesim.render.groundtruth`; read it back with `load_recording`.
    """
    t0 = time.perf_counter()
    check_size(width, height, fps)
    out = Path(out_dir)
    if (out / "meta.json").exists() or (out / "video.mp4").exists():
        raise HomesimError(f"{out}: already holds a recording; choose another folder")
    scene, timeline, name = prepare(program, graph, width=width, height=height, fps=fps,
                                    seed=seed, bindings=bindings, agent=agent,
                                    standing=standing)
    total = len(timeline)
    _check_length(total, width, height)
    writer = RecordingWriter(out, width, height, fps)
    try:
        with Renderer(scene, width, height) as renderer:
            for truth in record(scene, timeline, renderer):
                writer.add(truth)
                if progress is not None:
                    progress(truth.index + 1, total)
    except BaseException:
        writer.abort()
        raise
    steps = [StepSpan(i, str(program.steps[i]), a, b)
             for i, (a, b) in enumerate(timeline.step_frames)]
    meta = _meta(program, home or "graph", scene, name, width, height, fps, seed, total, steps)
    writer.close(meta)
    return RenderResult(out, total, width, height, fps, name, steps, time.perf_counter() - t0)


def render_video(program: Program, graph: EnvironmentGraph, path: str | Path, *,
                 width: int = 320, height: int = 240, fps: int = 12, seed: int = 0,
                 bindings: Bindings | None = None, progress: Progress | None = None,
                 agent: str | None = None,
                 standing: Mapping[int, tuple[float, float]] | None = None,
                 limit: tuple[int, str] | None = None) -> int:
    """Write only the video of a program (the frames and cameras `render_program` would
    record) to the MP4 file `path`; returns the number of frames. `standing`: as for
    `render_program`; `limit`: (frames x pixels, its name in `homesim.limits`) instead
    of `MAX_VIDEO_PIXEL_FRAMES`."""
    check_size(width, height, fps)
    scene, timeline, _ = prepare(program, graph, width=width, height=height, fps=fps,
                                 seed=seed, bindings=bindings, agent=agent, standing=standing)
    total = len(timeline)
    _check_length(total, width, height, limit)
    video = H264Writer(width, height, fps, Path(path))
    try:
        with Renderer(scene, width, height) as renderer:
            for truth in record(scene, timeline, renderer):
                video.add(truth.rgb)
                if progress is not None:
                    progress(truth.index + 1, total)
    finally:
        video.close()
    return total


def _meta(program, home: str, scene: SceneModel, agent, width, height, fps, seed, total,
          steps) -> dict:
    from homesim.render.agent import JOINTS
    from homesim.render.flow import intrinsics

    class_ids = {name: i for i, name in enumerate(scene.classes)}
    return {
        "program": str(program),
        "title": program.title,
        "home": home,
        "agent": agent,
        "seed": seed,
        "width": width,
        "height": height,
        "fps": fps,
        "num_frames": total,
        "steps": [{"index": s.index, "step": s.step, "start_frame": s.start_frame,
                   "end_frame": s.end_frame} for s in steps],
        "classes": {str(i): name for i, name in enumerate(scene.classes)},
        "instances": {str(n): {"class": c, "class_id": class_ids[c]}
                      for n, c in scene.instances.items()},
        "character_id": scene.character_id,
        "joints": list(JOINTS),
        "cameras": [{"name": c.name, "room_id": c.room_id, "fovy": c.fovy,
                     "aimed_at_agent": c.shot < 0,
                     "step": None if c.step < 0 else c.step,
                     "position": [float(x) for x in c.pos],
                     "intrinsics": intrinsics(width, height, c.fovy).tolist()}
                    for c in scene.cameras],
        "units": {"depth": "metres along the optical axis, 0 = nothing seen",
                  "flow": "pixels (du, dv) from this frame to the next",
                  "world": "metres, MuJoCo frame (z up) = Unity (x, z, y)",
                  "camera": "OpenCV: x right, y down, z forward; pixel centres at integers"},
    }


def render_keyframes(program: Program, graph: EnvironmentGraph, *, width: int = 320,
                     height: int = 240, seed: int = 0, bindings: Bindings | None = None,
                     agent: str | None = None,
                     standing: Mapping[int, tuple[float, float]] | None = None
                     ) -> list[tuple[int, np.ndarray]]:
    """(step index, RGB key frame of that step) for each step; nothing is written. A
    hands-on step's key frame is its effect (the hand on the object, seen by the step's
    close-up; `key_frames`), any other step's its last frame.

    `standing`: as for `render_program`."""
    return list(iter_keyframes(program, graph, width=width, height=height, seed=seed,
                               bindings=bindings, agent=agent, standing=standing))


def iter_keyframes(program: Program, graph: EnvironmentGraph, *, width: int = 320,
                   height: int = 240, seed: int = 0, bindings: Bindings | None = None,
                   agent: str | None = None,
                   standing: Mapping[int, tuple[float, float]] | None = None
                   ) -> Iterator[tuple[int, np.ndarray]]:
    """`render_keyframes` one frame at a time: memory holds one frame, not all of them."""
    check_size(width, height, 30)
    scene, timeline, _ = prepare(program, graph, width=width, height=height, fps=10,
                                 seed=seed, bindings=bindings, agent=agent, standing=standing)
    keys = key_frames(timeline)
    with Renderer(scene, width, height, shadows=True) as renderer:  # stills: no rush
        for step, (_, rgb) in enumerate(iter_still_frames(scene, timeline, renderer, keys)):
            yield step, rgb


def key_frames(timeline: Timeline) -> list[int]:
    """Per step, the frame that shows it: the effect of its last hands-on action (the
    frame its close-up is chosen for) if it has one, else its last frame."""
    keys = [end for _, end in timeline.step_frames]
    for it in timeline.interactions:
        keys[it.step] = it.peak
    return keys
