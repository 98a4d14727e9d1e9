"""The paper's Table 2: train the clip and video -> program models, then score every row.

`train_video(data, out, config)` writes to OUT: ``clip_<input>_<kind>.pt`` (clip models:
config, head labels, class columns, weights), ``mle.pt``, ``pg_lcs.pt``, ``pg_lcs_sim.pt``
(`Text2Prog` checkpoints of the video model: config and step vocabulary) and
``train.json`` (sizes, seed, wall times). `evaluate_video(out)` scores the test-seen and
test-unseen parts (`homesim.learn.videosplits`) and returns the rows.
"""

from __future__ import annotations

import copy
import json
import random
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

import torch

from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.learn import clips as C
from homesim.learn.execution import executable
from homesim.learn.metrics import score
from homesim.learn.text2prog import Text2Prog
from homesim.learn.train import TrainConfig, train_mle, train_pg
from homesim.learn.video2prog import Video2Prog, episode_features
from homesim.learn.videodata import Episode, load_episodes
from homesim.learn.videosplits import video_split
from homesim.program.model import Program

CLIP_MODELS = (("rgb", "trn"), ("rgb", "single"), ("oracle", "trn"))
PROGRAM_MODELS = {"mle": "MLE", "pg_lcs": "PG (LCS)", "pg_lcs_sim": "PG (LCS+Sim)"}
TESTS = {"test-seen": "seen homes", "test-unseen": "unseen homes"}
Report = Callable[[str], None]


@dataclass
class VideoRunConfig:
    """Everything a Table 2 run depends on; saved in train.json."""

    data: str
    seed: int = 0
    clip_epochs: int = 30
    mle_epochs: int = 60
    pg_epochs: int = 10
    batch_size: int = 16
    pg_lr: float = 5e-4


def _say(report: Report | None, line: str) -> None:
    if report:
        report(line)


def _clip_path(out: Path, kind: str, inp: str) -> Path:
    return out / f"clip_{inp}_{kind}.pt"


def save_clip_model(model: C.ClipModel, labels: C.Labels, classes: dict[str, int],
                    path: Path) -> None:
    """Config, head labels, class columns and weights in one file."""
    data = {"config": model.cfg.to_dict(), "state": model.state_dict(),
            "actions": labels.actions, "steps": labels.steps, "classes": classes}
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


def _video_model(train: list[Episode], clip_model: C.ClipModel, episodes: list[Episode],
                 seed: int, device: str) -> Video2Prog:
    v2p = Video2Prog.create_video([e.example for e in train], clip_model.cfg.feature, seed,
                                  device)
    v2p.features = {e.example.id: episode_features(clip_model, e, "rgb") for e in episodes}
    return v2p


def train_video(config: VideoRunConfig, out: Path, device: str = "cpu",
                report: Report | None = None) -> dict:
    """Train the three clip models and the three video -> program models; see the module."""
    out.mkdir(parents=True, exist_ok=True)
    episodes, classes = load_episodes(config.data)
    parts = video_split(episodes, config.seed)
    if not parts["train"]:
        raise HomesimError(f"{config.data}: no training episodes (seen homes, train agents)")
    seconds: dict[str, float] = {}
    models = {}
    for inp, kind in CLIP_MODELS:
        start = time.perf_counter()
        data = C.clip_set(parts["train"], inp, C.TRAIN_HOP)
        labels = C.Labels.build(data)
        cfg = C.ClipConfig(kind, inp, len(classes), len(labels.actions), len(labels.steps),
                           epochs=config.clip_epochs, seed=config.seed)
        model = C.train_clip_model(cfg, data, labels, device)
        save_clip_model(model, labels, classes, _clip_path(out, kind, inp))
        models[(inp, kind)] = model
        seconds[f"clip_{inp}_{kind}"] = time.perf_counter() - start
        _say(report, f"clip {inp} {kind}: {len(data.steps)} clips, "
             f"{seconds[f'clip_{inp}_{kind}']:.0f} s")
    train = [e.example for e in parts["train"]]
    start = time.perf_counter()
    v2p = _video_model(parts["train"], models[("rgb", "trn")], parts["train"], config.seed,
                       device)
    mle_cfg = TrainConfig(epochs=config.mle_epochs, batch_size=config.batch_size,
                          seed=config.seed)
    v2p.meta.update(model="mle", history=train_mle(v2p, train, mle_cfg))
    v2p.save(out / "mle.pt")
    seconds["mle"] = time.perf_counter() - start
    _say(report, f"MLE: {len(train)} episodes, {seconds['mle']:.0f} s")
    for name, use_sim in (("pg_lcs", False), ("pg_lcs_sim", True)):
        start = time.perf_counter()
        pg_model = copy.deepcopy(v2p)
        pg_cfg = TrainConfig(epochs=config.pg_epochs, batch_size=config.batch_size,
                             lr=config.pg_lr, seed=config.seed)
        pg_model.meta.update(model=name, history=train_pg(pg_model, train, pg_cfg, use_sim))
        pg_model.save(out / f"{name}.pt")
        seconds[name] = time.perf_counter() - start
        _say(report, f"{PROGRAM_MODELS[name]}: {seconds[name]:.0f} s")
    summary = {"config": asdict(config), "episodes": {p: len(v) for p, v in parts.items()},
               "clips": {p: sum(len(e.clips()) for e in v) for p, v in parts.items()},
               "train_seconds": seconds, "device": device}
    write_text(out / "train.json", json.dumps(summary, indent=2) + "\n")
    return summary


