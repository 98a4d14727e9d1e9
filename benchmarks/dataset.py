"""Activity data set throughput: episodes/hour with 1 and 2 local Ray workers, bytes per
frame (and the size of 5 193 episodes), and loader clips/s with 2 DataLoader workers.

Both generation runs make the same episodes (same seed) at 320x240 with every modality at
full frame rate; Ray is started before the clock starts, so the ratio compares the work,
not Ray's start-up. The loader is timed with 2 workers against 0 workers in the same run.

Goals (issue 14): 2 workers >= 1.8x the episodes/hour of 1; <= 100 KB per frame.

    python benchmarks/dataset.py [--n 8] [--width 320 --height 240 --fps 15]
    python benchmarks/dataset.py --data DIR     # the loader only, on a data set made before
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
from pathlib import Path

from homesim.dataset import DatasetConfig, Summary, generate_dataset

PAPER_EPISODES = 5193


def timed_generation(config: DatasetConfig, out: Path, workers: int) -> tuple[Summary, float]:
    import ray

    ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False,
             configure_logging=False, object_store_memory=256 * 1024**2)
    try:
        t0 = time.perf_counter()
        summary = generate_dataset(config, out, workers=workers)
        return summary, time.perf_counter() - t0
    finally:
        ray.shutdown()


def cpu_seconds() -> float:
    """User + system CPU time of this process and its finished children (loader workers)."""
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(
        resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def clips_per_second(root: Path, workers: int, modalities: tuple[str, ...]
                     ) -> tuple[int, float, float]:
    """Clips, clips per wall second and CPU seconds per clip."""
    from torch.utils.data import DataLoader

    from homesim.dataset.loader import ActivityClips

    loader = DataLoader(ActivityClips(root, modalities=modalities), batch_size=8,
                        num_workers=workers)
    t0, c0 = time.perf_counter(), cpu_seconds()
    clips = sum(len(batch["key"]) for batch in loader)
    return clips, clips / (time.perf_counter() - t0), (cpu_seconds() - c0) / clips


def time_loader(root: Path) -> None:
    """Clips/s with 2 DataLoader workers against 0, RGB only and every modality."""
    for modalities in (("rgb",), ("rgb", "depth", "class", "instance", "flow")):
        _, rate0, _ = clips_per_second(root, 0, modalities)
        n2, rate2, cpu = clips_per_second(root, 2, modalities)
        print(f"loader, {'+'.join(modalities)}, 2 s clips: {rate2:.1f} clips/s with 2 "
              f"workers, {rate0:.1f} clips/s with 0 ({n2} clips; ratio {rate2 / rate0:.2f}x); "
              f"{cpu:.3f} CPU s per clip with 2 workers")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=8, help="episodes per run")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--fps", type=int, default=15)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--data", type=Path, help="time the loader only, on this data set")
    args = parser.parse_args()
    if args.data:
        print(f"load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")
        time_loader(args.data)
        print(f"load average after: {os.getloadavg()[0]:.1f}")
        return
    config = DatasetConfig(n=args.n, seed=args.seed, width=args.width, height=args.height,
                           fps=args.fps, shard_size=2)
    print(f"load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")
    rates = {}
    with tempfile.TemporaryDirectory() as tmp:
        for workers in (1, 2):
            summary, seconds = timed_generation(config, Path(tmp) / f"w{workers}", workers)
            rates[workers] = summary.episodes / seconds * 3600
            print(f"{workers} Ray worker(s): {summary.episodes} episodes ({summary.failed} "
                  f"failed, {summary.frames} frames) in {seconds:.0f} s = "
                  f"{rates[workers]:.1f} episodes/hour")
        print(f"ratio 2 workers / 1 worker: {rates[2] / rates[1]:.2f}x (goal >= 1.8x)")
        per_episode = summary.disk_bytes / max(summary.ok, 1)
        print(f"bytes per frame on disk: {summary.bytes_per_frame / 1e3:.1f} KB (goal <= 100 KB); "
              f"{per_episode / 1e6:.1f} MB per episode -> {PAPER_EPISODES} episodes: "
              f"{per_episode * PAPER_EPISODES / 1e9:.1f} GB")
        time_loader(Path(tmp) / "w2")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
