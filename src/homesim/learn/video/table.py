"""The paper's Table 2, training: the clip models and the video -> program models, per seed.

`train_video(config, out)` reads the data set once (`videodata`, frames reduced and cached
per shard), splits it (`videosplits`: train, val, test parts), and for each seed writes to
``OUT/seed-<seed>/``: ``frame_cnn.pt`` (the RGB backbone, `homesim.learn.video.framecnn`),
``clip_<input>_<kind>.pt`` (clip models: config, head labels, class columns, weights),
``mle.pt``, ``pg_lcs.pt``, ``pg_lcs_sim.pt`` (`Text2Prog` checkpoints of the video model:
config, step vocabulary, meta with the chosen epoch), and ``OUT/train.json`` (config,
sizes, wall times). Every model keeps the weights of its best epoch on the validation
home. Scoring is `homesim.learn.video.eval`.
"""

from __future__ import annotations

import copy
import json
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import torch

from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.learn.text.train import BestOnDev, TrainConfig, train_mle, train_pg
from homesim.learn.video import clips as C
from homesim.learn.video.cache import VideoFormat
from homesim.learn.video.data import Episode, load_episodes
from homesim.learn.video.framecnn import (
    FrameCNN,
    FrameCNNConfig,
    frame_features,
    frame_set,
    train_frame_cnn,
)
from homesim.learn.video.splits import video_split
from homesim.learn.video.video2prog import Video2Prog, episode_features

CLIP_MODELS = (("rgb", "trn"), ("rgb", "single"), ("oracle", "trn"))
PROGRAM_MODELS = {"mle": "MLE", "pg_lcs": "PG (LCS)", "pg_lcs_sim": "PG (LCS+Sim)"}
DEFAULT_CACHE = Path.home() / ".cache" / "homesim" / "video"
Report = Callable[[str], None]


@dataclass
class VideoRunConfig:
    """Everything a Table 2 run depends on; saved in train.json."""

    data: str
    seeds: list[int] = field(default_factory=lambda: [0])
    frame_size: str = "64x48"
    fps: int = 4
    cache: str | None = str(DEFAULT_CACHE)
    workers: int = 2
    """Processes reducing shards not yet cached."""
    frame_epochs: int = 8
    clip_epochs: int = 30
    mle_epochs: int = 60
    pg_epochs: int = 10
    batch_size: int = 16
    pg_lr: float = 5e-4

    @property
    def format(self) -> VideoFormat:
        return VideoFormat.parse(self.frame_size, self.fps)


def _say(report: Report | None, line: str) -> None:
    if report:
        report(line)


def seed_dir(out: Path, seed: int) -> Path:
    return out / f"seed-{seed}"


def clip_path(folder: Path, kind: str, inp: str) -> Path:
    return folder / f"clip_{inp}_{kind}.pt"


def read_data(config: VideoRunConfig) -> tuple[dict[str, list[Episode]], dict[str, int]]:
    """The episodes of each split part, and the class columns."""
    episodes, classes = load_episodes(config.data, config.format,
                                      Path(config.cache) if config.cache else None,
                                      config.workers)
    return video_split(episodes), classes


def save_clip_model(model: C.ClipModel, labels: C.Labels, classes: dict[str, int],
                    path: Path, best_epoch: int | None) -> None:
    """Config, head labels, class columns, chosen epoch and weights in one file."""
    data = {"config": model.cfg.to_dict(), "state": model.state_dict(),
            "actions": labels.actions, "steps": labels.steps, "classes": classes,
            "best_epoch": best_epoch}
    buffer = path.with_suffix(".tmp")
    torch.save(data, buffer)
    buffer.replace(path)


def load_clip_model(path: Path, device: str = "cpu") -> tuple[C.ClipModel, C.Labels]:
    """A clip model written by `save_clip_model`."""
    try:
        data = torch.load(path, map_location=device, weights_only=True)
        model = C.ClipModel(C.ClipConfig(**data["config"])).to(device)
        model.load_state_dict(data["state"])
    except (OSError, KeyError, TypeError, RuntimeError) as e:
        raise HomesimError(f"{path}: not a clip model checkpoint ({e})") from None
    return model.eval(), C.Labels(data["actions"], data["steps"])


