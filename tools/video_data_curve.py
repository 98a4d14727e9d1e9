"""Is Table 2's clip recognition capped by the amount of data? A learning curve on
validation only.

For a trained run folder (`homesim learn train --task video2prog --out RUN`), the TRN of
each input named is trained again on a share of the training episodes (the first of them
in the order `table.train_subset` fixes), over the run's cached frame features and with the
run's settings, and scored on the validation clips (never a test part). Share 1 reads the
run's own model of that seed. The frame encoders stay those trained on every training
episode, so the curve measures the clip stage's appetite for data, not the encoders'.

    python tools/video_data_curve.py out/paper --inputs seg oracle --shares 0.125 0.25 0.5 1
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import torch

from homesim.learn.video import clips as C
from homesim.learn.video.eval import load_features
from homesim.learn.video.table import (
    clip_config,
    clip_path,
    load_clip_model,
    reopen_run,
    seed_dir,
    train_labels,
)


def val_scores(model: C.ClipModel, features: np.ndarray, val: C.ClipSet,
               labels: C.Labels) -> dict[str, float]:
    """Mean per-class accuracy (%) of action and step on the validation clips."""
    actions, steps = C.predict_clips(model, features, val, labels)
    return {"action": round(C.mean_class_accuracy(actions, val.actions), 2),
            "step": round(C.mean_class_accuracy(steps, val.steps), 2)}


def curve(out: Path, inputs: list[str], shares: list[float], seed: int) -> list[dict]:
    """One row per input and share: training episodes and clips, validation scores."""
    run, _ = reopen_run(out)
    config = run.config
    labels = train_labels(run)
    features = load_features(out)
    val = C.clip_set(run.episodes("val"), run.store.step)
    rows = []
    for inp in inputs:
        for share in shares:
            start = time.perf_counter()
            sub = replace(run, config=replace(config, train_share=share))
            episodes = sub.episodes("train")
            train = C.clip_set(episodes, run.store.step, config.train_hop)
            if share == 1.0:
                model, _, _ = load_clip_model(clip_path(seed_dir(out, seed), "trn", inp))
            else:
                cfg = clip_config(config, labels, "trn", inp, features[inp].shape[1], seed)
                model, _ = C.train_clip_model(cfg, features[inp], train, labels, val)
            row = {"input": inp, "share": share, "episodes": len(episodes),
                   "clips": len(train.steps), **val_scores(model, features[inp], val, labels),
                   "seconds": round(time.perf_counter() - start)}
            print(json.dumps(row), flush=True)
            rows.append(row)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("--inputs", nargs="+", default=["seg", "oracle"])
    parser.add_argument("--shares", nargs="+", type=float, default=[0.125, 0.25, 0.5, 1.0])
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", type=Path, help="Also write the rows here.")
    args = parser.parse_args()
    torch.set_num_threads(1)
    rows = curve(args.run, args.inputs, args.shares, args.seed)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
