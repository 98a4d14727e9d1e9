"""Animate programs in 3D with MuJoCo and record video with dense ground truth.

Glossary:
    scene: the MuJoCo model of a home (`SceneModel`): boxes per graph node, the agent,
        8 cameras per room.
    timeline: per-frame agent pose and object states, made from the simulator trace.
    animation: a `Run` (what `run_program` returned, with its trace) animated in a scene:
        the scene and its timeline (`animate`), drawn by the one loop `play`.
    sink: what `play` hands each frame's ground truth (`FrameTruth`) to: a recording
        folder, a video file, a data set episode (`FrameSink`).
    recording: a folder with video.mp4, per-frame depth / segmentation / flow, camera
        parameters, 2D/3D joints and the frames of each step (`load_recording`).

Only this package imports mujoco; `homesim.render.gl` picks the OpenGL backend
(`MUJOCO_GL`: osmesa on CPU, egl on GPU).
"""

from homesim.render.api import (
    Animation,
    FrameSink,
    RenderResult,
    animate,
    check_length,
    iter_keyframes,
    play,
    render_keyframes,
    render_program,
    render_video,
)
from homesim.render.gl import BACKEND, gl_available
from homesim.render.groundtruth import Recording, StepSpan, load_recording
from homesim.render.recorder import FrameTruth
from homesim.render.renderer import Renderer
from homesim.render.scene import SceneModel, build_scene
from homesim.render.sheet import contact_sheet

__all__ = [
    "BACKEND",
    "Animation",
    "FrameSink",
    "FrameTruth",
    "Recording",
    "RenderResult",
    "Renderer",
    "SceneModel",
    "StepSpan",
    "animate",
    "build_scene",
    "check_length",
    "contact_sheet",
    "gl_available",
    "iter_keyframes",
    "load_recording",
    "play",
    "render_keyframes",
    "render_program",
    "render_video",
]