def descriptors(episodes: list[Episode], inp: str, cnn: FrameCNN | None) -> C.Descriptors:
    """Each episode's frame descriptors: class pixel shares (oracle) or CNN features."""
    if inp == "oracle":
        return {e.key: e.classes for e in episodes}
    assert cnn is not None
    return frame_features(cnn, episodes)


def video_features(clip_model: C.ClipModel, episodes: list[Episode], rgb: C.Descriptors
                   ) -> dict[str, torch.Tensor]:
    """Each episode's sequence of RGB TRN clip features, by example id."""
    return {e.example.id: episode_features(clip_model, e, rgb[e.key]) for e in episodes}


def save_frame_cnn(model: FrameCNN, best_epoch: int | None, path: Path) -> None:
    torch.save({"config": model.cfg.to_dict(), "state": model.state_dict(),
                "best_epoch": best_epoch}, path)


def load_frame_cnn(path: Path, device: str = "cpu") -> FrameCNN:
    """A frame CNN written by `save_frame_cnn`."""
    try:
        data = torch.load(path, map_location=device, weights_only=True)
        model = FrameCNN(FrameCNNConfig(**data["config"])).to(device)
        model.load_state_dict(data["state"])
    except (OSError, KeyError, TypeError, RuntimeError) as e:
        raise HomesimError(f"{path}: not a frame CNN checkpoint ({e})") from None
    return model.eval()


def _train_cnn(config: VideoRunConfig, parts: dict[str, list[Episode]], labels: C.Labels,
               seed: int, folder: Path, device: str, report: Report | None) -> FrameCNN:
    start = time.perf_counter()
    train = frame_set(parts["train"], labels.actions, labels.steps)
    val = frame_set(parts["val"], labels.actions, labels.steps) if parts["val"] else None
    cfg = FrameCNNConfig(len(labels.actions), len(labels.steps), epochs=config.frame_epochs,
                         seed=seed)
    cnn, best_epoch, _ = train_frame_cnn(cfg, train, val, device)
    save_frame_cnn(cnn, best_epoch, folder / "frame_cnn.pt")
    _say(report, f"seed {seed} frame CNN: {len(train.frames)} frames, best epoch "
         f"{best_epoch}, {time.perf_counter() - start:.0f} s")
    return cnn


def _train_clips(config: VideoRunConfig, parts: dict[str, list[Episode]],
                 classes: dict[str, int], seed: int, folder: Path, device: str,
                 report: Report | None) -> tuple[C.ClipModel, C.Descriptors, dict[str, float]]:
    """The frame CNN and the three clip models of one seed; returns the RGB TRN model, the
    RGB descriptors of every episode and wall times."""
    start = time.perf_counter()
    everything = [e for v in parts.values() for e in v]
    oracle = descriptors(everything, "oracle", None)
    labels = C.Labels.build(C.clip_set(parts["train"], oracle, C.TRAIN_HOP))
    cnn = _train_cnn(config, parts, labels, seed, folder, device, report)
    vectors = {"oracle": oracle, "rgb": descriptors(everything, "rgb", cnn)}
    seconds = {"frame_cnn": time.perf_counter() - start}
    kept = None
    for inp, kind in CLIP_MODELS:
        start = time.perf_counter()
        data = C.clip_set(parts["train"], vectors[inp], C.TRAIN_HOP)
        cfg = C.ClipConfig(kind, inp, data.inputs.shape[2], len(labels.actions),
                           len(labels.steps), epochs=config.clip_epochs, seed=seed)
        val = C.clip_set(parts["val"], vectors[inp]) if parts["val"] else None
        trained = C.train_clip_model(cfg, data, labels, val, device)
        save_clip_model(trained.model, labels, classes, clip_path(folder, kind, inp),
                        trained.best_epoch)
        if (inp, kind) == ("rgb", "trn"):
            kept = trained.model
        seconds[f"clip_{inp}_{kind}"] = time.perf_counter() - start
        _say(report, f"seed {seed} clip {inp} {kind}: {len(data.steps)} clips, best epoch "
             f"{trained.best_epoch}, {seconds[f'clip_{inp}_{kind}']:.0f} s")
    assert kept is not None
    return kept, vectors["rgb"], seconds


