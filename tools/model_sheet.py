"""A sheet of object models: classes drawn side by side on a floor, as render draws them.

    python tools/model_sheet.py sofa pillow plate speaker ceilingfan teddybear \\
        [--size 1.0 0.5 0.8 ...] [--seed 0] [--variants 3] [--out out/models.png]

Each class stands in a 1.6 m cell at its knowledge-base size (`--size` overrides: one
width depth height triple for every class, Unity order x y z), one row per variant, lit
by the renderer's lights; the sheet is drawn from above and in front. It builds a small
home graph (one room, the objects on the floor) and renders it with
`homesim.render.Renderer`, one 320x240 view per object; nothing but the picture is
written.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from PIL import Image

from homesim.knowledge.objects import load_kb
from homesim.render.agent import AGENTS
from homesim.render.gl import mujoco
from homesim.render.renderer import Renderer
from homesim.render.scene import build_scene
from homesim.world.graph import EnvironmentGraph

CELL = 1.6
W, H = 320, 240


def _view(scene, data, renderer: Renderer, i: int, size) -> np.ndarray:
    """Cell `i` seen from the front and above, framing an object of `size` (x, y, z)."""
    m = scene.model
    reach = 1.4 * max(size) + 0.3
    target = np.array([(i + 0.5) * CELL, CELL / 2, 0.45 * size[1]])
    eye = target + reach * np.array([0.35, -0.8, 0.55])
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, [0, 0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.stack([right, up, -fwd], axis=1).reshape(-1))
    m.cam_pos[0], m.cam_quat[0], m.cam_fovy[0] = eye, quat, 45.0
    mujoco.mj_camlight(m, data)
    renderer.camera_moved(data, 0)
    return renderer.rgb(data, 0)


def _home(classes: list[str], sizes: list[tuple[float, float, float]], rows: int) -> dict:
    n = len(classes)
    wide, deep = n * CELL, rows * CELL
    nodes = [{"id": 1, "class_name": "livingroom", "category": "Rooms",
              "bounding_box": {"center": [wide / 2, 1.25, deep / 2],
                               "size": [wide + 2, 2.5, deep + 2]}},
             {"id": 2, "class_name": "floor", "category": "Floors",
              "bounding_box": {"center": [wide / 2, 0, deep / 2], "size": [wide + 2, 0, deep + 2]}},
             {"id": 3, "class_name": "character", "category": "Characters",
              "bounding_box": {"center": [-0.8, 0.9, -0.8], "size": [0.5, 1.8, 0.3]}}]
    nid = 10
    for r in range(rows):
        for i, (cls, size) in enumerate(zip(classes, sizes, strict=True)):
            nodes.append({"id": nid, "class_name": cls, "category": "Furniture",
                          "bounding_box": {"center": [(i + 0.5) * CELL, size[1] / 2,
                                                      (r + 0.5) * CELL], "size": list(size)}})
            nid += 1
    edges = [{"from_id": n["id"], "relation_type": "INSIDE", "to_id": 1} for n in nodes[1:]]
    return {"nodes": nodes, "edges": edges}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("classes", nargs="+")
    ap.add_argument("--size", type=float, nargs=3, default=None)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--variants", type=int, default=1, help="rows (seeds seed..seed+n-1)")
    ap.add_argument("--out", default="out/models.png")
    args = ap.parse_args()
    kb = load_kb()
    sizes = [tuple(args.size) if args.size else (kb.prefab_size(c) or (0.4, 0.4, 0.4))
             for c in args.classes]
    rows = []
    for v in range(args.variants):
        graph = EnvironmentGraph.from_dict(_home(args.classes, sizes, 1))
        scene = build_scene(graph, AGENTS["male1"], seed=args.seed + v, max_size=(W, H))
        data = mujoco.MjData(scene.model)
        mujoco.mj_forward(scene.model, data)
        with Renderer(scene, W, H, shadows=True) as r:
            rows.append(np.concatenate([_view(scene, data, r, i, size)
                                        for i, size in enumerate(sizes)], axis=1))
    frames = rows
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(np.concatenate(frames)).save(out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
