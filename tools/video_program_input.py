"""Do Table 2's program models follow perception? MLE trained on the clip features of each
input's TRN, scored on validation only.

For a trained run folder, the video -> program MLE of one seed is trained again with the
run's settings over the clip features of the TRN on each input named (the run itself
reads the best perceived input's; `oracle` reads the ground-truth class maps' TRN), and the
validation steps LCS of its best epoch is printed (the epoch chooser's own figure; no test
episode is read).

    python tools/video_program_input.py out/paper --inputs seg oracle --seed 0
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import torch

from homesim.learn.video.data import example
from homesim.learn.video.eval import load_features
from homesim.learn.video.table import (
    clip_path,
    fit_mle,
    load_clip_model,
    model_inputs,
    reopen_run,
    seed_dir,
    video_features,
)


def mle_on(out: Path, inputs: list[str], seed: int) -> list[dict]:
    """Per input, the validation steps LCS per epoch of an MLE over that input's TRN clip
    features (`table.fit_mle`, the run's own settings)."""
    run, _ = reopen_run(out)
    features = load_features(out)
    train_eps, val_eps = run.episodes("train"), run.episodes("val")
    train = [example(e) for e in train_eps]
    val = [example(e) for e in val_eps]
    rows = []
    for inp in inputs:
        start = time.perf_counter()
        clip_model, _, _ = load_clip_model(clip_path(seed_dir(out, seed), "trn", inp))
        feats = video_features(clip_model, train_eps + val_eps,
                               model_inputs(run, clip_model, features))
        _, best, _ = fit_mle(run, seed, clip_model.cfg.feature, feats, train, val)
        row = {"input": inp, "seed": seed, "best_epoch": best.epoch,
               "val_steps_lcs": round(best.best, 4),
               "val_per_epoch": [round(s, 4) for s in best.scores],
               "seconds": round(time.perf_counter() - start)}
        print(json.dumps(row), flush=True)
        rows.append(row)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("--inputs", nargs="+", default=["seg", "oracle"])
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    torch.set_num_threads(1)
    mle_on(args.run, args.inputs, args.seed)


if __name__ == "__main__":
    main()
