"""The paper's Table 2, scoring: every row on every test row of `videosplits.TEST_ROWS`,
for each seed of a run written by `homesim.learn.video.table.train_video`, then mean and
sample standard deviation over the seeds.

Left half (clips, mean per-class accuracy %): random retrieval, TRN (RGB), single frame
(RGB), TRN (oracle perception), and the oracle-perception gap (oracle TRN minus RGB TRN).
Right half (programs: LCS and Simulator %): random retrieval, MLE, PG (LCS), PG (LCS+Sim),
both constrained decodings, and the ground truth as a reference. Each model predicts every
test episode once; a row scores its episodes.
"""

from __future__ import annotations

import json
import random
import statistics
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

from homesim.errors import HomesimError
from homesim.learn.eval.scores import score
from homesim.learn.execution import executable
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.video import clips as C
from homesim.learn.video.data import Episode
from homesim.learn.video.splits import test_rows
from homesim.learn.video.table import (
    CLIP_MODELS,
    PROGRAM_MODELS,
    VideoRunConfig,
    clip_path,
    descriptors,
    load_clip_model,
    load_frame_cnn,
    read_data,
    seed_dir,
    video_features,
)
from homesim.learn.video.video2prog import Video2Prog
from homesim.program.model import Program

CLIP_NAMES = {("rgb", "trn"): "TRN (RGB)", ("rgb", "single"): "Single frame (RGB)",
              ("oracle", "trn"): "TRN (oracle perception: class maps)"}
GAP = "Oracle-perception gap (oracle TRN - RGB TRN)"
CONSTRAINED = {"mle": "MLE + constrained decoding",
               "pg_lcs_sim": "PG (LCS+Sim) + constrained decoding"}
TRUTH = "Ground truth (reference)"


def mean_sd(values: list[float]) -> dict:
    """{"mean", "sd" (sample; 0 for one value), "values"}."""
    sd = statistics.stdev(values) if len(values) > 1 else 0.0
    return {"mean": statistics.fmean(values), "sd": sd, "values": values}


def _clip_scores(folder: Path, rows: dict[str, list[Episode]], train: list[Episode],
                 vectors: dict[str, C.Descriptors], seed: int, device: str
                 ) -> dict[str, dict[str, dict[str, float]]]:
    """{test row: {method: {action, step, n}}} for one seed."""
    train_set = C.clip_set(train, vectors["oracle"])
    models = {key: load_clip_model(clip_path(folder, key[1], key[0]), device)
              for key in CLIP_MODELS}
    out: dict[str, dict[str, dict[str, float]]] = {}
    for row, episodes in rows.items():
        sets = {inp: C.clip_set(episodes, vectors[inp]) for inp in ("rgb", "oracle")}
        truth = sets["oracle"]
        n = len(truth.steps)
        out[row] = {"Random retrieval": {
            "action": C.mean_class_accuracy(
                C.random_retrieval(train_set.actions, n, seed), truth.actions),
            "step": C.mean_class_accuracy(
                C.random_retrieval(train_set.steps, n, seed), truth.steps), "n": n}}
        for key, (model, labels) in models.items():
            actions, steps = C.predict_clips(model, sets[key[0]], labels)
            out[row][CLIP_NAMES[key]] = {"action": C.mean_class_accuracy(actions, truth.actions),
                                         "step": C.mean_class_accuracy(steps, truth.steps),
                                         "n": n}
        rgb, oracle = out[row][CLIP_NAMES[("rgb", "trn")]], out[row][CLIP_NAMES[("oracle", "trn")]]
        out[row][GAP] = {m: oracle[m] - rgb[m] for m in ("action", "step")} | {"n": n}
    return out


def _predictors(folder: Path, tested: list[Episode], train: list[Episode],
                rgb: C.Descriptors, seed: int, device: str
                ) -> dict[str, Callable[[], list[Program]]]:
    """Method -> how it predicts the programs of `tested` (in order)."""
    clip_model, _ = load_clip_model(clip_path(folder, "trn", "rgb"), device)
    features = video_features(clip_model, tested, rgb)
    models = {}
    for name in PROGRAM_MODELS:
        base = Text2Prog.load(folder / f"{name}.pt", device)
        models[name] = Video2Prog(base.model, base.words, base.steps, base.meta, features)
    examples = [e.example for e in tested]
    rng = random.Random(seed)
    train_programs = [e.example.program for e in train]
    out: dict[str, Callable[[], list[Program]]] = {
        "Random retrieval": lambda: [rng.choice(train_programs) for _ in examples]}
    for name, label in PROGRAM_MODELS.items():
        out[label] = partial(models[name].predict, examples)
    for name, label in CONSTRAINED.items():
        out[label] = partial(models[name].predict, examples, constrained=True)
    out[TRUTH] = lambda: [e.program for e in examples]
    return out


def _program_scores(folder: Path, rows: dict[str, list[Episode]], train: list[Episode],
                    rgb: C.Descriptors, seed: int, device: str
                    ) -> dict[str, dict[str, dict]]:
    """{test row: {method: Scores dict}} for one seed."""
    tested = rows["all"] if "all" in rows else [e for v in rows.values() for e in v]
    at = {e.key: i for i, e in enumerate(tested)}
    out: dict[str, dict[str, dict]] = {row: {} for row in rows}
    for method, predict in _predictors(folder, tested, train, rgb, seed, device).items():
        programs = predict()
        flags = [executable(p, e.example) for p, e in zip(programs, tested, strict=True)]
        for row, episodes in rows.items():
            idx = [at[e.key] for e in episodes]
            out[row][method] = score([programs[i] for i in idx],
                                     [tested[i].example.program for i in idx],
                                     [flags[i] for i in idx]).to_dict()
    return out


def _over_seeds(per_seed: list[dict[str, dict[str, dict]]]) -> dict[str, dict[str, dict]]:
    """{row: {method: {metric: mean_sd, "n": n}}} from each seed's {row: {method: {...}}}."""
    out: dict[str, dict[str, dict]] = {}
    for row, methods in per_seed[0].items():
        out[row] = {}
        for method, first in methods.items():
            out[row][method] = {"n": first["n"], **{
                metric: mean_sd([float(s[row][method][metric]) for s in per_seed])
                for metric in first if metric != "n"}}
    return out


def evaluate_video(out: Path, device: str = "cpu") -> dict:
    """Every row of Table 2 on the run in `out` (its train.json names the data set)."""
    path = out / "train.json"
    if not path.is_file():
        raise HomesimError(f"{path}: not found; run 'homesim learn train --task video2prog'")
    summary = json.loads(path.read_text(encoding="utf-8"))
    config = VideoRunConfig(**summary["config"])
    parts, _ = read_data(config)
    rows = test_rows({p: v for p, v in parts.items() if p != "train"})
    everything = [e for v in parts.values() for e in v]
    start = time.perf_counter()
    clips, programs = [], []
    for seed in config.seeds:
        folder = seed_dir(out, seed)
        cnn = load_frame_cnn(folder / "frame_cnn.pt", device)
        vectors = {inp: descriptors(everything, inp, cnn) for inp in ("rgb", "oracle")}
        clips.append(_clip_scores(folder, rows, parts["train"], vectors, seed, device))
        programs.append(_program_scores(folder, rows, parts["train"], vectors["rgb"], seed,
                                        device))
    return {"train": summary, "rows": {r: len(v) for r, v in rows.items()},
            "clips": _over_seeds(clips), "programs": _over_seeds(programs),
            "eval_seconds": time.perf_counter() - start}
