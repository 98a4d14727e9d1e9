"""Is seeing the body what Table 2's clip models lack? Probes on validation only.

For a trained run folder (its frame stage done), the TRN of seed `--seed` is trained again
with the run's settings over other per-frame descriptors and scored on the validation
clips (never a test part):

- ``box``: the oracle map features + the agent's box in the ground-truth class map (its
  size, centre, extent, whether it shows: 7 numbers);
- ``pose``: the agent's ground-truth 2-D joints alone (the episodes' ``joints2d``: each
  joint relative to the body's centre in body heights, its visibility, the centre's place
  in the frame);
- ``oracle+pose``: the oracle map features and the joints.

The joints come from the data set's shards (the animation's ground truth), so these are
upper bounds for a recogniser that sees the body perfectly, not Table 2 rows.

    python tools/video_body_probe.py out/dev DATA --probes box pose oracle+pose
"""

from __future__ import annotations

import argparse
import io
import json
import tarfile
import time
from pathlib import Path

import numpy as np
import torch

from homesim.learn.video import clips as C
from homesim.learn.video.table import Run, clip_config, reopen_run, train_labels

JOINTS = 16


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


def _episode_pose(joints: np.ndarray, visible: np.ndarray, width: int, height: int
                  ) -> np.ndarray:
    j = joints.astype(np.float32) / np.array([width, height], np.float32)
    centre = j.mean(1, keepdims=True)
    tall = (j[..., 1].max(1) - j[..., 1].min(1))[:, None, None] + 1e-3
    rel = ((j - centre) / tall).reshape(len(j), -1)
    return np.concatenate([rel, visible.astype(np.float32), centre.reshape(len(j), 2)], 1)


def body_pose(run: Run, data: Path) -> np.ndarray:
    """(store rows, 3 x JOINTS + 2): each stored frame's joints (`_episode_pose`), read
    from the shards of the train and val parts (zeros elsewhere)."""
    where = {e.key: e for e in run.store.episodes}
    pose = np.zeros((len(run.store.step), 3 * JOINTS + 2), np.float32)
    for part in (*run.split.parts("train"), *run.split.parts("val")):
        size = _frame_size(data / part)
        for shard in sorted((data / part / "shards").glob("*.tar")):
            with tarfile.open(shard) as tar:
                members = {m.name: m for m in tar.getmembers()}
                for name, member in members.items():
                    ep = name.split(".")[0]
                    e = where.get(f"{part}/{ep}")
                    if not name.endswith(".joints2d.npy") or e is None:
                        continue
                    rows = _episode_pose(_array(tar, member),
                                         _array(tar, members[f"{ep}.joints_visible.npy"]),
                                         *size)
                    n = min(len(rows), e.length)
                    pose[e.start:e.start + n] = rows[:n]
    return pose


def _array(tar: tarfile.TarFile, member: tarfile.TarInfo) -> np.ndarray:
    data = tar.extractfile(member)
    assert data is not None
    return np.load(io.BytesIO(data.read()))


def _frame_size(folder: Path) -> tuple[int, int]:
    config = json.loads((folder / "dataset.json").read_text(encoding="utf-8"))["config"]
    return int(config["width"]), int(config["height"])


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("data", type=Path, help="The run's plan folder (its shards).")
    parser.add_argument("--probes", nargs="+", default=["box", "pose", "oracle+pose"])
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    torch.set_num_threads(1)
    run, _ = reopen_run(args.run)
    oracle = np.load(args.run / "features" / "oracle.npy").astype(np.float32)
    scale = 4 * float(np.abs(oracle).mean())  # extra numbers on the features' scale
    pose = body_pose(run, args.data) * scale if {"pose", "oracle+pose"} & set(args.probes) \
        else None
    for name in args.probes:
        start = time.perf_counter()
        if name == "box":
            box = agent_box(run.store.maps, run.store.classes.index("character"))
            x = np.concatenate([oracle, box * scale], 1)
        elif name == "pose" and pose is not None:
            x = pose
        elif name == "oracle+pose" and pose is not None:
            x = np.concatenate([oracle, pose], 1)
        else:
            raise SystemExit(f"--probes {name}: choose box, pose or oracle+pose")
        row = probe(run, name, x, args.seed)
        print(json.dumps({**row, "seconds": round(time.perf_counter() - start)}), flush=True)


if __name__ == "__main__":
    main()
