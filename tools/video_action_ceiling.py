"""How far can clip recognition go when actions share one animation? A ceiling on the
labels, and where a trained clip model's errors fall, on validation only.

Many actions of the catalog are drawn with one motion (`homesim.render.animate`:
`ACTIONS[key].motion`; `reach` serves Grab, Open, SwitchOn, PutBack, Wash, ... alike).
Clips whose action differs but whose motion and objects are the same show the same
thing, so no recogniser tells them apart. Two bounds on mean per-class action accuracy
(the Table 2 metric) follow from the labels alone:

- *motion only*: a recogniser that sees the motion perfectly and nothing else;
- *motion and objects*: one that also sees every object of the step (the step's object
  classes) but not what changes (a door swinging open or shut, a lamp lighting, a thing
  leaving the hand): what a clip model reaches unless it reads those changes;
- *motion and the objects the maps show*: as the last, but an object none of whose
  pixels is in the clip's ground-truth class maps (at the store's map size) is not seen:
  the oracle's bound at that resolution.

Each bound assigns every group of indistinguishable clips to the one action that adds
most to the mean per-class recall (a group's clips all get one answer).

With a run folder and `--input`, the trained TRN of that input (seed `--seed`) is scored
on the same validation clips: its action accuracy, its accuracy on the motion (actions
mapped to their motion), and the share of its action errors that stay within the true
motion.

    python tools/video_action_ceiling.py out/dev --input oracle seg oracle:e2e
"""

from __future__ import annotations

import argparse
import json
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np
import torch

from homesim.learn.video import clips as C
from homesim.learn.video.eval import load_features
from homesim.learn.video.table import (
    Run,
    clip_path,
    load_clip_model,
    model_inputs,
    reopen_run,
    seed_dir,
)
from homesim.render.animate import ACTIONS

VISUAL = {"find": "walk"}
"""Motions drawn alike: Find walks to its object (it only looks when the object is at hand)."""
MOTION_BY_NAME = {k.replace("_", "").lower(): VISUAL.get(a.motion, a.motion)
                  for k, a in ACTIONS.items()}


def motion_of(action: str) -> str:
    """``SwitchOn`` -> ``reach`` (the catalog's motion of the action)."""
    return MOTION_BY_NAME.get(action.replace("_", "").replace(" ", "").lower(), "?" + action)


def objects_of(step: str) -> str:
    """``[Grab] <cup>`` -> ``<cup>``."""
    return step.split("]", 1)[1].strip() if "]" in step else ""


def ceiling(actions: list[str], groups: list[str]) -> float:
    """Mean per-class recall (%) of the best answer per group of indistinguishable clips."""
    counts = Counter(actions)
    by_group: dict[str, Counter] = defaultdict(Counter)
    for a, g in zip(actions, groups, strict=True):
        by_group[g][a] += 1
    recall: dict[str, float] = defaultdict(float)
    for members in by_group.values():
        best = max(members, key=lambda a: (members[a] / counts[a], a))
        recall[best] += members[best] / counts[best]
    return 100.0 * sum(recall.values()) / len(counts)


def shown_objects(val: C.ClipSet, maps: np.ndarray, classes: list[str]) -> list[str]:
    """Each clip's step objects, ``?`` for one no pixel of its clip's class maps shows."""
    index = {c: i for i, c in enumerate(classes)}
    out = []
    for rows, step in zip(val.rows, val.steps, strict=True):
        present = set(np.unique(np.asarray(maps[np.sort(rows)])).tolist())
        names = [w.strip("<>") for w in objects_of(step).split()]
        out.append(" ".join(n if index.get(n) in present else "?" for n in names))
    return out


def label_report(val: C.ClipSet, maps: np.ndarray, classes: list[str]) -> dict:
    motions = [motion_of(a) for a in val.actions]
    with_objects = [f"{m} {objects_of(s)}" for m, s in zip(motions, val.steps, strict=True)]
    shown = shown_objects(val, maps, classes)
    with_shown = [f"{m} {o}" for m, o in zip(motions, shown, strict=True)]
    objects = [o for o in shown if o]
    per_motion: dict[str, set] = defaultdict(set)
    for a, m in zip(val.actions, motions, strict=True):
        per_motion[m].add(a)
    return {"clips": len(val.actions), "action_classes": len(set(val.actions)),
            "motions": len(set(motions)),
            "actions_per_motion": {m: sorted(a) for m, a in sorted(per_motion.items())},
            "ceiling_motion_only": round(ceiling(val.actions, motions), 1),
            "ceiling_motion_and_objects": round(ceiling(val.actions, with_objects), 1),
            "map_size": list(maps.shape[1:]),
            "clips_with_every_object_shown": round(
                100.0 * sum("?" not in o for o in objects) / max(len(objects), 1), 1),
            "ceiling_motion_and_shown_objects": round(ceiling(val.actions, with_shown), 1)}


def model_report(run: Run, name: str, seed: int, val: C.ClipSet, features: dict) -> dict:
    """`name`: an input (its TRN) or ``input:kind`` (the file ``clip_<input>_<kind>.pt``)."""
    inp, _, kind = name.partition(":")
    model, labels, _ = load_clip_model(clip_path(seed_dir(run.out, seed), kind or "trn", inp))
    pred, _ = C.predict_clips(model, model_inputs(run, model, features), val, labels)
    truth_m = [motion_of(a) for a in val.actions]
    pred_m = [motion_of(a) for a in pred]
    wrong = [(p, t) for p, t in zip(pred, val.actions, strict=True) if p != t]
    same_motion = sum(motion_of(p) == motion_of(t) for p, t in wrong)
    recall = {a: round(100.0 * sum(p == a for p, t in zip(pred, val.actions, strict=True)
                                   if t == a) / n, 1)
              for a, n in Counter(val.actions).most_common()}
    return {"model": name, "seed": seed,
            "action": round(C.mean_class_accuracy(pred, val.actions), 1),
            "motion": round(C.mean_class_accuracy(pred_m, truth_m), 1),
            "errors_within_true_motion": round(100.0 * same_motion / max(len(wrong), 1), 1),
            "recall_per_action": recall}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("--input", nargs="*", default=[],
                        help="Clip models to score: an input (its TRN) or input:kind.")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    torch.set_num_threads(1)
    run, _ = reopen_run(args.run)
    val = C.clip_set(run.episodes("val"), run.store.step)
    report = {"labels": label_report(val, run.store.maps, run.store.classes)}
    if args.input:
        features = load_features(args.run)
        report["models"] = [model_report(run, name, args.seed, val, features)
                            for name in args.input]
    print(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
