"""Build the MuJoCo model of a home: its parts, the agent and the room cameras.

`build_scene` writes MJCF (boxes with a colour per class, hinged doors, mocap bodies
for objects that can move, lamps with their lights, TV screens) and compiles it.
`SceneModel` keeps the index maps the recorder needs: geom -> graph node and class, the
mocap slot of each movable object, the qpos address of each hinge.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from homesim.errors import HomesimError, LimitError
from homesim.limits import MAX_RENDER_NODES
from homesim.render.agent import HINGES, JOINTS, AgentShape, agent_mjcf
from homesim.render.cameras import CameraSpec, room_cameras
from homesim.render.gl import mujoco
from homesim.render.layout import Layout, Part, build_layout, render_kind
from homesim.render.materials import Look
from homesim.render.models import Shape
from homesim.world.graph import EnvironmentGraph

BACKGROUND = 0
"""Instance and class id of pixels that show no object."""


def _v(a) -> str:
    return " ".join(f"{float(x):.4f}" for x in a)


def _rgba(c) -> str:
    return " ".join(f"{float(x):.3f}" for x in c)


_AXIS_EULER = {0: ' euler="0 1.5708 0"', 1: ' euler="1.5708 0 0"', 2: ""}
"""Turns MuJoCo's z-aligned cylinders and capsules to run along x or y."""


def _shape_geom(name: str, s: Shape, material: str, rgba, origin=None) -> str:
    center = s.center if origin is None else s.center - origin
    turn = _AXIS_EULER[s.axis] if s.kind in ("cylinder", "capsule") else ""
    color = "" if rgba is None else f' rgba="{_rgba(rgba)}"'
    return (f'<geom name="{name}" type="{s.kind}" pos="{_v(center)}" '
            f'size="{_v(s.mjcf_size())}"{turn} material="{material}"{color}/>')


LIGHT_HEIGHT = 2.35
"""Metres: the ceiling light of each room hangs here, pointing down."""


def _part_geoms(part: Part, look: Look) -> list[str]:
    """The MJCF of one part: static shapes, a mocap body, a hinged door."""
    n = part.node_id
    out = []
    body = look.body(part.class_name, part.rgba)

    def geom(name: str, s: Shape, origin=None) -> str:
        if s.role == "glow" and part.lamp:
            return _shape_geom(name.replace(":", ":g", 1), s, f"lamp{n}", None, origin)
        if s.role == "screen" and part.screen is not None:
            return _shape_geom(f"n{n}:screen", s, "screen_off", None, origin)
        mat, rgba = look.material(s.role, body)
        return _shape_geom(name, s, mat, rgba, origin)

    for k, s in enumerate(part.shapes):
        out.append(geom(f"n{n}:{k}", s))
    if part.movable is not None:
        out.append(f'<body name="m{n}" mocap="true" pos="{_v(part.movable.center)}">'
                   + "".join(geom(f"n{n}:m{k}", s) for k, s in enumerate(part.movable_shapes))
                   + "</body>")
    if part.hinge is not None:
        h = part.hinge
        out.append(f'<body name="h{n}" pos="{_v(h.pivot)}">'
                   f'<joint name="hinge{n}" type="hinge" axis="0 0 1"/>'
                   + "".join(geom(f"n{n}:d{k}", s) for k, s in enumerate(h.shapes))
                   + "</body>")
    return out


ROOM_LIGHT = (1.0, 0.84, 0.64)
"""Diffuse colour of a room's ceiling light: warm white, falling off with distance
(`ROOM_FALLOFF`: constant, linear, quadratic), so it pools under the lamp and the
room's corners stay dimmer."""
ROOM_FALLOFF = (0.45, 0.12, 0.09)
LAMP_LIGHT = (0.85, 0.62, 0.38)
"""A table or floor lamp's own light when on: warmer and weaker, falling off fast."""
LAMP_FALLOFF = (0.6, 0.6, 0.9)
AMBIENT = 0.14
"""The headlight's ambient and diffuse share: what a room gets with its lights off."""


