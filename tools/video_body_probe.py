"""Is seeing the body what Table 2's clip models lack? Probes on validation only.

For a trained run folder (its frame stage done), the TRN of seed `--seed` is trained again
with the run's settings over other per-frame descriptors and scored on the validation
clips (never a test part):

- ``box``: the oracle map features + the agent's box in the ground-truth class map (its
  size, centre, extent, whether it shows: 7 numbers);
- ``pose``: the agent's ground-truth 2-D joints alone (the store's ``joints``, from the
  episodes' ``joints2d``, as `pose.pose_descriptor` describes them);
- ``oracle+pose``: the oracle map features and the ground-truth joints;
- ``predicted-pose``: the joints the run's pose network predicts (`table.pose_network`,
  trained first if the run has none), alone;
- ``seg+pose``: the predicted maps' features and the predicted joints;
- ``seg+pose+hands``: those and the classes of the predicted maps round the predicted
  wrists (`hands.hand_context`; the Table 2 row of that name);
- ``oracle+pose+hands``: the oracle map features, the ground-truth joints and the classes
  of the ground-truth maps round their wrists.

The ground-truth joints are the animation's, so ``pose`` and ``oracle+pose`` are upper
bounds for a recogniser that sees the body perfectly, not Table 2 rows.

    python tools/video_body_probe.py out/dev --probes box pose oracle+pose seg+pose+hands
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np
import torch

from homesim.learn.video import clips as C
from homesim.learn.video.pose import pose_descriptor
from homesim.learn.video.table import (
    Run,
    body_features,
    clip_config,
    pose_network,
    reopen_run,
    train_labels,
    with_pose,
)


def agent_box(maps: np.ndarray, agent: int, chunk: int = 20000) -> np.ndarray:
    """(N, 7): the agent's class pixels in each map: sqrt of its share, centre x and y,
    width, height, top (all as fractions of the map) and whether it shows."""
    n, h, w = maps.shape
    ys, xs = np.mgrid[0:h, 0:w]
    out = np.zeros((n, 7), np.float32)
    for i in range(0, n, chunk):
        m = np.asarray(maps[i:i + chunk]) == agent
        area = m.sum((1, 2)).astype(np.float32)
        seen = area > 0
        a = np.maximum(area, 1)
        cols, rows = m.any(1), m.any(2)
        x0 = np.where(seen, cols.argmax(1), 0) / w
        x1 = np.where(seen, w - cols[:, ::-1].argmax(1), 0) / w
        y0 = np.where(seen, rows.argmax(1), 0) / h
        y1 = np.where(seen, h - rows[:, ::-1].argmax(1), 0) / h
        out[i:i + chunk] = np.stack([np.sqrt(area / (h * w)), (m * xs).sum((1, 2)) / a / w,
                                     (m * ys).sum((1, 2)) / a / h, x1 - x0, y1 - y0, y0,
                                     seen], 1)
    return out


def probe(run: Run, name: str, descriptors: np.ndarray, seed: int) -> dict:
    """The TRN of `seed` over `descriptors` (store rows, width), scored on validation."""
    cfg_run, labels = run.config, train_labels(run)
    train = C.clip_set(run.episodes("train"), run.store.step, cfg_run.train_hop)
    val = C.clip_set(run.episodes("val"), run.store.step)
    x = descriptors.astype(np.float16)
    cfg = clip_config(cfg_run, labels, "trn", "oracle", x.shape[1], seed)
    model, _ = C.train_clip_model(cfg, x, train, labels, val)
    actions, steps = C.predict_clips(model, x, val, labels)
    recall = {a: round(100.0 * sum(p == a for p, t in zip(actions, val.actions, strict=True)
                                   if t == a) / val.actions.count(a), 1)
              for a in sorted(set(val.actions))}
    return {"probe": name, "action": round(C.mean_class_accuracy(actions, val.actions), 2),
            "step": round(C.mean_class_accuracy(steps, val.steps), 2), "recall": recall}


def descriptors(run: Run, name: str) -> np.ndarray:
    """The per-frame descriptors of probe `name` (see the module)."""
    train_rows = run.store.rows(run.episodes("train"))
    features = run.out / "features"
    if name == "box":
        oracle = np.load(features / "oracle.npy")
        box = agent_box(run.store.maps, run.store.classes.index("character"))
        scale = 4 * float(np.abs(oracle).mean())  # the box on the features' scale
        return np.concatenate([oracle.astype(np.float32), box * scale], 1)
    if name == "pose":
        return pose_descriptor(run.store.joints)
    if name == "oracle+pose":
        return with_pose(np.load(features / "oracle.npy"), run.store.joints, train_rows)
    if name == "predicted-pose":
        return pose_descriptor(pose_network(run))
    if name == "seg+pose":
        return with_pose(np.load(features / "seg.npy"), pose_network(run), train_rows)
    if name == "seg+pose+hands":
        maps = np.load(features / "segmaps.npy", mmap_mode="r")
        return body_features(run, np.load(features / "seg.npy"), pose_network(run), maps)
    if name == "oracle+pose+hands":
        return body_features(run, np.load(features / "oracle.npy"), run.store.joints,
                             run.store.maps)
    raise SystemExit(f"--probes {name}: choose box, pose, oracle+pose, predicted-pose, "
                     "seg+pose, seg+pose+hands or oracle+pose+hands")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("--probes", nargs="+", default=["box", "pose", "oracle+pose"])
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    torch.set_num_threads(1)
    run, _ = reopen_run(args.run)
    for name in args.probes:
        start = time.perf_counter()
        row = probe(run, name, descriptors(run, name), args.seed)
        print(json.dumps({**row, "seconds": round(time.perf_counter() - start)}), flush=True)


if __name__ == "__main__":
    main()
