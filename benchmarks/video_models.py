"""Training speed of Table 2's models on a device against the CPU, in the same run.

For each model (the segmentation network, the RGB and class-map frame encoders, the clip
TRN over frame features) a fixed number of training batches of random inputs of the
learning format (64x48 frames, 32x24 maps, 8-frame clips of 64-d features), timed on
`--device` and on the CPU (the reference): items per second on each and the ratio.
Random inputs cost what real ones do (the models are dense), and need no data set.

    python benchmarks/video_models.py --device cuda [--batches 30] [--threads 2]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
import torch
import torch.nn.functional as F

from homesim.learn.video.clips import FRAMES, ClipConfig, ClipModel
from homesim.learn.video.framecnn import FrameCNN, FrameCNNConfig
from homesim.learn.video.segment import SegConfig, SegNet

CLASSES, ACTIONS, STEPS = 120, 12, 700


def _models(batch: int) -> dict[str, tuple[torch.nn.Module, torch.Tensor, object]]:
    """Name -> (model, input batch, target) on the CPU."""
    rng = np.random.default_rng(0)
    frames = torch.from_numpy(rng.integers(0, 256, (batch, 3, 48, 64), dtype=np.uint8))
    maps = torch.from_numpy(rng.integers(0, CLASSES, (batch, 24, 32), dtype=np.uint8))
    clips = torch.from_numpy(rng.standard_normal((batch, FRAMES, 64)).astype(np.float32))
    heads = (torch.from_numpy(rng.integers(0, ACTIONS, batch)),
             torch.from_numpy(rng.integers(0, STEPS, batch)))
    torch.manual_seed(0)
    return {
        "segmentation": (SegNet(SegConfig(CLASSES)), frames, maps.long()),
        "frame encoder (rgb)": (FrameCNN(FrameCNNConfig(ACTIONS, STEPS)), frames, heads),
        "frame encoder (map)": (FrameCNN(FrameCNNConfig(ACTIONS, STEPS, "map", CLASSES)),
                                maps, heads),
        "clip TRN": (ClipModel(ClipConfig("trn", "rgb", 64, ACTIONS, STEPS)), clips, heads),
    }


def _loss(name: str, model: torch.nn.Module, x: torch.Tensor, y: object) -> torch.Tensor:
    if name == "segmentation":
        return F.cross_entropy(model(x), y)  # type: ignore[arg-type]
    out = model.heads(x) if isinstance(model, FrameCNN) else model(x)
    ya, ys = y  # type: ignore[misc]
    return F.cross_entropy(out[0], ya) + F.cross_entropy(out[1], ys)


def items_per_second(name: str, model: torch.nn.Module, x: torch.Tensor, y: object,
                     device: str, batches: int) -> float:
    """Training batches of (x, y) on `device`: items per second after two warm-ups."""
    model = model.to(device).train()
    x = x.to(device)
    y = tuple(t.to(device) for t in y) if isinstance(y, tuple) else y.to(device)  # type: ignore[union-attr]
    opt = torch.optim.Adam(model.parameters(), lr=1e-3)

    def one() -> None:
        loss = _loss(name, model, x, y)
        opt.zero_grad()
        loss.backward()
        opt.step()

    for _ in range(2):
        one()
    if device.startswith("cuda"):
        torch.cuda.synchronize()
    start = time.perf_counter()
    for _ in range(batches):
        one()
    if device.startswith("cuda"):
        torch.cuda.synchronize()
    return batches * len(x) / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--batches", type=int, default=30)
    parser.add_argument("--batch-size", type=int, default=64)
    parser.add_argument("--threads", type=int, default=2, help="CPU threads (reference)")
    args = parser.parse_args()
    torch.set_num_threads(args.threads)
    out = {}
    for name, (model, x, y) in _models(args.batch_size).items():
        cpu = items_per_second(name, model, x, y, "cpu", args.batches)
        dev = items_per_second(name, model, x, y, args.device, args.batches)
        out[name] = {"cpu": cpu, args.device: dev, "ratio": dev / cpu}
        print(f"{name:22s} cpu ({args.threads} threads) {cpu:9.0f}/s   {args.device} "
              f"{dev:9.0f}/s   ratio {dev / cpu:6.1f}x")
    print(json.dumps(out))


if __name__ == "__main__":
    main()
