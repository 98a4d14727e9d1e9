"""What a data set is made of: its options (`DatasetConfig`) and each episode's random
choices (`EpisodeSpec`), drawn from the seed and recorded so that an episode can be
rendered again exactly (`homesim dataset replay`).

Every episode draws from its own stream, ``random.Random("homesim-episode-SEED-INDEX")``,
so an episode's choices do not depend on which episodes ran before it, in what order or
on which worker: resuming and scaling out give the same episodes.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

from homesim.errors import DataError, HomesimError, LimitError
from homesim.limits import MAX_EPISODES

AGENT_NAMES: tuple[str, ...] = ("male1", "female1", "male2", "female2")
"""The four agents of `homesim.render.agent.AGENTS` (a test keeps the two equal)."""

DEFAULT_HOMES: tuple[str, ...] = (
    "scene1", "scene2", "scene3", "scene4", "scene5", "gen-0", "gen-1", "gen-2", "gen-3",
    "gen-4")
"""The five apartments and five generated homes (`homesim.world.procedural`)."""

MODALITIES: tuple[str, ...] = ("rgb", "depth", "class", "instance", "flow")
"""Per-frame images an episode can hold; pose, cameras and step spans are always kept."""



@dataclass(frozen=True)
class Profile:
    """What each episode of a data set keeps: image size, frame rate, per-frame maps."""

    width: int
    height: int
    fps: int
    modalities: tuple[str, ...]
    gt_stride: int = 1


PROFILES: dict[str, Profile] = {
    "full": Profile(320, 240, 15, MODALITIES),
    "learn": Profile(64, 48, 4, ("rgb", "class")),
}
"""The named profiles of ``homesim dataset generate --profile``: ``full`` (the default)
keeps every modality at 320x240, 15 frames/s; ``learn`` only what the video models read
(`homesim.learn.video.cache.VideoFormat`: 64x48 at 4 frames/s, RGB and class maps), so
nothing is drawn, computed or stored for them to throw away."""

SPEED_RANGE = (0.8, 1.25)
"""Action speed factor drawn per episode: every motion takes 1/speed of its time."""

MAX_MOVES = 6
"""At most this many objects are moved to other allowed places per episode."""

FORMAT = "homesim-activity/8"
"""Data set format; /2: the mp4 encoded as `video.H264Writer` does since x264 was pinned
to SSE2 (other bytes than /1 for the same frames); /3: an episode whose program does not
run in its drawn home is made in the next home it runs in (`episode.homes_to_try`; /2
recorded it as failed), and the manifest has a `drawn_home` column; /4: a room camera is
turned toward the agent and zoomed in on it each time it is chosen (`cameras.aimed`; /3
and before kept them fixed); /5: a room camera with something close in front of it (a
wall edge, a door) scores less when cameras are chosen (`recorder.BLOCK_PENALTY`), and
a step that no candidate close-up shows gets none (`shots.plan_shots`); /6: the close-up
of switching a screen on or off is chosen by how much of the screen it shows, not of the
whole set (`shots._seen_part`; /5 often filmed a TV's back); /7: issue 43's third round
(close-ups of small things framed at the effect, reaches and walks never from behind a
wall, put back where taken from, carried water, fingertips on switches) gives other
close-ups and poses, and where a reach or walk changed, other frame counts; /8: issue
43's fourth and fifth rounds (bodies out of furniture: standing spots on the object's
side of walls, reaches that bow less, sitting where the seat is clear, stepping back
before drinking, letting a door's handle go) give other poses and walks."""


@dataclass(frozen=True)
class DatasetConfig:
    """The options of ``homesim dataset generate``: a run restarted with the same config
    continues; a different config in the same folder is refused."""

    programs: str = "synth"  # "synth" or a program file / folder / JSONL data set
    n: int = 200
    seed: int = 0
    width: int = 320
    height: int = 240
    fps: int = 15
    modalities: tuple[str, ...] = MODALITIES
    gt_stride: int = 1  # dense maps (depth, class, instance, flow) every k-th frame
    homes: tuple[str, ...] = DEFAULT_HOMES  # names, or graph files (.json, .json.gz)
    shard_size: int = 8  # episodes per shard
    format: str = FORMAT
    agents: tuple[str, ...] = AGENT_NAMES

    def __post_init__(self) -> None:
        unknown = [m for m in self.modalities if m not in MODALITIES]
        if unknown:
            raise HomesimError(f"unknown modality {unknown[0]!r}; choose from "
                               f"{', '.join(MODALITIES)}")
        if self.n < 1 or self.gt_stride < 1 or self.shard_size < 1:
            raise HomesimError("--n, --gt-stride and --shard-size must be at least 1")
        if max(self.n, self.gt_stride, self.shard_size) > MAX_EPISODES:
            raise LimitError(f"--n, --gt-stride and --shard-size must be at most "
                             f"{MAX_EPISODES:,} (MAX_EPISODES)", "MAX_EPISODES")
        if not self.homes:
            raise HomesimError("no homes to choose from")
        bad = [a for a in self.agents if a not in AGENT_NAMES]
        if bad or not self.agents:
            raise HomesimError(f"agent {bad[0] if bad else ''!r}: choose from "
                               f"{', '.join(AGENT_NAMES)}")
        from homesim.render.video import check_size  # reading a data set needs no renderer

        check_size(self.width, self.height, self.fps)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["modalities"], d["homes"] = list(self.modalities), list(self.homes)
        d["agents"] = list(self.agents)
        return d

    @classmethod
    def from_dict(cls, data: Any) -> DatasetConfig:
        """The config a data set's json recorded; `DataError` naming the field that is
        missing or of the wrong type."""
        d = typed_fields(data, _CONFIG_TYPES, "config", required=False)
        try:
            return cls(**d)
        except HomesimError as e:
            raise DataError(f"config: {e}") from None

    @classmethod
    def from_profile(cls, profile: str, **options: Any) -> DatasetConfig:
        """The config of a named profile (`PROFILES`), `options` overriding its values."""
        if profile not in PROFILES:
            raise HomesimError(f"unknown profile {profile!r}; choose from "
                               f"{', '.join(PROFILES)}")
        return cls(**{**asdict(PROFILES[profile]), **options})

    @property
    def num_shards(self) -> int:
        return -(-self.n // self.shard_size)


@dataclass(frozen=True)
class EpisodeSpec:
    """Everything that decides one episode: with the config's size, fps and modalities
    it renders to the same bytes every time."""

    index: int
    program_id: str
    program: str  # the program's text: title, description, steps (`parse_program`)
    home: str
    agent: str
    render_seed: int  # cameras (positions, angles, fields of view) and render details
    ground_seed: int  # preparation and grounding: which instances the program acts on
    placement_seed: int  # which objects move where, and the agent's start
    moves: int  # how many objects to try to move
    speed: float  # action speed factor
    extra: dict[str, Any] = field(default_factory=dict, compare=False)

    @property
    def key(self) -> str:
        """The episode's WebDataset key (``ep-000042``)."""
        return episode_key(self.index)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("extra")
        return d

    @classmethod
    def from_dict(cls, data: Any) -> EpisodeSpec:
        return cls(**typed_fields(data, _SPEC_TYPES, "episode spec"))


_CONFIG_TYPES: dict[str, type] = {
    "programs": str, "n": int, "seed": int, "width": int, "height": int, "fps": int,
    "modalities": tuple, "gt_stride": int, "homes": tuple, "shard_size": int, "format": str,
    "agents": tuple}
_SPEC_TYPES: dict[str, type] = {
    "index": int, "program_id": str, "program": str, "home": str, "agent": str,
    "render_seed": int, "ground_seed": int, "placement_seed": int, "moves": int,
    "speed": float}


def typed_fields(data: Any, types: dict[str, type], what: str, required: bool = True
                 ) -> dict[str, Any]:
    """The fields of JSON object `data` named in `types`, each checked to be of its type
    (``tuple``: a list of strings; ``float``: any number); `DataError` naming the first
    that is not. Missing fields are an error when `required`, else left out."""
    if not isinstance(data, dict):
        raise DataError(f"{what}: expected a JSON object")
    out: dict[str, Any] = {}
    for name, kind in types.items():
        if name not in data:
            if required:
                raise DataError(f"{what} lacks {name!r}")
            continue
        value = data[name]
        if kind is tuple and isinstance(value, list) and all(isinstance(v, str)
                                                             for v in value):
            value = tuple(value)
        elif kind is float and type(value) in (int, float):
            value = float(value)
        elif type(value) is not kind:
            wanted = "a list of strings" if kind is tuple else kind.__name__
            raise DataError(f"{what}: {name!r} must be {wanted}, got {str(value)[:40]!r}")
        out[name] = value
    return out


def episode_key(index: int) -> str:
    return f"ep-{index:06d}"


def draw_spec(config: DatasetConfig, index: int, program_id: str, program: str
              ) -> EpisodeSpec:
    """The random choices of episode `index` (its own stream; see the module docstring)."""
    rng = random.Random(f"homesim-episode-{config.seed}-{index}")
    home = rng.choice(config.homes)
    agent = rng.choice(config.agents)
    seeds = [rng.randrange(2**31) for _ in range(3)]
    moves = rng.randint(0, MAX_MOVES)
    speed = round(rng.uniform(*SPEED_RANGE), 3)
    return EpisodeSpec(index, program_id, program, home, agent, seeds[0], seeds[1], seeds[2],
                       moves, speed)


def plan_episodes(config: DatasetConfig, programs: Sequence[tuple[str, str]]
                  ) -> list[EpisodeSpec]:
    """One spec per episode; program i of `programs` (id, text) goes to episode i, cycling
    when there are fewer programs than episodes."""
    if not programs:
        raise HomesimError(f"{config.programs}: no programs")
    return [draw_spec(config, i, *programs[i % len(programs)]) for i in range(config.n)]
