"""One episode: randomise the home, run the program, render it and write its members.

An episode is one WebDataset sample: members ``KEY.json`` (spec, program, steps, legends,
cameras), ``KEY.mp4`` (RGB, H.264), ``KEY.NNNNNN.<map>.png`` per frame (depth, class,
instance, flow; `homesim.dataset.encode`) and ``KEY.<array>.npy`` per-frame arrays (pose,
cameras, step of each frame). The frames stream from the recorder straight into the tar:
memory holds one frame and the compressed video, never the episode's images.
"""

from __future__ import annotations

import io
import json
import random
import tarfile
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from homesim.dataset import encode
from homesim.dataset.randomize import Move, Start, move_character, move_objects
from homesim.dataset.spec import FORMAT, DatasetConfig, EpisodeSpec
from homesim.dataset.tarfiles import MemberHash, add_member, open_writer
from homesim.errors import HomesimError
from homesim.files import atomic_write
from homesim.ground.pipeline import Run, run_program
from homesim.knowledge.kbtypes import default_kb
from homesim.processes import rasterize_in_drawing_thread
from homesim.program.parse import parse_program
from homesim.render.video import H264Writer
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import open_home

if TYPE_CHECKING:
    from homesim.render import Animation, FrameTruth

ARRAYS = ("camera", "intrinsics", "world_to_cam", "joints3d", "joints2d", "joints_visible",
          "cut", "step")


class EpisodeFailed(HomesimError):
    """An episode that cannot be made (its program does not ground in the home...)."""

    def __init__(self, stage: str, reason: str):
        self.stage, self.reason = stage, reason
        super().__init__(f"{stage}: {reason}")


@dataclass(frozen=True)
class Outcome:
    """What became of one episode (a row of the manifest)."""

    key: str
    index: int
    ok: bool
    stage: str | None = None  # where it failed: home, grounding, render, internal
    reason: str | None = None
    num_frames: int = 0
    num_steps: int = 0
    sha256: str | None = None  # `MemberHash` of its members
    bytes: dict[str, int] = field(default_factory=dict)  # member bytes per modality
    seconds: float = 0.0  # wall time (not part of the manifest: it varies run to run)
    home: str | None = None  # where it was made (the spec's or one of `homes_to_try`)

    def to_row(self, spec: EpisodeSpec) -> dict[str, Any]:
        return {"key": self.key, "index": self.index, "status": "ok" if self.ok else "failed",
                "stage": self.stage, "reason": self.reason, "program_id": spec.program_id,
                "home": self.home or spec.home, "drawn_home": spec.home,
                "agent": spec.agent, "speed": spec.speed,
                "render_seed": spec.render_seed, "ground_seed": spec.ground_seed,
                "placement_seed": spec.placement_seed, "moves": spec.moves,
                "num_frames": self.num_frames, "num_steps": self.num_steps,
                "sha256": self.sha256, "bytes": sum(self.bytes.values()),
                **{f"bytes_{k}": v for k, v in sorted(self.bytes.items())}}


@dataclass(frozen=True)
class EpisodeHome:
    """The home of an episode after its random changes, and the program run in it."""

    home: str
    run: Run
    moves: list[Move]
    start: Start | None


def build_home(spec: EpisodeSpec, home: str
               ) -> tuple[EnvironmentGraph, list[Move], Start | None]:
    """`home` with objects moved and the agent placed (from the spec's `placement_seed`)."""
    try:
        graph = open_home(home)
    except HomesimError as e:
        raise EpisodeFailed("home", str(e)) from None
    rng = random.Random(spec.placement_seed)
    graph, moves = move_objects(graph, spec.moves, rng, default_kb())
    graph, start = move_character(graph, rng)
    return graph, moves, start


def homes_to_try(spec: EpisodeSpec, homes: Sequence[str]) -> list[str]:
    """The spec's home, then the other `homes` in an order drawn from its placement seed."""
    others = sorted(set(homes) - {spec.home})
    random.Random(f"homesim-episode-homes-{spec.placement_seed}").shuffle(others)
    return [spec.home, *others]


def ground_episode(spec: EpisodeSpec, homes: Sequence[str] = ()) -> EpisodeHome:
    """Randomise the spec's home and run the program there (`run_program`, `ground_seed`);
    where it does not run, the next of `homes_to_try` that it runs in. The reason given
    when it runs in none is the spec's home's."""
    program = parse_program(spec.program)
    first: EpisodeFailed | None = None
    for home in homes_to_try(spec, homes):
        try:
            graph, moves, start = build_home(spec, home)
        except EpisodeFailed as e:
            first = first or e
            continue
        run = run_program(program, graph, seed=spec.ground_seed, trace=True, repair=False)
        if run.executable and run.grounding is not None:
            return EpisodeHome(home, run, moves, start)
        first = first or EpisodeFailed(run.stage or "execution", run.message)
    assert first is not None  # homes_to_try gives at least the spec's home
    raise first