def _room_lights(layout: Layout) -> list[str]:
    """One ceiling light per room, under its ceiling lamps (else over its middle): its
    lamps and switch turn it on and off; and a light of its own for each table or floor
    lamp, at its shade."""
    out = []
    lamps: dict[int, list[np.ndarray]] = {}
    for part in layout.parts:
        room = layout.room_of_part.get(part.node_id)
        if part.lamp and part.class_name == "ceilinglamp" and part.boxes and room is not None:
            lamps.setdefault(room, []).append(part.boxes[0].center)
    r, g, b = ROOM_LIGHT
    for rid, box in sorted(layout.room_floors.items()):
        x, y = np.mean(lamps[rid], axis=0)[:2] if rid in lamps else box.center[:2]
        out.append(f'<light name="room{rid}" pos="{x:.3f} {y:.3f} {LIGHT_HEIGHT}" '
                   'dir="0 0 -1" directional="false" cutoff="85" exponent="1" '
                   f'diffuse="{r} {g} {b}" specular="0.2 0.18 0.15" '
                   f'attenuation="{_v(ROOM_FALLOFF)}" castshadow="false"/>')
    r, g, b = LAMP_LIGHT
    for part in layout.parts:
        if part.lamp and render_kind(part.class_name) == "lamp" and part.boxes:
            top = part.boxes[0].hi
            c = part.boxes[0].center
            out.append(f'<light name="lamp{part.node_id}" pos="{c[0]:.3f} {c[1]:.3f} '
                       f'{top[2] - 0.08:.3f}" dir="0 0 -1" directional="false" cutoff="180" '
                       f'diffuse="{r} {g} {b}" specular="0 0 0" '
                       f'attenuation="{_v(LAMP_FALLOFF)}" castshadow="false"/>')
    return out


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
    lamp_light: dict[int, int] = field(default_factory=dict)  # node id -> its room's light
    room_light: dict[int, int] = field(default_factory=dict)  # room id -> light id
    light_room: dict[int, int] = field(default_factory=dict)  # light id -> its room id
    screen_geom: dict[int, int] = field(default_factory=dict)  # node id -> geom id
    screen_mats: tuple[int, int] = (-1, -1)  # (off, on) material ids
    joint_qpos: dict[str, int] = field(default_factory=dict)  # agent hinge -> qpos address
    joint_sites: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    hand_sites: dict[str, int] = field(default_factory=dict)  # "l"/"r" -> site id
    palm_sites: dict[str, int] = field(default_factory=dict)  # "l"/"r" -> palm contact site
    mjcf: tuple[str, dict[str, bytes]] = ("", {})  # what `model` was compiled from

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
               max_size: tuple[int, int] = (640, 480), look: Look | None = None
               ) -> tuple[str, dict[str, bytes]]:
    """The MJCF text of a home with the agent standing at its start position, and the
    texture files it reads (pass both to `mujoco.MjModel.from_xml_string`)."""
    look = look or Look(0, layout.room_names)
    assets, files = look.assets()
    body = []
    for part in layout.parts:
        if part.lamp:
            assets.append(f'<material name="lamp{part.node_id}" rgba="1 0.96 0.85 1" '
                          'emission="0" specular="0"/>')
        body.extend(_part_geoms(part, look))
    body.extend(_room_lights(layout))
    body.extend(_camera_mjcf(cam) for cam in cameras)
    width, height = max_size
    slices, stacks = tessellation(max_size)
    xml = f"""<mujoco model="home">
  <compiler angle="radian"/>
  <statistic extent="20" center="0 0 1"/>
  <visual>
    <global offwidth="{width}" offheight="{height}"/>
    <quality shadowsize="{SHADOW_SIZE}" offsamples="0" numquads="1" numslices="{slices}"
             numstacks="{stacks}"/>
    <map znear="0.002" zfar="3" shadowclip="6" shadowscale="0.6"/>
    <headlight ambient="{AMBIENT} {AMBIENT} {AMBIENT}" diffuse="{AMBIENT} {AMBIENT} {AMBIENT}"
               specular="0.03 0.03 0.03"/>
  </visual>
  <default><geom contype="0" conaffinity="0"/></default>
  <asset>{"".join(assets)}</asset>
  <worldbody>
{agent_mjcf(agent, (float(layout.start[0]), float(layout.start[1])))}
{chr(10).join(body)}
  </worldbody>
</mujoco>"""
    return xml, files


SMALL_FRAME = 120
"""Pixels: frames no taller than this (the data set's `learn` profile, 64x48) draw round
shapes with `SMALL_TESSELLATION`, larger ones with `TESSELLATION`..."""
TESSELLATION = (12, 6)
SMALL_TESSELLATION = (8, 4)
"""... (slices around, stacks along a sphere, cylinder or capsule). In a small frame a
limb is a few pixels across, where the finer shapes change no more than the pixels of
their outline, yet the agent's round geoms are most of a draw's time there (~80 % at
64x48 with llvmpipe: the vertices, not the pixels, cost); 8 x 4 takes 40 % off them and
a third off a frame's draw."""


def tessellation(max_size: tuple[int, int]) -> tuple[int, int]:
    """(slices, stacks) of round shapes for frames up to `max_size` (width, height)."""
    return SMALL_TESSELLATION if max_size[1] <= SMALL_FRAME else TESSELLATION


def _camera_mjcf(cam: CameraSpec) -> str:
    return (f'<camera name="{cam.name}" pos="{_v(cam.pos)}" '
            f'xyaxes="{_v(cam.xaxis)} {_v(cam.yaxis)}" fovy="{cam.fovy:.2f}"/>')


_END = "\n  </worldbody>"
"""Where `scene_mjcf` closes the world body: cameras are its last children."""


