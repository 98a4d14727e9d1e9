"""Render test builders: a one-room home with geometry, and a GL skip."""

from __future__ import annotations

import pytest

from homesim.world.graph import EnvironmentGraph

try:  # homesim.render.gl picks MUJOCO_GL before mujoco is first imported
    import numpy as np

    import homesim.render.gl  # noqa: F401
except ImportError:
    pytest.skip("needs the render extra (mujoco)", allow_module_level=True)


def _box(center, size):
    return {"center": list(center), "size": list(size)}


def box_home_dict() -> dict:
    """A 4 m x 4 m room (Unity frame, y up): walls, a table with a cup, an apple and a lamp,
    a TV and a fridge.

    MuJoCo frame (x, z, y): walls' inner faces at x = +-1.95 and y = +-1.95.
    """
    nodes = [
        {"id": 1, "class_name": "livingroom", "category": "Rooms",
         "bounding_box": _box((0, 1.25, 0), (4.1, 2.5, 4.1))},
        {"id": 2, "class_name": "floor", "category": "Floors",
         "bounding_box": _box((0, 0, 0), (4, 0, 4))},
        {"id": 3, "class_name": "wall", "category": "Walls",
         "bounding_box": _box((2.0, 1.25, 0), (0.1, 2.5, 4))},
        {"id": 4, "class_name": "wall", "category": "Walls",
         "bounding_box": _box((-2.0, 1.25, 0), (0.1, 2.5, 4))},
        {"id": 5, "class_name": "wall", "category": "Walls",
         "bounding_box": _box((0, 1.25, 2.0), (4, 2.5, 0.1))},
        {"id": 6, "class_name": "wall", "category": "Walls",
         "bounding_box": _box((0, 1.25, -2.0), (4, 2.5, 0.1))},
        {"id": 10, "class_name": "character", "category": "Characters",
         "bounding_box": _box((-1.0, 0.9, -1.4), (0.5, 1.8, 0.3))},
        {"id": 20, "class_name": "table", "category": "Furniture", "properties": ["SURFACES"],
         "bounding_box": _box((1.0, 0.4, -1.0), (0.6, 0.8, 0.6))},
        {"id": 21, "class_name": "cup", "category": "Props",
         "properties": ["GRABBABLE", "RECIPIENT"],
         "bounding_box": _box((1.0, 0.85, -1.0), (0.08, 0.1, 0.08))},
        {"id": 22, "class_name": "tv", "category": "Electronics",
         "properties": ["HAS_SWITCH", "LOOKABLE"], "states": ["OFF"],
         "bounding_box": _box((1.7, 1.0, 1.0), (0.15, 0.6, 1.0))},
        {"id": 23, "class_name": "fridge", "category": "Appliances",
         "properties": ["CAN_OPEN", "CONTAINERS"], "states": ["CLOSED"],
         "bounding_box": _box((-1.6, 0.9, 1.4), (0.6, 1.8, 0.6))},
        {"id": 24, "class_name": "apple", "category": "Food",
         "properties": ["GRABBABLE", "EATABLE"],
         "bounding_box": _box((1.15, 0.85, -0.85), (0.08, 0.08, 0.08))},
        {"id": 25, "class_name": "tablelamp", "category": "Lamps",
         "properties": ["HAS_SWITCH"], "states": ["OFF"],
         "bounding_box": _box((0.85, 1.0, -1.15), (0.2, 0.4, 0.2))},
    ]
    edges = [(n["id"], "INSIDE", 1) for n in nodes[1:]]
    edges += [(21, "ON", 20), (21, "CLOSE", 20), (20, "CLOSE", 21),
              (24, "ON", 20), (24, "CLOSE", 20), (20, "CLOSE", 24),
              (25, "ON", 20), (25, "CLOSE", 20), (20, "CLOSE", 25)]
    return {"nodes": nodes,
            "edges": [{"from_id": a, "relation_type": r, "to_id": b} for a, r, b in edges]}


@pytest.fixture
def box_home() -> EnvironmentGraph:
    return EnvironmentGraph.from_dict(box_home_dict(), source="box home")


@pytest.fixture(scope="session")
def gl():
    """Skip when no OpenGL context can be created (no OSMesa / EGL on this machine)."""
    from homesim.render.gl import BACKEND, gl_available

    if not gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={BACKEND}")
    return BACKEND


def place_camera(scene, data, index: int, pos, forward) -> None:
    """Move fixed camera `index` to `pos` looking along `forward` (world frame)."""
    from homesim.render.cameras import look_at
    from homesim.render.gl import mujoco

    pos = np.asarray(pos, float)
    x, y = look_at(pos, pos + np.asarray(forward, float))
    mat = np.stack([x, y, np.cross(x, y)], axis=1)  # columns: camera axes in world
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, mat.reshape(-1))
    scene.model.cam_pos[index] = pos
    scene.model.cam_quat[index] = quat
    mujoco.mj_kinematics(scene.model, data)
    mujoco.mj_camlight(scene.model, data)


def ran(text: str, graph: EnvironmentGraph, **options):
    """The `Run` render animates: `text` run in `graph` with its trace; a program with
    plain ids (``<tv> (22)``) names nodes by id (as ``homesim render --no-ground``)."""
    import homesim

    program = homesim.parse_program(text)
    reference = not program.is_grounded and "reference" not in options
    return homesim.run_program(program, graph, trace=True,
                               **{"reference": reference, **options})