def _train_programs(config: VideoRunConfig, parts: dict[str, list[Episode]],
                    clip_model: C.ClipModel, rgb: C.Descriptors, seed: int, folder: Path,
                    device: str, report: Report | None) -> dict[str, float]:
    """MLE, then PG (LCS) and PG (LCS+Sim) from it; each keeps its best epoch on val."""
    seconds: dict[str, float] = {}
    start = time.perf_counter()
    train = [e.example for e in parts["train"]]
    val = [e.example for e in parts["val"]]
    v2p = Video2Prog.create_video(train, clip_model.cfg.feature, seed, device)
    v2p.features = video_features(clip_model, parts["train"] + parts["val"], rgb)
    best = BestOnDev(v2p, val)
    cfg = TrainConfig(epochs=config.mle_epochs, batch_size=config.batch_size, seed=seed)
    history = train_mle(v2p, train, cfg, after_epoch=best if val else None)
    best.restore()
    v2p.meta.update(model="mle", history=history, val=best.scores, best_epoch=best.epoch)
    v2p.save(folder / "mle.pt")
    seconds["mle"] = time.perf_counter() - start
    _say(report, f"seed {seed} MLE: {len(train)} episodes, best epoch {best.epoch}, "
         f"{seconds['mle']:.0f} s")
    for name, use_sim in (("pg_lcs", False), ("pg_lcs_sim", True)):
        start = time.perf_counter()
        pg = copy.deepcopy(v2p)
        best = BestOnDev(pg, val, use_sim)
        if val:
            best(-1)  # the MLE weights are a candidate too (epoch -1)
        cfg = TrainConfig(epochs=config.pg_epochs, batch_size=config.batch_size,
                          lr=config.pg_lr, seed=seed)
        history = train_pg(pg, train, cfg, use_sim, after_epoch=best if val else None)
        best.restore()
        pg.meta.update(model=name, history=history, val=best.scores, best_epoch=best.epoch)
        pg.save(folder / f"{name}.pt")
        seconds[name] = time.perf_counter() - start
        _say(report, f"seed {seed} {PROGRAM_MODELS[name]}: best epoch {best.epoch}, "
             f"{seconds[name]:.0f} s")
    return seconds


def train_video(config: VideoRunConfig, out: Path, device: str = "cpu",
                report: Report | None = None) -> dict:
    """Train every model of every seed; see the module."""
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    parts, classes = read_data(config)
    load_seconds = time.perf_counter() - start
    _say(report, f"data: {', '.join(f'{p} {len(v)}' for p, v in parts.items())} episodes, "
         f"{load_seconds:.0f} s to read")
    if not parts["train"]:
        raise HomesimError(f"{config.data}: no training episodes (seen homes, train agents)")
    seconds: dict[str, dict[str, float]] = {}
    for seed in config.seeds:
        folder = seed_dir(out, seed)
        folder.mkdir(exist_ok=True)
        clip_model, rgb, clip_seconds = _train_clips(config, parts, classes, seed, folder,
                                                     device, report)
        seconds[str(seed)] = {**clip_seconds, **_train_programs(
            config, parts, clip_model, rgb, seed, folder, device, report)}
    summary = {"config": asdict(config), "episodes": {p: len(v) for p, v in parts.items()},
               "clips": {p: sum(len(e.clips()) for e in v) for p, v in parts.items()},
               "train_clips": sum(len(e.clips(hop=C.TRAIN_HOP)) for e in parts["train"]),
               "load_seconds": load_seconds, "train_seconds": seconds,
               "total_seconds": time.perf_counter() - start, "device": device}
    write_text(out / "train.json", json.dumps(summary, indent=2) + "\n")
    return summary