SHADOW_SIZE = 1024
"""Pixels per side of the shadow map of the light of the camera's room."""


def _material_lamps(model, layout: Layout) -> dict[int, int]:
    out = {}
    for part in layout.parts:
        if part.lamp:
            out[part.node_id] = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_MATERIAL,
                                                  f"lamp{part.node_id}")
    return out


def _lamp_lights(scene: SceneModel, graph: EnvironmentGraph) -> None:
    """Each room's light, and the light each lamp turns on: a table or floor lamp its
    own, a ceiling or wall lamp its room's (several share one; the recorder lights it
    when any of them is on)."""
    m = scene.model
    light = mujoco.mjtObj.mjOBJ_LIGHT
    for rid in scene.layout.room_floors:
        scene.room_light[rid] = mujoco.mj_name2id(m, light, f"room{rid}")
        scene.light_room[scene.room_light[rid]] = rid
    for part in scene.layout.parts:
        room = graph.room_of(part.node_id)
        own = mujoco.mj_name2id(m, light, f"lamp{part.node_id}") if part.lamp else -1
        if own >= 0:
            scene.lamp_light[part.node_id] = own
            if room is not None:
                scene.light_room[own] = room
        elif part.lamp and room in scene.room_light:
            scene.lamp_light[part.node_id] = scene.room_light[room]


def build_scene(graph: EnvironmentGraph, agent: AgentShape, *, seed: int = 0,
                max_size: tuple[int, int] = (640, 480),
                shots: Sequence[CameraSpec] = ()) -> SceneModel:
    """Compile a home with geometry into a `SceneModel` (cameras randomised by `seed`;
    `shots`: close-up cameras added after the room cameras, see `homesim.render.shots`)."""
    if len(graph) > MAX_RENDER_NODES:
        raise LimitError(f"the home has {len(graph):,} nodes, over the limit of "
                         f"{MAX_RENDER_NODES:,} for rendering (MAX_RENDER_NODES)",
                         "MAX_RENDER_NODES")
    layout = build_layout(graph, seed)
    if not layout.floors:
        raise HomesimError("the home has no floor boxes: rendering needs a home with 3D "
                           "geometry (e.g. --home scene1, not scene1_trimmed)")
    if graph.character_id is None:
        raise HomesimError("the home has no character node to animate")
    cameras = room_cameras(layout, seed)
    xml, files = scene_mjcf(layout, cameras, agent, max_size, Look(seed, layout.room_names))
    scene = _index(_compile(xml, files), layout, cameras, graph)
    scene.mjcf = (xml, files)
    return add_cameras(scene, shots) if shots else scene


def add_cameras(scene: SceneModel, shots: Sequence[CameraSpec]) -> SceneModel:
    """`scene` with close-up cameras added after its cameras: its model compiled again
    from the same MJCF with the cameras appended (no geom, body or joint changes, so the
    index maps stay), the same model `build_scene` makes with these `shots`."""
    xml, files = scene.mjcf
    if not xml.endswith(_END + "\n</mujoco>"):
        raise AssertionError("the scene's MJCF must end with its world body")
    at = len(xml) - len(_END + "\n</mujoco>")
    xml = xml[:at] + "".join("\n" + _camera_mjcf(c) for c in shots) + xml[at:]
    return replace(scene, model=_compile(xml, files), cameras=[*scene.cameras, *shots],
                   mjcf=(xml, files))


def _compile(xml: str, files: dict[str, bytes]) -> mujoco.MjModel:
    try:
        return mujoco.MjModel.from_xml_string(xml, files)
    except ValueError as e:  # a bug of ours, but say where
        raise HomesimError(f"could not compile the scene model: {e}") from None


def _index(model: mujoco.MjModel, layout: Layout, cameras: list[CameraSpec],
           graph: EnvironmentGraph) -> SceneModel:
    """The `SceneModel` of a compiled home: the maps from MuJoCo ids to graph ids."""
    # Lamps and screens: attach materials to their geoms now that ids are known.
    lamp_mat = _material_lamps(model, layout)
    classes = ["background"]
    class_index: dict[str, int] = {}
    node_class = {p.node_id: p.class_name for p in layout.parts}
    char = graph.character_id
    assert char is not None  # build_scene checked
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
    _lamp_lights(scene, graph)
    if model.jnt_qposadr[model.joint("a:root").id] != 0:
        raise AssertionError("the agent's free joint must come first in qpos")
    scene.joint_qpos = {h: int(model.jnt_qposadr[model.joint(f"a:{h}").id]) for h in HINGES}
    scene.joint_sites = np.array([model.site(f"j:{j}").id for j in JOINTS], int)
    scene.hand_sites = {s: model.site(f"{s}_hand").id for s in ("l", "r")}
    scene.palm_sites = {s: model.site(f"{s}_palm").id for s in ("l", "r")}
    return scene
