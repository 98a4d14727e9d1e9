"""The agent: an articulated humanoid written as MJCF, in four body shapes.

Local frame of the agent: it faces +x, its left is +y, up is +z. Hinge signs follow
the right-hand rule, so a negative hip or shoulder pitch swings the limb forward and a
positive knee / negative elbow angle bends it naturally.
"""

from __future__ import annotations

from dataclasses import dataclass

from homesim.errors import HomesimError


@dataclass(frozen=True)
class AgentShape:
    """Body measurements (metres) and colours of one agent."""

    name: str
    height: float
    shoulder: float  # half the shoulder width
    hip: float  # half the hip width
    girth: float  # torso capsule radius
    shirt: tuple[float, float, float]
    pants: tuple[float, float, float]
    skin: tuple[float, float, float]

    @property
    def thigh(self) -> float:
        return 0.245 * self.height

    @property
    def shin(self) -> float:
        return 0.25 * self.height

    @property
    def torso(self) -> float:
        return 0.29 * self.height

    @property
    def upper_arm(self) -> float:
        return 0.18 * self.height

    @property
    def forearm(self) -> float:
        return 0.15 * self.height

    @property
    def ankle(self) -> float:
        return 0.04 * self.height

    @property
    def pelvis_height(self) -> float:
        """Height of the pelvis above the floor when standing straight."""
        return self.thigh + self.shin + self.ankle


AGENTS: dict[str, AgentShape] = {
    s.name: s for s in (
        AgentShape("male1", 1.78, 0.20, 0.10, 0.13, (0.20, 0.35, 0.75), (0.15, 0.15, 0.25),
                   (0.87, 0.68, 0.55)),
        AgentShape("female1", 1.65, 0.17, 0.10, 0.11, (0.80, 0.25, 0.30), (0.25, 0.20, 0.30),
                   (0.93, 0.76, 0.65)),
        AgentShape("male2", 1.85, 0.22, 0.12, 0.15, (0.20, 0.60, 0.35), (0.35, 0.30, 0.22),
                   (0.55, 0.38, 0.28)),
        AgentShape("female2", 1.70, 0.17, 0.11, 0.12, (0.90, 0.70, 0.20), (0.20, 0.30, 0.45),
                   (0.70, 0.50, 0.38)),
    )
}
"""The paper's four agents, as distinct body shapes and colours."""

JOINTS: tuple[str, ...] = (
    "pelvis", "neck", "head", "l_shoulder", "l_elbow", "l_wrist", "r_shoulder", "r_elbow",
    "r_wrist", "l_hip", "l_knee", "l_ankle", "r_hip", "r_knee", "r_ankle", "spine",
)
"""Names of the keypoints written as 2D/3D ground truth (MJCF sites ``j:<name>``)."""

HINGES: tuple[str, ...] = (
    "spine_pitch", "spine_yaw", "neck_yaw", "neck_pitch",
    "l_sh_pitch", "l_sh_roll", "l_sh_yaw", "l_elbow",
    "r_sh_pitch", "r_sh_roll", "r_sh_yaw", "r_elbow",
    "l_hip_pitch", "l_hip_roll", "l_knee", "r_hip_pitch", "r_hip_roll", "r_knee",
)
"""The agent's hinge joints (MJCF joint ``a:<name>``), radians."""


def agent_shape(name: str) -> AgentShape:
    """An agent by name (``male1``, ``female1``, ``male2``, ``female2``)."""
    try:
        return AGENTS[name]
    except KeyError:
        raise HomesimError(f"unknown agent {name!r}; choose one of {', '.join(AGENTS)}") \
            from None


def _rgb(c: tuple[float, float, float]) -> str:
    return f"{c[0]} {c[1]} {c[2]} 1"


def _j(name: str, axis: str, lo: float, hi: float) -> str:
    return f'<joint name="a:{name}" type="hinge" axis="{axis}" range="{lo} {hi}"/>'


def _arm(side: str, s: AgentShape) -> str:
    y = s.shoulder if side == "l" else -s.shoulder
    ua, fa, r = s.upper_arm, s.forearm, 0.035 * s.height / 1.75
    roll = ("-0.3 2.8" if side == "l" else "-2.8 0.3")
    return f"""
      <body name="a:{side}_shoulder" pos="0 {y:.3f} {s.torso - 0.04:.3f}">
        {_j(f"{side}_sh_pitch", "0 1 0", -3.1, 1.2)}
        <joint name="a:{side}_sh_roll" type="hinge" axis="1 0 0" range="{roll}"/>
        {_j(f"{side}_sh_yaw", "0 0 1", -1.6, 1.6)}
        <site name="j:{side}_shoulder" size="0.01"/>
        <geom name="agent:{side}_upper_arm" type="capsule" fromto="0 0 0 0 0 {-ua:.3f}"
              size="{r:.3f}" rgba="{_rgb(s.shirt)}"/>
        <body name="a:{side}_forearm" pos="0 0 {-ua:.3f}">
          {_j(f"{side}_elbow", "0 1 0", -2.6, 0.0)}
          <site name="j:{side}_elbow" size="0.01"/>
          <geom name="agent:{side}_forearm" type="capsule" fromto="0 0 0 0 0 {-fa:.3f}"
                size="{r * 0.85:.3f}" rgba="{_rgb(s.skin)}"/>
          <site name="j:{side}_wrist" pos="0 0 {-fa:.3f}" size="0.01"/>
          <site name="{side}_hand" pos="0 0 {-fa - 0.06:.3f}" size="0.01"/>
          <geom name="agent:{side}_hand" type="sphere" pos="0 0 {-fa - 0.04:.3f}"
                size="{r * 1.2:.3f}" rgba="{_rgb(s.skin)}"/>
        </body>
      </body>"""