def _clip_rows(out: Path, parts: dict[str, list[Episode]], seed: int, device: str
               ) -> dict[str, dict[str, dict[str, float]]]:
    """Left half: {test part: {row: {action, step}}} mean per-class accuracy (%)."""
    train_sets = {inp: C.clip_set(parts["train"], inp) for inp in ("rgb", "oracle")}
    rows: dict[str, dict[str, dict[str, float]]] = {}
    for part in (p for p in TESTS if parts[p]):
        sets = {inp: C.clip_set(parts[part], inp) for inp in ("rgb", "oracle")}
        truth = sets["rgb"]
        n = len(truth.steps)
        rows[part] = {"Random retrieval": {
            "action": C.mean_class_accuracy(
                C.random_retrieval(train_sets["rgb"].actions, n, seed), truth.actions),
            "step": C.mean_class_accuracy(
                C.random_retrieval(train_sets["rgb"].steps, n, seed), truth.steps),
            "n": n}}
        for inp, kind in CLIP_MODELS:
            model, labels = load_clip_model(_clip_path(out, kind, inp), device)
            actions, steps = C.predict_clips(model, sets[inp], labels)
            name = {"trn": "TRN", "single": "Single frame"}[kind]
            name += " (oracle perception: class maps)" if inp == "oracle" else " (RGB)"
            rows[part][name] = {"action": C.mean_class_accuracy(actions, truth.actions),
                                "step": C.mean_class_accuracy(steps, truth.steps), "n": n}
    return rows


def _program_rows(out: Path, parts: dict[str, list[Episode]], seed: int, device: str
                  ) -> dict[str, dict[str, dict]]:
    """Right half: {test part: {row: Scores dict}}."""
    clip_model, _ = load_clip_model(_clip_path(out, "trn", "rgb"), device)
    everything = [e for p in parts.values() for e in p]
    models = {}
    for name in PROGRAM_MODELS:
        base = Text2Prog.load(out / f"{name}.pt", device)
        models[name] = Video2Prog(base.model, base.words, base.steps, base.meta)
        models[name].features = {e.example.id: episode_features(clip_model, e, "rgb")
                                 for e in everything}
    train_programs = [e.example.program for e in parts["train"]]
    rows: dict[str, dict[str, dict]] = {}
    for part in (p for p in TESTS if parts[p]):
        test = [e.example for e in parts[part]]
        rng = random.Random(seed)
        preds: dict[str, list[Program]] = {
            "Random retrieval": [rng.choice(train_programs) for _ in test],
            **{label: models[name].predict(test) for name, label in PROGRAM_MODELS.items()},
            "Ground truth (reference)": [e.program for e in test]}
        rows[part] = {}
        for row, programs in preds.items():
            flags = [executable(p, e) for p, e in zip(programs, test, strict=True)]
            rows[part][row] = score(programs, [e.program for e in test], flags).to_dict()
    return rows


def evaluate_video(out: Path, device: str = "cpu") -> dict:
    """Every row of Table 2 on the run in `out` (its train.json names the data set)."""
    path = out / "train.json"
    if not path.is_file():
        raise HomesimError(f"{path}: not found; run 'homesim learn train --task video2prog'")
    summary = json.loads(path.read_text(encoding="utf-8"))
    config = VideoRunConfig(**summary["config"])
    episodes, _ = load_episodes(config.data)
    parts = video_split(episodes, config.seed)
    start = time.perf_counter()
    result = {"train": summary, "clips": _clip_rows(out, parts, config.seed, device),
              "programs": _program_rows(out, parts, config.seed, device)}
    result["eval_seconds"] = time.perf_counter() - start
    return result
