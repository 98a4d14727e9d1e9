"""Table 2's models scored on the validation part only: what settings are chosen by.

For each run folder (`homesim learn train --task video2prog --out RUN`, finished or not)
it prints, from validation episodes alone (never a test part):

- the frame encoders' and the segmentation network's validation score per epoch (as
  recorded while training) and the epoch kept;
- per seed and clip model: mean per-class accuracy of action and step on the validation
  clips (back to back, as the test clips are scored);
- per seed and program model (when trained): steps LCS and Simulator % of greedy and
  constrained decoding on the validation episodes, the epoch kept (-1: PG kept its MLE
  start) and the validation reward per epoch.

    python tools/video_dev.py out/dev-a out/dev-b [--json dev.json]

Runs that share a data set read the same frame store (cached). Nothing here reads a test
episode's label or prediction: settings chosen from this output are chosen on validation.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import torch

from homesim.learn.video import clips as C
from homesim.learn.video.eval import (
    CLIP_ROWS,
    CONSTRAINED,
    load_features,
    program_examples,
)
from homesim.learn.video.table import (
    PROGRAM_MODELS,
    Run,
    clip_path,
    load_clip_model,
    model_inputs,
    reopen_run,
    seed_dir,
)


def frame_scores(out: Path) -> dict[str, dict]:
    """Each frame model's validation score per epoch and its kept epoch."""
    found = {}
    for path in sorted((out / "frames").glob("*.pt")):
        data = torch.load(path, map_location="cpu", weights_only=True)
        found[path.stem] = {"val": [round(float(v), 2) for v in data.get("scores", [])],
                            "best_epoch": data.get("best_epoch")}
    return found


def clip_scores(run: Run, seed: int, features: dict[str, np.ndarray]) -> dict[str, dict]:
    """Clip model -> validation action and step mean per-class accuracy (%)."""
    val = C.clip_set(run.episodes("val"), run.store.step)
    out = {}
    for (inp, kind), name in CLIP_ROWS.items():
        path = clip_path(seed_dir(run.out, seed), kind, inp)
        if not path.is_file():
            continue
        model, labels, saved = load_clip_model(path)
        actions, steps = C.predict_clips(model, model_inputs(run, model, features), val,
                                         labels)
        out[name] = {"action": round(C.mean_class_accuracy(actions, val.actions), 2),
                     "step": round(C.mean_class_accuracy(steps, val.steps), 2),
                     "best_epoch": saved.get("best_epoch"),
                     "val_per_epoch": [round(float(v), 1) for v in saved.get("scores", [])]}
    return out


def program_scores(run: Run, seed: int, features: dict[str, np.ndarray]) -> dict[str, dict]:
    """Program model -> validation steps LCS and Simulator % (greedy and constrained)."""
    folder = seed_dir(run.out, seed)
    if not all((folder / f"{name}.pt").is_file() for name in PROGRAM_MODELS):
        return {}
    per_method = program_examples(run, seed, run.episodes("val"), features)
    out = {}
    for method, rows in per_method.items():
        out[method] = {"steps": round(float(np.mean([r["steps"] for r in rows])), 4),
                       "simulator": round(100 * float(np.mean([r["simulator"] for r in rows])), 1)}
    for name, label in PROGRAM_MODELS.items():
        meta = torch.load(folder / f"{name}.pt", map_location="cpu", weights_only=False)
        meta = meta.get("meta", {})
        out[label].update(best_epoch=meta.get("best_epoch"),
                          val_per_epoch=[round(float(v), 4) for v in meta.get("val", [])])
    assert all(m.replace(CONSTRAINED, "") in out for m in out)
    return out


def dev_report(out: Path) -> dict:
    """Everything above for one run folder."""
    run, summary = reopen_run(out)
    config = run.config
    features = load_features(out)
    seeds = {seed: {"clips": clip_scores(run, seed, features),
                    "programs": program_scores(run, seed, features)}
             for seed in config.seeds if seed_dir(out, seed).is_dir()}
    segment = out / "frames" / "segment.json"
    seg_val = json.loads(segment.read_text(encoding="utf-8"))["val"] if segment.is_file() else None
    return {"run": str(out), "episodes": summary["episodes"], "frames": frame_scores(out),
            "segment_val_miou_per_epoch": seg_val, "seeds": seeds,
            "seconds": summary.get("seconds", {})}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", type=Path)
    parser.add_argument("--json", type=Path, help="Also write the reports here.")
    args = parser.parse_args()
    torch.set_num_threads(1)
    reports = [dev_report(out) for out in args.runs]
    for r in reports:
        print(json.dumps(r, indent=1))
    if args.json:
        args.json.write_text(json.dumps(reports, indent=2) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