def _leg(side: str, s: AgentShape) -> str:
    y = s.hip if side == "l" else -s.hip
    th, sh, r = s.thigh, s.shin, 0.055 * s.height / 1.75
    return f"""
    <body name="a:{side}_thigh" pos="0 {y:.3f} 0">
      {_j(f"{side}_hip_pitch", "0 1 0", -2.2, 0.8)}
      {_j(f"{side}_hip_roll", "1 0 0", -0.6, 0.6)}
      <site name="j:{side}_hip" size="0.01"/>
      <geom name="agent:{side}_thigh" type="capsule" fromto="0 0 0 0 0 {-th:.3f}"
            size="{r:.3f}" rgba="{_rgb(s.pants)}"/>
      <body name="a:{side}_shin" pos="0 0 {-th:.3f}">
        {_j(f"{side}_knee", "0 1 0", 0.0, 2.6)}
        <site name="j:{side}_knee" size="0.01"/>
        <geom name="agent:{side}_shin" type="capsule" fromto="0 0 0 0 0 {-sh:.3f}"
              size="{r * 0.8:.3f}" rgba="{_rgb(s.pants)}"/>
        <site name="j:{side}_ankle" pos="0 0 {-sh:.3f}" size="0.01"/>
        <geom name="agent:{side}_foot" type="box" pos="0.05 0 {-sh - s.ankle / 2:.3f}"
              size="0.11 0.045 {s.ankle / 2:.3f}" rgba="0.15 0.12 0.1 1"/>
      </body>
    </body>"""


def agent_mjcf(shape: AgentShape, pos: tuple[float, float] = (0.0, 0.0)) -> str:
    """The agent's MJCF ``<body>``: a free root at the pelvis, 18 hinges, keypoint sites."""
    s = shape
    head_r = 0.065 * s.height
    return f"""
  <body name="agent" pos="{pos[0]:.3f} {pos[1]:.3f} {s.pelvis_height:.3f}">
    <freejoint name="a:root"/>
    <site name="j:pelvis" size="0.01"/>
    <geom name="agent:pelvis" type="capsule"
          fromto="0 {s.hip + 0.03:.3f} 0 0 {-s.hip - 0.03:.3f} 0"
          size="{s.girth * 0.85:.3f}" rgba="{_rgb(s.pants)}"/>
    <body name="a:torso" pos="0 0 0.05">
      {_j("spine_pitch", "0 1 0", -0.5, 1.4)}
      {_j("spine_yaw", "0 0 1", -0.8, 0.8)}
      <site name="j:spine" pos="0 0 {s.torso * 0.5:.3f}" size="0.01"/>
      <geom name="agent:torso" type="capsule" fromto="0 0 0.05 0 0 {s.torso - 0.08:.3f}"
            size="{s.girth:.3f}" rgba="{_rgb(s.shirt)}"/>
      <geom name="agent:chest" type="capsule"
            fromto="0 {s.shoulder - 0.03:.3f} {s.torso - 0.06:.3f}
                    0 {-s.shoulder + 0.03:.3f} {s.torso - 0.06:.3f}"
            size="{s.girth * 0.6:.3f}" rgba="{_rgb(s.shirt)}"/>
      <body name="a:head" pos="0 0 {s.torso:.3f}">
        {_j("neck_yaw", "0 0 1", -1.3, 1.3)}
        {_j("neck_pitch", "0 1 0", -0.8, 0.9)}
        <site name="j:neck" size="0.01"/>
        <geom name="agent:neck" type="capsule" fromto="0 0 0 0 0 0.08" size="0.045"
              rgba="{_rgb(s.skin)}"/>
        <site name="j:head" pos="0 0 {0.08 + head_r:.3f}" size="0.01"/>
        <geom name="agent:head" type="sphere" pos="0.01 0 {0.08 + head_r:.3f}" size="{head_r:.3f}"
              rgba="{_rgb(s.skin)}"/>
        <geom name="agent:nose" type="sphere" pos="{head_r:.3f} 0 {0.08 + head_r:.3f}"
              size="{head_r * 0.22:.3f}" rgba="{_rgb(s.skin)}"/>
      </body>{_arm("l", s)}{_arm("r", s)}
    </body>{_leg("l", s)}{_leg("r", s)}
  </body>"""
