"""The paper's Table 2, training: the frame models once, then the clip models and the
video -> program models of every seed, each stage resumable.

`train_video(config, out)` reads the data set into a frame store (`data`), then:

1. frame stage (once; seed `backbone_seed`): the RGB frame encoder, the segmentation
   network (`segment`; its pixel accuracy and mean IoU on validation and test frames go
   to ``OUT/frames/segment.json``), its predicted class map of every frame, and the map
   encoders on ground-truth and on predicted maps (`framecnn`); the pose network
   (`pose`; its joint error and PCK go to ``OUT/frames/pose.json``) and its predicted
   joints of every frame. Each encoder's 64-d feature of every frame goes to
   ``OUT/features/<input>.npy``, and ``seg+pose+hands.npy`` joins the predicted maps'
   feature with the predicted joints' descriptor and the predicted classes round the
   predicted wrists (`hands`): the frame-feature cache every seed and clip model reads.
2. per seed, ``OUT/seed-<seed>/``: the clip models (TRN on each input, single frame on
   RGB) and the video -> program models (MLE, PG (LCS), PG (LCS+Sim)) over the clip
   features of the TRN whose validation score is best among the inputs that are not the
   oracle.

Every model trains with a checkpoint per epoch (``*.ckpt``) and is saved when done
(``*.pt``); a stage whose result is on disk is skipped. So a job stopped at any point
(a sitting that ends) goes on where it was when run again, and ends with the same
numbers. ``OUT/train.json`` holds the config, the sizes and each stage's wall time.
"""

from __future__ import annotations

import copy
import hashlib
import json
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, fields, replace
from pathlib import Path

import numpy as np
import torch

from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.learn.text.train import BestOnDev, TrainConfig, train_mle, train_pg
from homesim.learn.video import clips as C
from homesim.learn.video.cache import VideoFormat
from homesim.learn.video.data import example, read_store
from homesim.learn.video.fit import FitResult
from homesim.learn.video.framecnn import (
    FrameCNNConfig,
    FrameLabels,
    frame_features,
    train_frame_cnn,
)
from homesim.learn.video.hands import hand_context, with_hands
from homesim.learn.video.pose import (
    PoseConfig,
    pose_descriptor,
    pose_scores,
    predict_joints,
    train_posenet,
)
from homesim.learn.video.segment import (
    SegConfig,
    predict_maps,
    segmentation_scores,
    train_segnet,
)
from homesim.learn.video.splits import Split
from homesim.learn.video.store import FrameStore, StoredEpisode
from homesim.learn.video.video2prog import Video2Prog, episode_features

BODY = "seg+pose+hands"
"""The predicted maps' feature joined with the predicted joints' descriptor and what the
predicted maps show round the predicted wrists (`hands`)."""
CLIP_MODELS = (("rgb", "trn"), ("rgb", "single"), ("seg", "trn"), (BODY, "trn"),
               ("oracle", "trn"))
