"""A home seen from above, lights on, beside VirtualHome's Unity picture of it.

    python tools/topdown.py scene1 [--seed 0] [--size 900] [--out docs/render/topdown]
                                   [--reference ../shared/data/virtualhome/reference_images]

The home is built as render builds it (`build_scene`, the seed's theme), the ceilings and
the agent left out, every room light and lamp on, and drawn from a camera high above the
middle looking straight down (a narrow field of view: nearly a plan). Where the reference
folder has ``<home>rot.png`` (the Unity render of the same apartment), the two go side by
side in ``<out>/<home>_topdown.png``; a generated home gets its picture alone. The Unity
pictures are rotated so that their layout reads like ours: pass `--turn` (quarter turns)
and `--flip` to match one by eye.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from PIL import Image

import homesim
from homesim.render.agent import AGENTS
from homesim.render.gl import mujoco
from homesim.render.renderer import Renderer
from homesim.render.scene import build_scene

ROOT = Path(__file__).resolve().parents[1]


def top_view(home: str, seed: int, size: int) -> np.ndarray:
    """(size, size, 3) RGB of a home from above, ceilings and agent hidden, lights on."""
    graph = homesim.load_home(home)
    scene = build_scene(graph, AGENTS["male1"], seed=seed, max_size=(size, size))
    m = scene.model
    data = mujoco.MjData(m)
    hide = {scene.character_id} | {n.id for n in graph if n.class_name == "ceiling"}
    for g in range(m.ngeom):
        if int(scene.geom_node[g]) in hide:
            m.geom_rgba[g, 3] = 0.0
            m.geom_group[g] = 5
    m.light_active[:] = 1
    for mat in scene.lamp_mat.values():
        m.mat_emission[mat] = 0.9
    mujoco.mj_forward(m, data)
    floors = np.array([[*b.lo[:2], *b.hi[:2]] for b in scene.layout.room_floors.values()])
    lo, hi = floors[:, :2].min(axis=0), floors[:, 2:].max(axis=0)
    span = float(max(hi - lo)) * 1.05
    fovy = 12.0
    height = span / 2 / math.tan(math.radians(fovy / 2))
    center = (lo + hi) / 2
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.eye(3).reshape(-1))  # looking down -z, x right, y up
    m.cam_pos[0], m.cam_quat[0], m.cam_fovy[0] = (*center, height), quat, fovy
    m.vis.map.zfar = max(m.vis.map.zfar, (height + 5) / m.stat.extent)
    mujoco.mj_camlight(m, data)
    with Renderer(scene, size, size, shadows=False) as r:
        r._light_masks = {}  # every light (up to MuJoCo's eight)
        r.camera_moved(data, 0)
        return r.rgb(data, 0)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("home")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--size", type=int, default=900)
    ap.add_argument("--out", default=str(ROOT / "docs" / "render" / "topdown"))
    ap.add_argument("--reference", default=str(ROOT.parent / "shared" / "data" / "virtualhome"
                                               / "reference_images"))
    ap.add_argument("--turn", type=int, default=0, help="quarter turns of the reference")
    ap.add_argument("--flip", action="store_true", help="mirror the reference left-right")
    args = ap.parse_args()
    ours = Image.fromarray(top_view(args.home, args.seed, args.size))
    ref_path = Path(args.reference) / f"{args.home}rot.png"
    if ref_path.is_file():
        ref = Image.open(ref_path).convert("RGB").rotate(90 * args.turn, expand=True)
        if args.flip:
            ref = ref.transpose(Image.Transpose.FLIP_LEFT_RIGHT)
        ref = ref.resize((round(ref.width * args.size / ref.height), args.size))
        sheet = Image.new("RGB", (ours.width + ref.width + 10, args.size), (255, 255, 255))
        sheet.paste(ours, (0, 0))
        sheet.paste(ref, (ours.width + 10, 0))
    else:
        sheet = ours
    out = Path(args.out) / f"{args.home}_topdown.jpg"
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out, format="JPEG", quality=85, optimize=True)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
