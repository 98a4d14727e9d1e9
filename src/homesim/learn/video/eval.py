"""The paper's Table 2, scoring: every row on every test row of the run's split, for each
seed of a run written by `homesim.learn.video.table.train_video`; mean and sample sd over
the seeds and a 95 % bootstrap interval over test episodes.

Left half (clips, mean per-class accuracy %): random retrieval, single frame (RGB), TRN on
RGB, TRN on the predicted segmentation, TRN on the predicted segmentation, pose (`pose`)
and the classes round the hands (`hands`), TRN on the ground-truth class maps (the oracle).
Right half (programs: LCS and Simulator %): random retrieval, MLE, PG (LCS),
PG (LCS+Sim), each also with constrained decoding, and the ground truth as a reference.
Each model predicts every test episode once; a row scores its episodes.

Bootstrap: each of `BOOTSTRAP` replicates draws the row's test episodes with replacement
(a clip row: every clip of each drawn episode, as often as it is drawn) and averages the
seeds' figures; its 2.5 and 97.5 percentiles bound the interval. Programs use
`homesim.learn.eval.summary` (the text task's intervals).
"""

from __future__ import annotations

import json
import random
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

import numpy as np

from homesim.learn.eval.scores import example_scores
from homesim.learn.eval.summary import BOOTSTRAP, BOOTSTRAP_SEED, summarize
from homesim.learn.execution import executable
from homesim.learn.video import clips as C
from homesim.learn.video.data import example
from homesim.learn.video.store import StoredEpisode
from homesim.learn.video.table import (
    BODY,
    INPUTS,
    PROGRAM_MODELS,
    Run,
    clip_path,
    load_clip_model,
    model_inputs,
    reopen_run,
    seed_dir,
    video_features,
)
from homesim.learn.video.video2prog import Video2Prog
from homesim.program.model import Program

CLIP_ROWS = {("rgb", "single"): "Single frame (RGB)", ("rgb", "trn"): "TRN (RGB)",
             ("seg", "trn"): "TRN (predicted segmentation)",
             (BODY, "trn"): "TRN (predicted segmentation + pose + hands)",
             ("oracle", "trn"): "TRN (ground-truth class maps: oracle)"}
RANDOM = "Random retrieval"
CONSTRAINED = " + constrained decoding"
TRUTH = "Ground truth (reference)"
PROGRAM_METRICS = ("action", "objects", "steps", "mean", "simulator")


def row_episodes(run: Run) -> dict[str, list[StoredEpisode]]:
    """Test row -> its episodes (rows with none left out)."""
    rows = {row: [e for p in parts for e in run.store.part(p)]
            for row, _, parts in run.split.rows}
    return {row: eps for row, eps in rows.items() if eps}


def clip_predictions(run: Run, seed: int, test: C.ClipSet, features: dict[str, np.ndarray],
                     train_labels: list[tuple[str, str]]) -> dict[str, dict[str, list[str]]]:
    """Method -> {"action": [...], "step": [...]} predicted for every test clip."""
    folder = seed_dir(run.out, seed)
    rng = random.Random(seed)
    drawn = [rng.choice(train_labels) for _ in test.steps]
    out = {RANDOM: {"action": [a for a, _ in drawn], "step": [s for _, s in drawn]}}
    for (inp, kind), name in CLIP_ROWS.items():
        model, labels, _ = load_clip_model(clip_path(folder, kind, inp), run.device)
        actions, steps = C.predict_clips(model, model_inputs(run, model, features), test,
                                         labels)
        out[name] = {"action": actions, "step": steps}
    return out