PERCEIVED = ("rgb", "seg", BODY)
"""Inputs a model may read at test time (the oracle reads the ground truth)."""
INPUTS = ("rgb", "seg", BODY, "oracle")
"""Every input's frame features (``OUT/features/<input>.npy``)."""
ENCODED = ("rgb", "seg", "oracle")
"""The inputs read through one frame encoder (`framecnn`): those an end-to-end clip model
can hold; the others join features and read them fixed."""
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
    cache: str = str(DEFAULT_CACHE)
    workers: int = 2
    """Processes reducing shards not yet cached."""
    backbone_seed: int = 0
    frame_epochs: int = 6
    frames_per_epoch: int = 60000
    frame_lr: float = 2e-3
    frame_dropout: float = 0.3
    frame_grid: str = "1x1"
    """The frame encoders' last features averaged over WxH cells ("1x1": the spatial
    mean; "4x3" keeps where things are: `FrameCNNConfig.grid_w`)."""
    seg_epochs: int = 4
    seg_frames_per_epoch: int = 40000
    seg_width: int = 16
    seg_lr: float = 2e-3
    pose_epochs: int = 6
    pose_frames_per_epoch: int = 40000
    pose_width: int = 16
    pose_lr: float = 2e-3
    clip_epochs: int = 20
    clip_lr: float = 1e-3
    clip_feature: int = 128
    clip_hidden: int = 256
    clip_dropout: float = 0.3
    clip_end_to_end: bool = False
    """The clip models hold their frame encoder, started from the frame stage's, and
    fine-tune it with the TRN on the clips' labels (as TRN trains its backbone); False:
    they read the fixed frame features (`OUT/features/`)."""
    mle_epochs: int = 60
    mle_lr: float = 2e-3
    pg_epochs: int = 10
    batch_size: int = 16
    pg_lr: float = 5e-4
    sim_weight: float = 0.1
    """The PG (LCS+Sim) reward's bonus when the program executes (`TrainConfig`)."""
    train_share: float = 1.0
    """Share of the training episodes used (a learning curve: the first of them in an
    order fixed by their keys' hashes, `train_subset`); validation and test unchanged."""
    train_hop: float = C.TRAIN_HOP
    """Seconds between the starts of training clips (overlapping: twice the clips)."""
    word_dim: int = 64
    """The video -> program model's sizes (`Seq2SeqConfig`): clip features are projected
    to `word_dim`."""
    hidden: int = 100
    step_dim: int = 100

    @property
    def format(self) -> VideoFormat:
        return VideoFormat.parse(self.frame_size, self.fps)

    def with_settings(self, path: Path) -> VideoRunConfig:
        """These settings with the fields a JSON file names replaced (`--settings`)."""
        try:
            given = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as e:
            raise HomesimError(f"--settings {path}: not a readable JSON file ({e})") from None
        if not isinstance(given, dict):
            raise HomesimError(f"--settings {path}: a JSON object of settings, not "
                               f"{type(given).__name__}")
        known = {f.name for f in fields(self)} - {"data", "seeds"}
        for name, value in given.items():
            if name not in known:
                raise HomesimError(f"--settings {path}: {name!r} is not a setting of a video "
                                   "run (the fields of VideoRunConfig but data and seeds)")
            if not isinstance(value, type(getattr(self, name))) and not (
                    isinstance(getattr(self, name), float) and isinstance(value, int)):
                kind = {int: "an integer", float: "a number"}.get(type(getattr(self, name)),
                                                                  "text")
                raise HomesimError(f"--settings {path}: {name} must be {kind}, not {value!r}")
        return replace(self, **given)


@dataclass
class Run:
    """A run in progress: its folder, the store and split, and the wall times so far."""

    config: VideoRunConfig
    out: Path
    store: FrameStore
    split: Split
    device: str
    report: Report | None
    seconds: dict[str, float] = field(default_factory=dict)
    after_stage: Callable[[], object] | None = None
    """Called when a stage's time is recorded (`train_video` writes train.json then, so
    a sitting that ends inside a stage keeps the times of those done before it)."""

    def episodes(self, role: str) -> list[StoredEpisode]:
        eps = [e for p in self.split.parts(role) for e in self.store.part(p)]
        return train_subset(eps, self.config.train_share) if role == "train" else eps

    def say(self, line: str) -> None:
        if self.report:
            self.report(line)

    def timed(self, name: str, start: float) -> None:
        self.seconds[name] = self.seconds.get(name, 0.0) + time.perf_counter() - start
        self.say(f"{name}: {time.perf_counter() - start:.0f} s")
        if self.after_stage:
            self.after_stage()


def train_subset(episodes: list[StoredEpisode], share: float) -> list[StoredEpisode]:
    """The first `share` of `episodes` in an order fixed by their keys' hashes (nested:
    a smaller share's episodes are in every larger one's), in store order."""
    if share >= 1:
        return episodes
    if share <= 0:
        raise HomesimError(f"train_share {share}: a share in (0, 1]")
    ranked = sorted(episodes, key=lambda e: hashlib.sha256(e.key.encode()).digest())
    kept = {e.key for e in ranked[:max(1, round(share * len(episodes)))]}
    return [e for e in episodes if e.key in kept]


