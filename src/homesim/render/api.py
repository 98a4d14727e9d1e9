"""Render a `Run`: animate what `homesim.run_program` ran, then draw it frame by frame.

A program meets the simulator once, in `run_program` (with ``trace=True``); render never
executes it again. The run's trace says what each step did to which node (the bindings),
its grounding where the agent stands for each step (`Grounding.standing`).

- `animate(run, ...)` -> `Animation`: the scene (built once, the close-ups of the
  interactions added) and the timeline of every frame; nothing is drawn.
- `play(animation, sink)`: the one loop that draws every frame and hands its ground truth
  (`FrameTruth`) to a `FrameSink`. The recording folder (`render_program`), the MP4 file
  (`render_video`) and the data set's episodes (`homesim.dataset`) are sinks.
- `iter_keyframes` / `render_keyframes`: one still per step of the same `Animation`.

>>> from homesim.ground import run_program
>>> run = run_program("[Walk] <tv> (1)\\n[SwitchOn] <tv> (1)", "scene1", trace=True)
>>> render_program(run, "out/tv", width=320, height=240, fps=10)  # doctest: +SKIP
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

import numpy as np

from homesim.errors import ExecutionError, HomesimError, LimitError
from homesim.limits import MAX_VIDEO_PIXEL_FRAMES
from homesim.program.model import Program
from homesim.render.agent import AGENTS, agent_shape
from homesim.render.animate import Animator, Timeline
from homesim.render.groundtruth import RecordingWriter, StepSpan
from homesim.render.recorder import FrameTruth, iter_still_frames, record
from homesim.render.renderer import Renderer
from homesim.render.scene import SceneModel, add_cameras, build_scene
from homesim.render.shots import plan_shots
from homesim.render.video import H264Writer, check_size
from homesim.sim.execute import ExecutionResult

if TYPE_CHECKING:
    from homesim.ground import Run

Progress = Callable[[int, int], None]
"""Called as ``progress(frames_done, frames_total)``."""


class FrameSink(Protocol):
    """What `play` hands each frame to, in order (a recording folder, a video, an
    episode of the data set)."""

    def add(self, truth: FrameTruth) -> None:
        """Take one frame's ground truth (its arrays are the sink's to keep)."""


@dataclass(frozen=True)
class Animation:
    """A `Run` animated in a home, ready to draw (`animate`)."""

    run: Run
    scene: SceneModel
    timeline: Timeline
    agent: str  # the agent's name (`homesim.render.agent.AGENTS`)
    width: int
    height: int
    fps: int
    seed: int

    @property
    def program(self) -> Program:
        """The program as it ran (grounded: its refs carry node ids, where it was)."""
        return self.result.program

    @property
    def result(self) -> ExecutionResult:
        assert self.run.result is not None  # `animate` checked
        return self.run.result

    @property
    def steps(self) -> list[StepSpan]:
        """Each step and the frames that show it."""
        steps = self.program.steps
        return [StepSpan(i, str(steps[i]), a, b)
                for i, (a, b) in enumerate(self.timeline.step_frames)]

    def __len__(self) -> int:
        return len(self.timeline)


def animate(run: Run, *, width: int, height: int, fps: int, seed: int = 0,
            agent: str | None = None, speed: float = 1.0) -> Animation:
    """Animate what `run` did (its trace) in its home, for frames of `width` x `height`.

    `run` comes from `run_program(..., trace=True)` and must be executable; the home
    needs 3D geometry. `agent`: one of `AGENTS` (default: chosen by `seed`, which also
    draws cameras and looks). `speed` scales how fast the agent moves (2.0: every motion
    takes half its time)."""
    check_size(width, height, fps)
    if not speed > 0:
        raise HomesimError(f"speed must be positive, got {speed}")
    result = _trace(run)
    name = agent or list(AGENTS)[seed % len(AGENTS)]
    shape = agent_shape(name)
    standing = run.grounding.standing if run.grounding is not None else None
    scene = build_scene(run.graph, shape, seed=seed, max_size=(width, height))
    timeline = Animator(scene, run.graph, shape, fps=fps / speed, seed=seed,
                        standing=standing).run(result)
    shots = plan_shots(scene, timeline, (width, height))
    if shots:  # the same model with a close-up camera per interaction
        scene = add_cameras(scene, shots)
    return Animation(run, scene, timeline, name, width, height, fps, seed)


def _trace(run: Run) -> ExecutionResult:
    """The run's execution, with its trace; why it cannot be rendered otherwise."""
    result = run.result
    if result is None or not run.executable:
        raise ExecutionError(f"cannot render a program that does not run: {run.message}")
    if result.trace is None:
        raise HomesimError("render needs the run's trace: run_program(..., trace=True)")
    if not result.program.steps:
        raise HomesimError("the program has no steps to render")
    return result


def check_length(animation: Animation, limit: tuple[int, str] | None = None) -> None:
    """Refuse an animation over `MAX_VIDEO_PIXEL_FRAMES` frames x pixels (or `limit`: its
    value and its name in `homesim.limits`) before anything is drawn."""
    most, name = limit or (MAX_VIDEO_PIXEL_FRAMES, "MAX_VIDEO_PIXEL_FRAMES")
    frames, width, height = len(animation), animation.width, animation.height
    if frames * width * height > most:
        raise LimitError(f"{frames} frames at {width}x{height} is over the limit of "
                         f"{most:,} frames x pixels per video ({name}); lower the frame "
                         "rate or the image size", name)