def _class_tables(test: C.ClipSet, episodes: list[StoredEpisode], metric: str,
                  predicted: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """(episodes, classes) counts of the row's clips and of its correct predictions."""
    truth = test.actions if metric == "action" else test.steps
    classes = {c: i for i, c in enumerate(sorted(set(truth)))}
    at = {e.key: i for i, e in enumerate(episodes)}
    counts = np.zeros((len(episodes), len(classes)))
    hits = np.zeros_like(counts)
    for key, t, p in zip(test.episodes, truth, predicted, strict=True):
        if key in at:
            counts[at[key], classes[t]] += 1
            hits[at[key], classes[t]] += p == t
    return counts, hits


def _recall(counts: np.ndarray, hits: np.ndarray) -> np.ndarray:
    """Mean per-class accuracy (%) of each row of (draws, classes) tables."""
    present = counts > 0
    recall = np.divide(hits, counts, out=np.zeros_like(hits), where=present)
    return 100.0 * recall.sum(-1) / np.maximum(present.sum(-1), 1)


def clip_summary(tables: list[tuple[np.ndarray, np.ndarray]]) -> dict:
    """Mean, sd over seeds and bootstrap interval from each seed's class tables."""
    full = [float(_recall(c.sum(0), h.sum(0))) for c, h in tables]
    n = len(tables[0][0])
    rng = np.random.default_rng(BOOTSTRAP_SEED)
    draws = np.stack([np.bincount(d, minlength=n) for d in
                      rng.integers(0, n, size=(BOOTSTRAP, n))]).astype(float)
    reps = np.mean([_recall(draws @ c, draws @ h) for c, h in tables], axis=0)
    lo, hi = np.percentile(reps, [2.5, 97.5])
    return {"mean": float(np.mean(full)),
            "sd": float(np.std(full, ddof=1)) if len(full) > 1 else 0.0,
            "lo": float(lo), "hi": float(hi), "seeds": full}


def program_predictions(run: Run, seed: int, tested: list[StoredEpisode],
                        features: dict[str, np.ndarray]
                        ) -> dict[str, Callable[[], list[Program]]]:
    """Method -> how it predicts the programs of `tested` (in order)."""
    folder = seed_dir(run.out, seed)
    examples = [example(e) for e in tested]
    models = {name: Video2Prog.load(folder / f"{name}.pt", run.device)
              for name in PROGRAM_MODELS}
    inp = models["mle"].meta.get("input", "rgb")
    clip_model, _, _ = load_clip_model(clip_path(folder, "trn", inp), run.device)
    feats = video_features(clip_model, tested, model_inputs(run, clip_model, features))
    rng = random.Random(seed)
    train_programs = [example(e).program for e in run.episodes("train")]
    out: dict[str, Callable[[], list[Program]]] = {
        RANDOM: lambda: [rng.choice(train_programs) for _ in examples]}
    for name, label in PROGRAM_MODELS.items():
        model = models[name]
        v2p = Video2Prog(model.model, model.words, model.steps, model.meta, feats)
        out[label] = partial(v2p.predict, examples)
        out[label + CONSTRAINED] = partial(v2p.predict, examples, constrained=True)
    out[TRUTH] = lambda: [e.program for e in examples]
    return out


def program_examples(run: Run, seed: int, tested: list[StoredEpisode],
                     features: dict[str, np.ndarray]) -> dict[str, list[dict]]:
    """Method -> per-episode scores (`example_scores`) of every tested episode."""
    examples = [example(e) for e in tested]
    out = {}
    for method, predict in program_predictions(run, seed, tested, features).items():
        programs = predict()
        out[method] = [example_scores(p, x.program, executable(p, x), None)
                       for p, x in zip(programs, examples, strict=True)]
    return out


def load_features(out: Path) -> dict[str, np.ndarray]:
    """The frame-feature cache of a run (`table.frame_stage`): the inputs whose features
    are written (all of them once the frame stage is done)."""
    folder = out / "features"
    paths = {inp: folder / f"{inp}.npy" for inp in INPUTS}
    return {inp: np.load(path) for inp, path in paths.items() if path.is_file()}


def _clip_rows(run: Run, features: dict[str, np.ndarray], rows: dict[str, list]) -> dict:
    tested = [e for eps in rows.values() for e in eps]
    unique = list({e.key: e for e in tested}.values())
    test = C.clip_set(unique, run.store.step)
    train = C.clip_set(run.episodes("train"), run.store.step, run.config.train_hop)
    pairs = list(zip(train.actions, train.steps, strict=True))
    per_seed = [clip_predictions(run, seed, test, features, pairs)
                for seed in run.config.seeds]
    out: dict[str, dict] = {}
    for row, eps in rows.items():
        out[row] = {}
        n = sum(k in {e.key for e in eps} for k in test.episodes)
        for method in per_seed[0]:
            out[row][method] = {"n": n, **{metric: clip_summary(
                [_class_tables(test, eps, metric, seed[method][metric]) for seed in per_seed])
                for metric in ("action", "step")}}
    return out


def _program_rows(run: Run, features: dict[str, np.ndarray], rows: dict[str, list]) -> dict:
    tested = list({e.key: e for eps in rows.values() for e in eps}.values())
    at = {e.key: i for i, e in enumerate(tested)}
    per_seed = [program_examples(run, seed, tested, features) for seed in run.config.seeds]
    out: dict[str, dict] = {}
    for row, eps in rows.items():
        idx = [at[e.key] for e in eps]
        out[row] = {method: {"n": len(idx), **{
            metric: summarize([[s[method][i] for i in idx] for s in per_seed], metric)
            for metric in PROGRAM_METRICS}} for method in per_seed[0]}
    return out


def evaluate_video(out: Path, device: str = "cpu") -> dict:
    """Every row of Table 2 on the run in `out` (its train.json names the data set)."""
    run, summary = reopen_run(out, device)
    features = load_features(out)
    rows = row_episodes(run)
    start = time.perf_counter()
    clips = _clip_rows(run, features, rows)
    programs = _program_rows(run, features, rows)
    segment = json.loads((out / "frames" / "segment.json").read_text(encoding="utf-8"))
    pose_path = out / "frames" / "pose.json"
    pose = json.loads(pose_path.read_text(encoding="utf-8")) if pose_path.is_file() else None
    return {"train": summary, "rows": {r: len(v) for r, v in rows.items()},
            "labels": {r: label for r, label, _ in run.split.rows},
            "clips": clips, "programs": programs, "segment": segment, "pose": pose,
            "eval_seconds": time.perf_counter() - start}
