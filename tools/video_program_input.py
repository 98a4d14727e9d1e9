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

from homesim.learn.text.train import BestOnDev, TrainConfig, train_mle
from homesim.learn.video.data import example
from homesim.learn.video.eval import load_features
from homesim.learn.video.table import (
    VideoRunConfig,
    clip_path,
    load_clip_model,
    open_run,
    seed_dir,
    video_features,
)
from homesim.learn.video.video2prog import Video2Prog


def mle_on(out: Path, inp: str, seed: int) -> dict:
    """Validation steps LCS per epoch of an MLE over input `inp`'s TRN clip features."""
    start = time.perf_counter()
    summary = json.loads((out / "train.json").read_text(encoding="utf-8"))
    cfg = VideoRunConfig(**summary["config"])
    run = open_run(cfg, out)
    features = load_features(out)
    clip_model, _, _ = load_clip_model(clip_path(seed_dir(out, seed), "trn", inp))
    train_eps, val_eps = run.episodes("train"), run.episodes("val")
    train = [example(e) for e in train_eps]
    val = [example(e) for e in val_eps]
    v2p = Video2Prog.create_video(train, clip_model.cfg.feature, seed, "cpu",
                                  word_dim=cfg.word_dim, hidden=cfg.hidden,
                                  step_dim=cfg.step_dim)
    v2p.features = video_features(clip_model, train_eps + val_eps, features[inp])
    best = BestOnDev(v2p, val)
    train_mle(v2p, train, TrainConfig(epochs=cfg.mle_epochs, batch_size=cfg.batch_size,
                                      lr=cfg.mle_lr, seed=seed), after_epoch=best)
    return {"input": inp, "seed": seed, "best_epoch": best.epoch,
            "val_steps_lcs": round(best.best, 4),
            "val_per_epoch": [round(s, 4) for s in best.scores],
            "seconds": round(time.perf_counter() - start)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("--inputs", nargs="+", default=["seg", "oracle"])
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    torch.set_num_threads(1)
    for inp in args.inputs:
        print(json.dumps(mle_on(args.run, inp, args.seed)), flush=True)


if __name__ == "__main__":
    main()
