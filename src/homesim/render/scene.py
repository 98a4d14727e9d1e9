"""Build the MuJoCo model of a home: its parts, the agent and the room cameras.

`build_scene` writes MJCF (boxes with a colour per class, hinged doors, mocap bodies
for objects that can move, lamps with their lights, TV screens) and compiles it.
`SceneModel` keeps the index maps the recorder needs: geom -> graph node and class, the
mocap slot of each movable object, the qpos address of each hinge.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from homesim.errors import HomesimError
from homesim.render.agent import HINGES, JOINTS, AgentShape, agent_mjcf
from homesim.render.cameras import CameraSpec, room_cameras
from homesim.render.gl import mujoco
from homesim.render.layout import Box, Layout, build_layout
from homesim.world.graph import EnvironmentGraph

BACKGROUND = 0
"""Instance and class id of pixels that show no object."""


def _v(a) -> str:
    return " ".join(f"{float(x):.4f}" for x in a)


def _rgba(c) -> str:
    return " ".join(f"{float(x):.3f}" for x in c)


def _box_geom(name: str, box: Box, rgba, extra: str = "") -> str:
    return (f'<geom name="{name}" type="box" pos="{_v(box.center)}" '
            f'size="{_v(np.maximum(box.half, 1e-3))}" rgba="{_rgba(rgba)}" {extra}/>')


@dataclass
class SceneModel:
    """A compiled home with the maps from MuJoCo ids to graph ids."""

    model: mujoco.MjModel
    layout: Layout
    cameras: list[CameraSpec]
    character_id: int
    classes: list[str]  # class index -> class name; index 0 is background
    geom_node: np.ndarray  # (ngeom,) int32 graph node id per geom
    geom_class: np.ndarray  # (ngeom,) int32 class index per geom
    mocap: dict[int, int] = field(default_factory=dict)  # node id -> mocap index
    hinge_qpos: dict[int, int] = field(default_factory=dict)  # node id -> qpos address
    hinge_open: dict[int, float] = field(default_factory=dict)  # node id -> open angle
    lamp_mat: dict[int, int] = field(default_factory=dict)  # node id -> material id
    lamp_light: dict[int, int] = field(default_factory=dict)  # node id -> light id
    screen_geom: dict[int, int] = field(default_factory=dict)  # node id -> geom id
    screen_mats: tuple[int, int] = (-1, -1)  # (off, on) material ids
    joint_qpos: dict[str, int] = field(default_factory=dict)  # agent hinge -> qpos address
    joint_sites: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    hand_sites: dict[str, int] = field(default_factory=dict)  # "l"/"r" -> site id

    @property
    def instances(self) -> dict[int, str]:
        """Node id -> class name of everything that can appear in a frame."""
        out: dict[int, str] = {}
        for g in range(self.model.ngeom):
            nid = int(self.geom_node[g])
            if nid != BACKGROUND:
                out[nid] = self.classes[int(self.geom_class[g])]
        return dict(sorted(out.items()))

    def camera_id(self, name: str) -> int:
        cid = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_CAMERA, name)
        if cid < 0:
            raise HomesimError(f"no camera named {name!r}")
        return cid


def scene_mjcf(layout: Layout, cameras: list[CameraSpec], agent: AgentShape,
               max_size: tuple[int, int] = (640, 480)) -> str:
    """The MJCF text of a home with the agent standing at its start position."""
    assets = [
        '<texture name="tv_image" type="2d" builtin="gradient" rgb1="0.1 0.5 0.95" '
        'rgb2="0.95 0.5 0.1" width="64" height="64"/>',
        '<material name="screen_off" rgba="0.02 0.02 0.03 1" specular="0.6" shininess="0.8"/>',
        '<material name="screen_on" texture="tv_image" rgba="1 1 1 1" emission="1"/>',
    ]
    body = []
    for part in layout.parts:
        n = part.node_id
        for k, box in enumerate(part.boxes):
            body.append(_box_geom(f"n{n}:{k}", box, part.rgba))
        if part.movable is not None:
            body.append(f'<body name="m{n}" mocap="true" pos="{_v(part.movable.center)}">'
                        + _box_geom(f"n{n}:m", Box(np.zeros(3), part.movable.half), part.rgba)
                        + "</body>")
        if part.hinge is not None:
            h = part.hinge
            body.append(f'<body name="h{n}" pos="{_v(h.pivot)}">'
                        f'<joint name="hinge{n}" type="hinge" axis="0 0 1"/>'
                        + _box_geom(f"n{n}:door", h.panel, part.rgba) + "</body>")
        if part.screen is not None:
            # No rgba on the screen: its colour comes from the material swapped at runtime.
            body.append(f'<geom name="n{n}:screen" type="box" pos="{_v(part.screen.center)}" '
                        f'size="{_v(part.screen.half)}" material="screen_off"/>')
        if part.lamp:
            assets.append(f'<material name="lamp{n}" rgba="{_rgba(part.rgba)}" emission="0"/>')
            top = max((b.hi[2] for b in part.boxes), default=2.4)
            center = part.boxes[0].center if part.boxes else np.zeros(3)
            body.append(f'<light name="light{n}" pos="{center[0]:.3f} {center[1]:.3f} '
                        f'{min(top, 2.4) - 0.2:.3f}" dir="0 0 -1" directional="false" '
                        'diffuse="0.45 0.42 0.35" specular="0 0 0" attenuation="1 0.15 0.05" '
                        'castshadow="false" active="false"/>')
    for cam in cameras:
        body.append(f'<camera name="{cam.name}" pos="{_v(cam.pos)}" '
                    f'xyaxes="{_v(cam.xaxis)} {_v(cam.yaxis)}" fovy="{cam.fovy:.2f}"/>')
    width, height = max_size
    return f"""<mujoco model="home">
  <compiler angle="radian"/>
  <statistic extent="20" center="0 0 1"/>
  <visual>
    <global offwidth="{width}" offheight="{height}"/>
    <quality shadowsize="0" offsamples="0" numquads="1" numslices="12" numstacks="8"/>
    <map znear="0.002" zfar="3"/>
    <headlight ambient="0.38 0.38 0.38" diffuse="0.45 0.45 0.45" specular="0.05 0.05 0.05"/>
  </visual>
  <default><geom contype="0" conaffinity="0"/></default>
  <asset>{"".join(assets)}</asset>
  <worldbody>
{agent_mjcf(agent, (float(layout.start[0]), float(layout.start[1])))}
{chr(10).join(body)}
  </worldbody>