def seed_dir(out: Path, seed: int) -> Path:
    return out / f"seed-{seed}"


def train_labels(run: Run) -> C.Labels:
    """The heads' classes: those of the training clips (1-s hop)."""
    return C.Labels.build(C.clip_set(run.episodes("train"), run.store.step, run.config.train_hop))


def frame_labels(store: FrameStore, labels: C.Labels) -> FrameLabels:
    """Each store row's action and step class ids (-100: no step, or a class not in
    training)."""
    actions = np.full(len(store.step), -100, np.int64)
    steps = np.full(len(store.step), -100, np.int64)
    a_index = {n: i for i, n in enumerate(labels.actions)}
    s_index = {n: i for i, n in enumerate(labels.steps)}
    for ep in store.episodes:
        shown = store.step[ep.start:ep.start + ep.length].astype(np.int64)
        names = [C.step_class(t) for t in ep.steps]
        s_ids = np.array([s_index.get(n, -100) for n in names] + [-100])
        a_ids = np.array([a_index.get(C.action_name(n), -100) for n in names]
                         + [-100])
        steps[ep.start:ep.start + ep.length] = s_ids[shown]  # -1 picks the last: -100
        actions[ep.start:ep.start + ep.length] = a_ids[shown]
    return FrameLabels(actions, steps)


def _save_model(model: torch.nn.Module, path: Path, **extra: object) -> None:
    cfg = model.cfg.to_dict()  # type: ignore[union-attr, operator]
    tmp = path.with_suffix(".tmp")
    torch.save({"config": cfg, "state": model.state_dict(), **extra}, tmp)
    tmp.replace(path)


def _grid(text: str) -> tuple[int, int]:
    """``"4x3"`` -> (4, 3), refusing anything else in one line."""
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        w = h = 0
    if w < 1 or h < 1:
        raise HomesimError(f"frame_grid {text!r}: cells across x down, e.g. '4x3'")
    return w, h


def _frame_encoder(run: Run, name: str, data: np.ndarray, labels: FrameLabels,
                   n: tuple[int, int]) -> np.ndarray:
    """Train (or load) a frame encoder on `data` and return its feature of every row,
    cached in OUT/features/<name>.npy."""
    path = run.out / "features" / f"{name}.npy"
    if path.is_file():
        return np.load(path)
    start = time.perf_counter()
    cfg = run.config
    kind = "map" if data.ndim == 3 else "rgb"
    grid_w, grid_h = _grid(cfg.frame_grid)
    model_cfg = FrameCNNConfig(n[0], n[1], kind, len(run.store.classes),
                               epochs=cfg.frame_epochs, seed=cfg.backbone_seed,
                               frames_per_epoch=cfg.frames_per_epoch, lr=cfg.frame_lr,
                               dropout=cfg.frame_dropout, grid_w=grid_w, grid_h=grid_h)
    folder = run.out / "frames"
    folder.mkdir(parents=True, exist_ok=True)
    model, fitted = train_frame_cnn(
        model_cfg, data, labels, run.store.rows(run.episodes("train")),
        run.store.rows(run.episodes("val")), run.device, folder / f"{name}.ckpt")
    _save_model(model, folder / f"{name}.pt", best_epoch=fitted.best_epoch,
                scores=fitted.scores)
    features = frame_features(model, data)
    path.parent.mkdir(parents=True, exist_ok=True)
    np.save(path, features)
    run.timed(f"frames_{name}", start)
    return features


def scored_parts(run: Run) -> dict[str, np.ndarray]:
    """The store rows a frame model is scored on: each validation and test part, and all
    test parts together ("all test"); parts without frames are left out."""
    store = run.store
    parts = {part: store.rows(store.part(part))
             for part in [*run.split.parts("val"), *run.split.parts("test")]}
    parts["all test"] = store.rows(run.episodes("test"))
    return {part: rows for part, rows in parts.items() if len(rows)}


