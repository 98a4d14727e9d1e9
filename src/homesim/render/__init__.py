"""Animate programs in 3D with MuJoCo and record video with dense ground truth.

Glossary:
    scene: the MuJoCo model of a home (`SceneModel`): boxes per graph node, the agent,
        8 cameras per room.
    timeline: per-frame agent pose and object states, made from the simulator trace.
    recording: a folder with video.mp4, per-frame depth / segmentation / flow, camera
        parameters, 2D/3D joints and the frames of each step (`load_recording`).

Only this package imports mujoco; `homesim.render.gl` picks the OpenGL backend
(`MUJOCO_GL`: osmesa on CPU, egl on GPU).
"""

from homesim.render.api import (
    RenderResult,
    iter_keyframes,
    render_keyframes,
    render_program,
    render_video,
)
from homesim.render.gl import BACKEND, gl_available
from homesim.render.groundtruth import Recording, StepSpan, load_recording
from homesim.render.renderer import Renderer
from homesim.render.scene import SceneModel, build_scene
from homesim.render.sheet import contact_sheet

__all__ = [
    "BACKEND",
    "Recording",
    "RenderResult",
    "Renderer",
    "SceneModel",
    "StepSpan",
    "build_scene",
    "contact_sheet",
    "gl_available",
    "iter_keyframes",
    "load_recording",
    "render_keyframes",
    "render_program",
    "render_video",
]