</mujoco>"""


def _material_lamps(model, layout: Layout) -> dict[int, int]:
    out = {}
    for part in layout.parts:
        if part.lamp:
            out[part.node_id] = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_MATERIAL,
                                                  f"lamp{part.node_id}")
    return out


def build_scene(graph: EnvironmentGraph, agent: AgentShape, *, seed: int = 0,
                max_size: tuple[int, int] = (640, 480),
                shots: Sequence[CameraSpec] = ()) -> SceneModel:
    """Compile a home with geometry into a `SceneModel` (cameras randomised by `seed`;
    `shots`: close-up cameras added after the room cameras, see `homesim.render.shots`)."""
    layout = build_layout(graph)
    if not layout.floors:
        raise HomesimError("the home has no floor boxes: rendering needs a home with 3D "
                           "geometry (e.g. --home scene1, not scene1_trimmed)")
    if graph.character_id is None:
        raise HomesimError("the home has no character node to animate")
    cameras = room_cameras(layout, seed) + list(shots)
    xml = scene_mjcf(layout, cameras, agent, max_size)
    try:
        model = mujoco.MjModel.from_xml_string(xml)
    except ValueError as e:  # a bug of ours, but say where
        raise HomesimError(f"could not compile the scene model: {e}") from None
    # Lamps and screens: attach materials to their geoms now that ids are known.
    lamp_mat = _material_lamps(model, layout)
    classes = ["background"]
    class_index: dict[str, int] = {}
    node_class = {p.node_id: p.class_name for p in layout.parts}
    char = graph.character_id
    node_class[char] = graph.node(char).class_name
    geom_node = np.zeros(model.ngeom, np.int32)
    geom_class = np.zeros(model.ngeom, np.int32)
    screen_geom: dict[int, int] = {}
    for g in range(model.ngeom):
        name = model.geom(g).name
        nid = char if name.startswith("agent:") else int(name[1:].split(":")[0])
        cls = node_class[nid]
        if cls not in class_index:
            class_index[cls] = len(classes)
            classes.append(cls)
        geom_node[g] = nid
        geom_class[g] = class_index[cls]
        if name.endswith(":screen"):
            screen_geom[nid] = g
        elif nid in lamp_mat:
            model.geom_matid[g] = lamp_mat[nid]
    scene = SceneModel(model, layout, cameras, char, classes, geom_node, geom_class,
                       lamp_mat=lamp_mat, screen_geom=screen_geom)
    obj = mujoco.mjtObj
    scene.screen_mats = (mujoco.mj_name2id(model, obj.mjOBJ_MATERIAL, "screen_off"),
                         mujoco.mj_name2id(model, obj.mjOBJ_MATERIAL, "screen_on"))
    for part in layout.parts:
        n = part.node_id
        if part.movable is not None:
            scene.mocap[n] = int(model.body_mocapid[model.body(f"m{n}").id])
        if part.hinge is not None:
            scene.hinge_qpos[n] = int(model.jnt_qposadr[model.joint(f"hinge{n}").id])
            scene.hinge_open[n] = part.hinge.open_angle
        if part.lamp:
            scene.lamp_light[n] = mujoco.mj_name2id(model, obj.mjOBJ_LIGHT, f"light{n}")
    if model.jnt_qposadr[model.joint("a:root").id] != 0:
        raise AssertionError("the agent's free joint must come first in qpos")
    scene.joint_qpos = {h: int(model.jnt_qposadr[model.joint(f"a:{h}").id]) for h in HINGES}
    scene.joint_sites = np.array([model.site(f"j:{j}").id for j in JOINTS], int)
    scene.hand_sites = {s: model.site(f"{s}_hand").id for s in ("l", "r")}
    return scene