def play(animation: Animation, sink: FrameSink, *, flow: bool = True,
         progress: Progress | None = None, limit: tuple[int, str] | None = None) -> int:
    """Draw every frame of `animation` in order and hand its ground truth to `sink`;
    returns the number of frames. Without `flow`, the optical flow is not computed
    (`FrameTruth.flow` is None). `limit`: as for `check_length`, checked first."""
    check_length(animation, limit)
    total = len(animation)
    with Renderer(animation.scene, animation.width, animation.height) as renderer:
        for truth in record(animation.scene, animation.timeline, renderer, flow=flow):
            sink.add(truth)
            if progress is not None:
                progress(truth.index + 1, total)
    return total


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


def render_program(run: Run, out_dir: str | Path, *, width: int = 640, height: int = 480,
                   fps: int = 30, seed: int = 0, progress: Progress | None = None,
                   agent: str | None = None, home: str | None = None) -> RenderResult:
    """Animate a run (`run_program(..., trace=True)` in a home with geometry) and record
    it with ground truth into the folder `out_dir`.

    `home` names the home in ``meta.json`` (a built-in home's name or the graph file).
    Writes the folder layout described in `homesim.render.groundtruth`; read it back with
    `load_recording`.
    """
    t0 = time.perf_counter()
    out = Path(out_dir)
    if (out / "meta.json").exists() or (out / "video.mp4").exists():
        raise HomesimError(f"{out}: already holds a recording; choose another folder")
    animation = animate(run, width=width, height=height, fps=fps, seed=seed, agent=agent)
    check_length(animation)  # before the folder is made
    writer = RecordingWriter(out, width, height, fps)
    try:
        total = play(animation, writer, progress=progress)
    except BaseException:
        writer.abort()
        raise
    writer.close(_meta(animation, home or "graph"))
    return RenderResult(out, total, width, height, fps, animation.agent, animation.steps,
                        time.perf_counter() - t0)


class _VideoSink:
    """The colour of each frame into an `H264Writer`."""

    def __init__(self, video: H264Writer):
        self.video = video

    def add(self, truth: FrameTruth) -> None:
        self.video.add(truth.rgb)


def render_video(run: Run, path: str | Path, *, width: int = 320, height: int = 240,
                 fps: int = 12, seed: int = 0, progress: Progress | None = None,
                 agent: str | None = None, limit: tuple[int, str] | None = None) -> int:
    """Write only the video of a run (the frames and cameras `render_program` would
    record) to the MP4 file `path`; returns the number of frames. `limit`: (frames x
    pixels, its name in `homesim.limits`) instead of `MAX_VIDEO_PIXEL_FRAMES`."""
    animation = animate(run, width=width, height=height, fps=fps, seed=seed, agent=agent)
    check_length(animation, limit)  # before the file is made
    video = H264Writer(width, height, fps, Path(path))
    try:
        return play(animation, _VideoSink(video), flow=False, progress=progress, limit=limit)
    finally:
        video.close()


def _meta(animation: Animation, home: str) -> dict:
    from homesim.render.agent import JOINTS
    from homesim.render.flow import intrinsics

    scene, width, height = animation.scene, animation.width, animation.height
    class_ids = {name: i for i, name in enumerate(scene.classes)}
    return {
        "program": str(animation.program),
        "title": animation.program.title,
        "home": home,
        "agent": animation.agent,
        "seed": animation.seed,
        "width": width,
        "height": height,
        "fps": animation.fps,
        "num_frames": len(animation),
        "steps": [{"index": s.index, "step": s.step, "start_frame": s.start_frame,
                   "end_frame": s.end_frame} for s in animation.steps],
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


KEYFRAME_FPS = 10
"""Frame rate of the animation key frames are picked from."""


def render_keyframes(run: Run, *, width: int = 320, height: int = 240, seed: int = 0,
                     agent: str | None = None) -> list[tuple[int, np.ndarray]]:
    """(step index, RGB key frame of that step) for each step of a run; nothing is
    written. A hands-on step's key frame is its effect (the hand on the object, seen by
    the step's close-up; `key_frames`), any other step's its last frame."""
    return list(iter_keyframes(run, width=width, height=height, seed=seed, agent=agent))


def iter_keyframes(run: Run, *, width: int = 320, height: int = 240, seed: int = 0,
                   agent: str | None = None) -> Iterator[tuple[int, np.ndarray]]:
    """`render_keyframes` one frame at a time: memory holds one frame, not all of them."""
    animation = animate(run, width=width, height=height, fps=KEYFRAME_FPS, seed=seed,
                        agent=agent)
    scene, timeline = animation.scene, animation.timeline
    with Renderer(scene, width, height, shadows=True) as renderer:  # stills: no rush
        for step, (_, rgb) in enumerate(iter_still_frames(scene, timeline, renderer,
                                                          key_frames(timeline))):
            yield step, rgb


def key_frames(timeline: Timeline) -> list[int]:
    """Per step, the frame that shows it: the effect of its last hands-on action (the
    frame its close-up is chosen for) if it has one, else its last frame."""
    keys = [end for _, end in timeline.step_frames]
    for it in timeline.interactions:
        keys[it.step] = it.peak
    return keys
