"""Draw the four agents standing, walking, sitting and holding a cup: docs/render/agents.png.

    .venv/bin/python tools/render_agents.py [--out docs/render/agents.png]

Each cell is 640x480, drawn with MuJoCo in a small room with a chair and a cup (the
poses are `homesim.render.poses` presets; the cup rides in the right hand, which grips).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from homesim.render.agent import AGENTS, AgentShape
from homesim.render.gl import mujoco
from homesim.render.poses import Pose, carrying, gripping, sitting, standing, walk_cycle, write_qpos
from homesim.render.scene import SceneModel, build_scene
from homesim.render.sheet import contact_sheet
from homesim.world.graph import EnvironmentGraph

OUT = Path(__file__).resolve().parents[1] / "docs" / "render" / "agents.png"
W, H = 640, 480
CHAIR = (0.0, 1.2)  # MuJoCo (x, y) of the chair
CUP = 20


def _box(center, size) -> dict:
    return {"center": list(center), "size": list(size)}


def studio() -> EnvironmentGraph:
    """A 6 m room (Unity frame, y up) with a chair by a wall and a cup in a corner."""
    nodes = [
        {"id": 1, "class_name": "livingroom", "category": "Rooms",
         "bounding_box": _box((0, 1.25, 0), (6.1, 2.5, 6.1))},
        {"id": 2, "class_name": "floor", "category": "Floors",
         "bounding_box": _box((0, 0, 0), (6, 0, 6))},
        {"id": 3, "class_name": "wall", "category": "Walls",
         "bounding_box": _box((-3.0, 1.25, 0), (0.1, 2.5, 6))},
        {"id": 4, "class_name": "wall", "category": "Walls",
         "bounding_box": _box((0, 1.25, 3.0), (6, 2.5, 0.1))},
        {"id": 10, "class_name": "character", "category": "Characters",
         "bounding_box": _box((0, 0.9, 0), (0.5, 1.8, 0.3))},
        {"id": 11, "class_name": "chair", "category": "Furniture", "properties": ["SITTABLE"],
         "bounding_box": _box((CHAIR[0], 0.45, CHAIR[1]), (0.5, 0.9, 0.5))},
        {"id": CUP, "class_name": "cup", "category": "Props",
         "properties": ["GRABBABLE", "RECIPIENT"],
         "bounding_box": _box((2.5, 0.05, -2.5), (0.08, 0.1, 0.08))},
    ]
    edges = [{"from_id": n["id"], "relation_type": "INSIDE", "to_id": 1} for n in nodes[1:]]
    return EnvironmentGraph.from_dict({"nodes": nodes, "edges": edges}, source="studio")


def poses(shape: AgentShape) -> list[tuple[str, Pose, float]]:
    """(label, pose, camera azimuth in degrees) of each column."""
    stand = standing(shape, (0.0, -0.6), math.radians(-20))
    walk = walk_cycle(standing(shape, (0.0, -0.6), math.radians(-70)), math.pi / 2 + 0.2)
    seat = sitting(shape, (CHAIR[0], CHAIR[1] + 0.05), -math.pi / 2, 0.45)
    hold = gripping(carrying(standing(shape, (0.0, -0.6), math.radians(-25)), "r"), "r")
    return [("standing", stand, 160.0), ("walking", walk, 200.0),
            ("sitting", seat, 60.0), ("holding a cup (right hand grips)", hold, 145.0)]


def draw(scene: SceneModel, renderer: mujoco.Renderer, pose: Pose, azimuth: float,
         close: bool) -> np.ndarray:
    data = mujoco.MjData(scene.model)
    write_qpos(data.qpos, pose, scene.joint_qpos)
    mujoco.mj_kinematics(scene.model, data)
    hand = data.site_xpos[scene.hand_sites["r"]]
    data.mocap_pos[scene.mocap[CUP]] = hand if pose.r_grip > 0 else (2.5, 2.5, 0.05)
    mujoco.mj_kinematics(scene.model, data)
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = (*pose.xy, (1.25 if close else 0.85) * pose.z + (0.1 if close else 0.0))
    cam.distance = 1.7 if close else 3.1
    cam.azimuth, cam.elevation = azimuth, -12.0
    renderer.update_scene(data, cam)
    return renderer.render().copy()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(OUT))
    args = ap.parse_args()
    graph = studio()
    frames = []
    for name, shape in AGENTS.items():
        scene = build_scene(graph, shape, max_size=(W, H))
        with mujoco.Renderer(scene.model, H, W) as renderer:
            for label, pose, azimuth in poses(shape):
                frames.append((f"{name} ({shape.sex}, {shape.height:.2f} m): {label}",
                               draw(scene, renderer, pose, azimuth, label.startswith("hold"))))
    print(contact_sheet(frames, args.out, columns=4,
                        title="homesim agents (tools/render_agents.py)"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