def write_episode_file(spec: EpisodeSpec, config: DatasetConfig, path: Path) -> Outcome:
    """Make the episode and write it as a tar at `path` (atomically: a failure leaves
    `path` as it was); a failure is an `Outcome` with its reason, never an exception
    (Ctrl-C and kills still stop it)."""
    rasterize_in_drawing_thread()  # Ray workers get it from `runners.task_environment`
    t0 = time.perf_counter()
    try:
        with atomic_write(path, "wb") as f:
            outcome = write_episode(spec, config, f)
    except EpisodeFailed as e:
        outcome = Outcome(spec.key, spec.index, False, e.stage, _one_line(e.reason))
    except HomesimError as e:
        outcome = Outcome(spec.key, spec.index, False, "render", _one_line(str(e)))
    except Exception as e:  # a bug of ours: record it, keep the run going
        outcome = Outcome(spec.key, spec.index, False, "internal",
                          _one_line(f"{type(e).__name__}: {e}"))
    return Outcome(**{**outcome.__dict__, "seconds": time.perf_counter() - t0})


def _one_line(text: str) -> str:
    return " ".join(text.split())[:500]


def write_episode(spec: EpisodeSpec, config: DatasetConfig, fileobj: Any) -> Outcome:
    """Ground, animate and record the episode into a tar stream: the `Run` of
    `ground_episode` animated (`homesim.render.animate`) and drawn by render's one loop
    (`homesim.render.play`) into the episode's writer, a `FrameSink`."""
    from homesim.render import animate, check_length, play

    home = ground_episode(spec, config.homes)
    animation = animate(home.run, width=config.width, height=config.height, fps=config.fps,
                        seed=spec.render_seed, agent=spec.agent, speed=spec.speed)
    check_length(animation)
    writer = _EpisodeWriter(spec, config, fileobj, len(animation))
    writer.start(_meta(spec, config, home, animation))
    play(animation, writer, flow="flow" in config.modalities)
    return replace(writer.finish(animation.timeline.step_frames), home=home.home)


class _EpisodeWriter:
    """Streams an episode's members into a tar (see the module docstring): a
    `homesim.render.FrameSink` of `total` frames."""

    def __init__(self, spec: EpisodeSpec, config: DatasetConfig, fileobj: Any, total: int):
        self.spec, self.config, self.total = spec, config, total
        self.tar: tarfile.TarFile = open_writer(fileobj)
        self.hash = MemberHash()
        self.sizes: dict[str, int] = {}
        self.arrays: dict[str, list[Any]] = {k: [] for k in ARRAYS if k != "step"}
        self.video: H264Writer | None = None
        self.codes = encode.InstanceCodes({})

    def put(self, suffix: str, data: bytes, modality: str) -> None:
        name = f"{self.spec.key}.{suffix}"
        add_member(self.tar, name, data)
        self.hash.add(name, data)
        self.sizes[modality] = self.sizes.get(modality, 0) + len(data)

    def start(self, meta: dict[str, Any]) -> None:
        self.codes = encode.InstanceCodes(
            {item["node_id"]: item["index"] for item in meta["instances"]})
        self.put("json", json.dumps(meta, indent=1, sort_keys=True).encode(), "json")
        if "rgb" in self.config.modalities:
            self.video = H264Writer(self.config.width, self.config.height, self.config.fps)

    def add(self, truth: FrameTruth) -> None:
        if self.video is not None:
            self.video.add(truth.rgb)
        for name in self.arrays:
            self.arrays[name].append(getattr(truth, name))
        if truth.index % self.config.gt_stride:
            return
        stem, mods = f"{truth.index:06d}", self.config.modalities
        if "depth" in mods:
            self.put(f"{stem}.depth.png", encode.encode_depth(truth.depth), "depth")
        if "class" in mods:
            self.put(f"{stem}.class.png", encode.png16(truth.class_seg), "class")
        if "instance" in mods:
            self.put(f"{stem}.instance.png",
                     encode.encode_instances(truth.instance_seg, self.codes), "instance")
        if "flow" in mods:
            self.put(f"{stem}.flow.png", encode.encode_flow(*_flow(
                truth, last=truth.index == self.total - 1)), "flow")

    def finish(self, step_frames: list[tuple[int, int]]) -> Outcome:
        if self.video is not None:
            self.put("mp4", self.video.close(), "rgb")
        total = len(self.arrays["camera"])
        for name, values in self.arrays.items():
            self.put(f"{name}.npy", _npy(np.asarray(values, _DTYPES[name])), "pose")
        self.put("step.npy", _npy(frame_steps(step_frames, total)), "pose")
        self.tar.close()
        return Outcome(self.spec.key, self.spec.index, True, num_frames=total,
                       num_steps=len(step_frames), sha256=self.hash.hexdigest(),
                       bytes=dict(self.sizes))


