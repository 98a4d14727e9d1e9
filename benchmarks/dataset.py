"""Activity data set throughput: episodes/hour per core of the `full` and `learn` profiles,
bytes per frame; with --scaling, 1 and 2 local Ray workers; with --data, the loader.

Profiles (default): both make the same episodes (same seed, programs and choices) with
`generate_dataset(workers=0)`, one after the other in this process: one core, llvmpipe
rasterizing in the calling thread as in a data set worker. Each is timed after one
warm-up episode (another seed: imports, knowledge base, GL context, paid once per
worker, not per episode). Per core: episodes / CPU hours of this process (every thread of it);
the wall rate is printed beside it (the same on a quiet machine). The ratio learn / full
is measured in the same run.

Scaling (--scaling): the same episodes with 1 and 2 local Ray workers (Ray started before
the clock), and the loader with 2 DataLoader workers against 0.

Goals: learn >= 2 000 episodes/h per core (issue 42); 2 workers >= 1.8x the episodes/hour
of 1 and <= 100 KB per frame (issue 14, full profile).

    python benchmarks/dataset.py [--n 12] [--seed 0] [--profiles full,learn]
    python benchmarks/dataset.py --scaling [--n 8] [--profile full]
    python benchmarks/dataset.py --data DIR     # the loader only, on a data set made before
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from homesim.dataset import DatasetConfig, Summary, generate_dataset
from homesim.dataset.spec import MODALITIES, PROFILES

PAPER_EPISODES = 5193
LEARN_GOAL = 2000  # episodes per hour per core


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


def profile_rate(name: str, n: int, seed: int, tmp: Path) -> tuple[Summary, float, float]:
    """(summary, wall seconds, CPU seconds) of `n` episodes of a profile, in this process,
    after a warm-up episode of another seed."""
    config = DatasetConfig.from_profile(name, n=n, seed=seed, shard_size=4)
    generate_dataset(replace(config, n=1, seed=seed + 1), tmp / f"{name}-warm", workers=0)
    t0, c0 = time.perf_counter(), time.process_time()
    summary = generate_dataset(config, tmp / name, workers=0)
    return summary, time.perf_counter() - t0, time.process_time() - c0


def profiles(n: int, seed: int, names: tuple[str, ...] = ("full", "learn")) -> None:
    """Episodes/h per core of each profile and the ratio learn / full (when both ran)."""
    rates = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            p = PROFILES[name]
            summary, wall, cpu = profile_rate(name, n, seed, Path(tmp))
            per_core = n / cpu * 3600
            rates[name] = per_core
            print(f"{name}: {p.width}x{p.height}, {p.fps} fps, {'+'.join(p.modalities)}: "
                  f"{summary.episodes} episodes ({summary.failed} failed, {summary.frames} "
                  f"frames) in {cpu:.1f} CPU s / {wall:.1f} s wall = {per_core:.0f} "
                  f"episodes/h per core ({n / wall * 3600:.0f} by wall); "
                  f"{summary.bytes_per_frame / 1e3:.1f} KB per frame")
    if "full" in rates and "learn" in rates:
        print(f"ratio learn / full: {rates['learn'] / rates['full']:.2f}x")
    if "learn" in rates:
        print(f"learn {rates['learn']:.0f} episodes/h per core (goal >= {LEARN_GOAL})")


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


def time_loader(root: Path, kept: tuple[str, ...] = MODALITIES) -> None:
    """Clips/s with 2 DataLoader workers against 0, RGB only and every modality the data
    set keeps (`kept`: the learn profile has no depth, instance or flow)."""
    for modalities in (("rgb",), tuple(m for m in MODALITIES if m in kept)):
        _, rate0, _ = clips_per_second(root, 0, modalities)
        n2, rate2, cpu = clips_per_second(root, 2, modalities)
        print(f"loader, {'+'.join(modalities)}, 2 s clips: {rate2:.1f} clips/s with 2 "
              f"workers, {rate0:.1f} clips/s with 0 ({n2} clips; ratio {rate2 / rate0:.2f}x); "
              f"{cpu:.3f} CPU s per clip with 2 workers")


def scaling(n: int, seed: int, profile: str) -> None:
    """Episodes/hour with 1 and 2 local Ray workers, bytes per frame, the loader."""
    config = DatasetConfig.from_profile(profile, n=n, seed=seed, shard_size=2)
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
        if "rgb" in config.modalities:
            time_loader(Path(tmp) / "w2", config.modalities)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=12, help="timed episodes per run")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--scaling", action="store_true",
                        help="1 and 2 Ray workers and the loader instead of the profiles")
    parser.add_argument("--profile", default="full", choices=sorted(PROFILES),
                        help="the profile of --scaling")
    parser.add_argument("--data", type=Path, help="time the loader only, on this data set")
    parser.add_argument("--profiles", default="full,learn",
                        help="the profiles to time, comma-separated (default: full,learn)")
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")
    if args.data:
        time_loader(args.data)
    elif args.scaling:
        scaling(args.n, args.seed, args.profile)
    else:
        names = tuple(args.profiles.split(","))
        unknown = sorted(set(names) - set(PROFILES))
        if unknown:
            parser.error(f"--profiles: unknown {', '.join(unknown)}; choose from "
                         f"{', '.join(PROFILES)}")
        profiles(args.n, args.seed, names)
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