def _keep_frame_model(run: Run, name: str, model: torch.nn.Module, fitted: FitResult,
                     scores: dict[str, dict[str, float]], predicted: np.ndarray, path: Path,
                     start: float) -> np.ndarray:
    """Save a trained frame model (OUT/frames/<name>.pt), its scores per part with its
    best epoch and validation curve (<name>.json) and its prediction for every frame
    (`path`); record the stage's time. Returns the prediction."""
    folder = run.out / "frames"
    _save_model(model, folder / f"{name}.pt", best_epoch=fitted.best_epoch,
                scores=fitted.scores)
    write_text(folder / f"{name}.json", json.dumps(
        {"scores": scores, "best_epoch": fitted.best_epoch, "val": fitted.scores},
        indent=2) + "\n", force=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    np.save(path, predicted)
    run.timed(f"frames_{name}", start)
    return predicted


def _segmentation(run: Run) -> np.ndarray:
    """Train (or load) the segmentation network; its predicted map of every frame
    (OUT/features/segmaps.npy) and its scores (OUT/frames/segment.json)."""
    path = run.out / "features" / "segmaps.npy"
    if path.is_file():
        return np.load(path, mmap_mode="r")
    start = time.perf_counter()
    cfg, store = run.config, run.store
    seg_cfg = SegConfig(len(store.classes), width=cfg.seg_width, epochs=cfg.seg_epochs,
                        lr=cfg.seg_lr, seed=cfg.backbone_seed,
                        frames_per_epoch=cfg.seg_frames_per_epoch)
    folder = run.out / "frames"
    folder.mkdir(parents=True, exist_ok=True)
    model, fitted = train_segnet(seg_cfg, store.frames, store.maps,
                                 store.rows(run.episodes("train")),
                                 store.rows(run.episodes("val")), run.device,
                                 folder / "segment.ckpt")
    scores = {part: segmentation_scores(model, store.frames, store.maps, rows)
              for part, rows in scored_parts(run).items()}
    return _keep_frame_model(run, "segment", model, fitted, scores,
                             predict_maps(model, store.frames), path, start)


def pose_network(run: Run) -> np.ndarray:
    """Train (or load) the pose network; its predicted joints of every frame
    (OUT/features/joints.npy) and its scores (OUT/frames/pose.json)."""
    path = run.out / "features" / "joints.npy"
    if path.is_file():
        return np.load(path)
    start = time.perf_counter()
    cfg, store = run.config, run.store
    pose_cfg = PoseConfig(store.joints.shape[1], width=cfg.pose_width, epochs=cfg.pose_epochs,
                          lr=cfg.pose_lr, seed=cfg.backbone_seed,
                          frames_per_epoch=cfg.pose_frames_per_epoch)
    folder = run.out / "frames"
    folder.mkdir(parents=True, exist_ok=True)
    model, fitted = train_posenet(pose_cfg, store.frames, store.joints,
                                  store.rows(run.episodes("train")),
                                  store.rows(run.episodes("val")), run.device,
                                  folder / "pose.ckpt")
    scores = {part: pose_scores(model, store.frames, store.joints, rows)
              for part, rows in scored_parts(run).items()}
    return _keep_frame_model(run, "pose", model, fitted, scores,
                             predict_joints(model, store.frames), path, start)


def with_pose(features: np.ndarray, joints: np.ndarray, train_rows: np.ndarray
              ) -> np.ndarray:
    """(N, width + descriptor) float16: the frame features and the joints' `pose_descriptor`,
    each descriptor column standardised over `train_rows` and brought to the features'
    spread (the clip model's first layer reads both on one scale)."""
    desc = pose_descriptor(joints)
    mean, std = desc[train_rows].mean(0), desc[train_rows].std(0) + 1e-6
    spread = float(np.asarray(features[train_rows], np.float32).std())
    joined = np.concatenate([np.asarray(features, np.float32),
                             (desc - mean) / std * spread], 1)
    return joined.astype(np.float16)


def body_features(run: Run, features: np.ndarray, joints: np.ndarray, maps: np.ndarray
                  ) -> np.ndarray:
    """`features` joined with the `joints`' descriptor (`with_pose`) and the classes of
    `maps` round their wrists, the agent's own left out (`with_hands`)."""
    train_rows, classes = run.store.rows(run.episodes("train")), run.store.classes
    hands = hand_context(maps, joints, len(classes), classes.index("character"))
    return with_hands(with_pose(features, joints, train_rows), hands, train_rows)


def _body_features(run: Run, seg: np.ndarray) -> np.ndarray:
    """The `BODY` input: `body_features` of the predicted maps' feature `seg`, the
    predicted joints and the predicted maps, cached in OUT/features/<BODY>.npy."""
    path = run.out / "features" / f"{BODY}.npy"
    if path.is_file():
        return np.load(path)
    joined = body_features(run, seg, pose_network(run), _segmentation(run))
    np.save(path, joined)
    return joined


def frame_stage(run: Run, labels: C.Labels) -> dict[str, np.ndarray]:
    """Every input's feature of every frame (see the module)."""
    per_row = frame_labels(run.store, labels)
    n = (len(labels.actions), len(labels.steps))
    rgb = _frame_encoder(run, "rgb", run.store.frames, per_row, n)
    oracle = _frame_encoder(run, "oracle", run.store.maps, per_row, n)
    seg = _frame_encoder(run, "seg", _segmentation(run), per_row, n)
    return {"rgb": rgb, "seg": seg, BODY: _body_features(run, seg), "oracle": oracle}


def raw_inputs(run: Run, inp: str) -> np.ndarray:
    """What an end-to-end clip model of `inp` reads: the frames (rgb), the predicted class
    maps (seg) or the ground-truth ones (oracle)."""
    if inp == "rgb":
        return run.store.frames
    if inp == "oracle":
        return run.store.maps
    return np.load(run.out / "features" / "segmaps.npy", mmap_mode="r")


def model_inputs(run: Run, model: C.ClipModel, features: dict[str, np.ndarray]
                 ) -> np.ndarray:
    """What a clip model reads: its input's frame features, or the frames or maps
    themselves when it holds its frame encoder (`VideoRunConfig.clip_end_to_end`)."""
    inp = model.cfg.input
    return raw_inputs(run, inp) if model.backbone is not None else features[inp]


def _backbone(run: Run, inp: str) -> tuple[dict | None, dict | None]:
    """The frame stage's encoder of `inp` (config, weights) for an end-to-end clip model;
    (None, None) when the clip models read fixed features, and for joined inputs."""
    if not run.config.clip_end_to_end or inp not in ENCODED:
        return None, None
    saved = torch.load(run.out / "frames" / f"{inp}.pt", map_location="cpu",
                       weights_only=True)
    return saved["config"], saved["state"]


def clip_path(folder: Path, kind: str, inp: str) -> Path:
    return folder / f"clip_{inp}_{kind}.pt"


def load_clip_model(path: Path, device: str = "cpu") -> tuple[C.ClipModel, C.Labels, dict]:
    """A clip model saved by `_clip_models`, its labels and what else was saved."""
    try:
        data = torch.load(path, map_location=device, weights_only=True)
        model = C.ClipModel(C.ClipConfig(**data["config"])).to(device)
        model.load_state_dict(data["state"])
    except (OSError, KeyError, TypeError, RuntimeError) as e:
        raise HomesimError(f"{path}: not a clip model checkpoint ({e})") from None
    return model.eval(), C.Labels(data["actions"], data["steps"]), data


def clip_config(config: VideoRunConfig, labels: C.Labels, kind: str, inp: str,
                n_inputs: int, seed: int, backbone: dict | None = None) -> C.ClipConfig:
    """A clip model of the run's settings over descriptors `n_inputs` wide."""
    return C.ClipConfig(kind, inp, n_inputs, len(labels.actions), len(labels.steps),
                        feature=config.clip_feature, epochs=config.clip_epochs,
                        lr=config.clip_lr, seed=seed, hidden=config.clip_hidden,
                        dropout=config.clip_dropout, backbone=backbone)


def _clip_models(run: Run, seed: int, labels: C.Labels, features: dict[str, np.ndarray]
                 ) -> None:
    """The clip models of one seed (each skipped when saved)."""
    folder = seed_dir(run.out, seed)
    folder.mkdir(parents=True, exist_ok=True)
    train = C.clip_set(run.episodes("train"), run.store.step, run.config.train_hop)
    val = C.clip_set(run.episodes("val"), run.store.step)
    for inp, kind in CLIP_MODELS:
        path = clip_path(folder, kind, inp)
        if path.is_file():
            continue
        start = time.perf_counter()
        rc = run.config
        backbone, weights = _backbone(run, inp)
        cfg = clip_config(rc, labels, kind, inp, features[inp].shape[1], seed, backbone)
        data = raw_inputs(run, inp) if backbone else features[inp]
        model, fitted = C.train_clip_model(cfg, data, train, labels, val, run.device,
                                           path.with_suffix(".ckpt"), weights)
        _save_model(model, path, actions=labels.actions, steps=labels.steps,
                    best_epoch=fitted.best_epoch, scores=fitted.scores,
                    val_score=max(fitted.scores, default=0.0))
        run.timed(f"seed {seed} clip_{inp}_{kind}", start)


def program_input(folder: Path) -> str:
    """The perceived input whose TRN scores best on validation: what the video ->
    program models read."""
    scores = {inp: load_clip_model(clip_path(folder, "trn", inp))[2]["val_score"]
              for inp in PERCEIVED}
    return max(PERCEIVED, key=lambda inp: (scores[inp], inp == "seg"))


def video_features(clip_model: C.ClipModel, episodes: list[StoredEpisode],
                   features: np.ndarray) -> dict[str, torch.Tensor]:
    """Each episode's sequence of clip features, by example id."""
    return {e.key: episode_features(clip_model, e, features) for e in episodes}


def fit_mle(run: Run, seed: int, feature_dim: int, feats: dict[str, torch.Tensor],
            train: list, val: list) -> tuple[Video2Prog, BestOnDev, list[float]]:
    """The video -> program MLE of one seed over clip features `feats` (by example id),
    its best epoch on `val` restored; with the chooser and the loss of each epoch."""
    cfg = run.config
    v2p = Video2Prog.create_video(train, feature_dim, seed, run.device,
                                  word_dim=cfg.word_dim, hidden=cfg.hidden,
                                  step_dim=cfg.step_dim)
    v2p.features = feats
    best = BestOnDev(v2p, val)
    mle = TrainConfig(epochs=cfg.mle_epochs, batch_size=cfg.batch_size, lr=cfg.mle_lr,
                      seed=seed)
    history = train_mle(v2p, train, mle, after_epoch=best if val else None)
    best.restore()
    return v2p, best, history


def _program_models(run: Run, seed: int, features: dict[str, np.ndarray]) -> None:
    """MLE, then PG (LCS) and PG (LCS+Sim) from it; each keeps its best epoch on val."""
    folder = seed_dir(run.out, seed)
    if all((folder / f"{name}.pt").is_file() for name in PROGRAM_MODELS):
        return
    inp = program_input(folder)
    clip_model, _, _ = load_clip_model(clip_path(folder, "trn", inp), run.device)
    train_eps, val_eps = run.episodes("train"), run.episodes("val")
    train = [example(e) for e in train_eps]
    val = [example(e) for e in val_eps]
    feats = video_features(clip_model, train_eps + val_eps,
                           model_inputs(run, clip_model, features))
    mle_path = folder / "mle.pt"
    if mle_path.is_file():
        base = Video2Prog.load(mle_path, run.device)
        v2p = Video2Prog(base.model, base.words, base.steps, base.meta, feats)
    else:
        start = time.perf_counter()
        v2p, best, history = fit_mle(run, seed, clip_model.cfg.feature, feats, train, val)
        v2p.meta.update(model="mle", input=inp, history=history, val=best.scores,
                        best_epoch=best.epoch)
        v2p.save(mle_path)
        run.timed(f"seed {seed} mle", start)
    for name, use_sim in (("pg_lcs", False), ("pg_lcs_sim", True)):
        if (folder / f"{name}.pt").is_file():
            continue
        start = time.perf_counter()
        pg = copy.deepcopy(v2p)
        pg_cfg = TrainConfig(epochs=run.config.pg_epochs, batch_size=run.config.batch_size,
                             lr=run.config.pg_lr, seed=seed,
                             sim_weight=run.config.sim_weight)
        best = BestOnDev(pg, val, use_sim, pg_cfg.sim_weight)
        if val:
            best(-1)  # the MLE weights are a candidate too (epoch -1)
        history = train_pg(pg, train, pg_cfg, use_sim, after_epoch=best if val else None)
        best.restore()
        pg.meta.update(model=name, input=inp, history=history, val=best.scores,
                       best_epoch=best.epoch)
        pg.save(folder / f"{name}.pt")
        run.timed(f"seed {seed} {name}", start)


def _check_config(out: Path, config: VideoRunConfig, force: bool) -> dict[str, float]:
    """The wall times of an earlier sitting of the same run (refusing another run's
    folder unless `force`)."""
    path = out / "train.json"
    if not path.is_file():
        return {}
    old = json.loads(path.read_text(encoding="utf-8"))
    try:  # settings added since the run was made take their defaults
        same = asdict(VideoRunConfig(**old.get("config", {}))) == asdict(config)
    except TypeError:
        same = False
    if not same and not force:
        raise HomesimError(f"{path}: a run with other settings; use another --out folder "
                           "or --force")
    return old.get("seconds", {}) if same else {}


def _write_summary(run: Run, total_start: float) -> dict:
    store = run.store
    parts = {p: len(store.part(p)) for p in run.split.roles}
    clips = {p: len(C.clip_set(store.part(p), store.step).steps) for p in run.split.roles}
    summary = {"config": asdict(run.config), "episodes": parts, "clips": clips,
               "roles": run.split.roles,
               "rows": [[r[0], r[1], list(r[2])] for r in run.split.rows],
               "frames": len(store.step), "classes": len(store.classes),
               "seconds": run.seconds, "device": run.device,
               "sitting_seconds": time.perf_counter() - total_start}
    write_text(run.out / "train.json", json.dumps(summary, indent=2) + "\n", force=True)
    return summary


def open_run(config: VideoRunConfig, out: Path, device: str = "cpu",
             report: Report | None = None) -> Run:
    """The store and split of the run's data (read once, cached)."""
    start = time.perf_counter()
    store, split = read_store(config.data, config.format, Path(config.cache), config.workers)
    run = Run(config, out, store, split, device, report)
    run.timed("read", start)
    return run


def reopen_run(out: Path, device: str = "cpu") -> tuple[Run, dict]:
    """A trained (or partly trained) run folder's run, from its train.json, and that
    summary."""
    path = out / "train.json"
    if not path.is_file():
        raise HomesimError(f"{path}: not found; run 'homesim learn train --task video2prog'")
    summary = json.loads(path.read_text(encoding="utf-8"))
    return open_run(VideoRunConfig(**summary["config"]), out, device), summary


def train_video(config: VideoRunConfig, out: Path, device: str = "cpu",
                report: Report | None = None, force: bool = False) -> dict:
    """Train every model of every seed, resuming what an earlier sitting did; see the
    module."""
    total_start = time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    seconds = _check_config(out, config, force)
    run = open_run(config, out, device, report)
    run.seconds = {**seconds, "read": seconds.get("read", 0.0) + run.seconds["read"]}
    if not run.episodes("train"):
        raise HomesimError(f"{config.data}: no training episodes")
    run.say(f"data: {', '.join(f'{p} {len(run.store.part(p))}' for p in run.split.roles)} "
            f"episodes, {len(run.store.step)} frames")
    _write_summary(run, total_start)
    run.after_stage = lambda: _write_summary(run, total_start)
    labels = train_labels(run)
    features = frame_stage(run, labels)
    _write_summary(run, total_start)
    for seed in config.seeds:
        _clip_models(run, seed, labels, features)
        _write_summary(run, total_start)
        _program_models(run, seed, features)
        _write_summary(run, total_start)
    return _write_summary(run, total_start)