_DTYPES: Mapping[str, Any] = {
    "camera": np.int16, "intrinsics": np.float32, "world_to_cam": np.float32,
    "joints3d": np.float32, "joints2d": np.float32, "joints_visible": np.bool_,
    "cut": np.bool_}


def _flow(truth: FrameTruth, last: bool) -> tuple[np.ndarray, np.ndarray]:
    """The frame's flow and where it is valid (nowhere on the last frame: no next one)."""
    if truth.flow is None or truth.flow_valid is None:
        raise AssertionError("flow was not computed for an episode that keeps it")
    return truth.flow, np.zeros_like(truth.flow_valid) if last else truth.flow_valid


def frame_steps(step_frames: list[tuple[int, int]], total: int) -> np.ndarray:
    """(T,) int16: the step each frame shows (-1 for none; a later step wins a shared
    frame)."""
    out = np.full(total, -1, np.int16)
    for i, (a, b) in enumerate(step_frames):
        out[a:b + 1] = i
    return out


def _npy(array: np.ndarray) -> bytes:
    buf = io.BytesIO()
    np.save(buf, array, allow_pickle=False)
    return buf.getvalue()


def _meta(spec: EpisodeSpec, config: DatasetConfig, home: EpisodeHome,
          animation: Animation) -> dict[str, Any]:
    from homesim.render.agent import JOINTS
    from homesim.render.flow import intrinsics

    scene, timeline, agent = animation.scene, animation.timeline, animation.agent
    program = parse_program(spec.program)
    grounded = animation.program
    class_ids = {name: i for i, name in enumerate(scene.classes)}
    legend = scene.instances  # a property that builds a dict: read it once
    nodes = sorted(set(legend) | {scene.character_id})
    instances = [{"index": 0, "node_id": 0, "class": "background", "class_id": 0}]
    for i, n in enumerate(nodes, start=1):
        cls = legend.get(n, "character")
        instances.append({"index": i, "node_id": n, "class": cls,
                          "class_id": class_ids.get(cls, 0)})
    prepared = home.run.prepared
    w, h = config.width, config.height
    return {
        "format": FORMAT, "key": spec.key, "spec": spec.to_dict(),
        "title": program.title, "description": program.description,
        "program": "\n".join(str(s) for s in program.steps),
        "grounded_program": "\n".join(str(s) for s in grounded.steps),
        "home": home.home, "agent": agent, "width": w, "height": h, "fps": config.fps,
        "num_frames": len(timeline), "gt_stride": config.gt_stride,
        "modalities": list(config.modalities),
        "steps": [{"index": i, "step": str(program.steps[i]), "grounded": str(grounded.steps[i]),
                   "action": program.steps[i].action.key, "start_frame": a, "end_frame": b}
                  for i, (a, b) in enumerate(timeline.step_frames)],
        "classes": list(scene.classes), "instances": instances,
        "character_id": scene.character_id, "joints": list(JOINTS),
        "cameras": [{"name": c.name, "room_id": c.room_id, "fovy": c.fovy,
                     "aimed_at_agent": c.shot < 0,
                     "position": [float(x) for x in c.pos],
                     "intrinsics": intrinsics(w, h, c.fovy).tolist()} for c in scene.cameras],
        "moves": [m.to_dict() for m in home.moves],
        "start": None if home.start is None else home.start.to_dict(),
        "added": [] if prepared is None else [
            {"node_id": a.node_id, "class": a.class_name} for a in prepared.added],
        "units": UNITS,
    }


UNITS = {
    "depth": "PNG uint16 millimetres along the optical axis, 0 = nothing seen",
    "class": "PNG uint16 index into classes, 0 = background",
    "instance": "PNG uint16 index into instances (node_id, class), 0 = background",
    "flow": "PNG uint16 (2H, W): u rows then v rows, round(64 px) + 32768, 0 = invalid",
    "world": "metres, MuJoCo frame (z up) = Unity (x, z, y)",
    "camera": "OpenCV: x right, y down, z forward; pixel centres at integers",
}
