"""Reading episodes for Table 2: why frames are scaled by ffmpeg and cached per episode.

Each figure is a ratio against a reference measured in the same run, on one data set
shard (default: the first finished shard of the folder given):

- scaling: decoding the H.264 video at full size and area-pooling every frame with torch
  (the reference), against ffmpeg's area filter scaling while it decodes
  (`videocache.small_video`);
- cache: reducing the shard's episodes (video, class maps, steps) against reading the
  reduced episodes back from the cache.

Goal: the cache read at least 20x faster than reducing, so that every seed and the
evaluation of the table read a 200-episode set in seconds once it has been reduced.

    python benchmarks/video_cache.py --data /work/data/act200 [--repeat 2]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F

from _timing import best_of
from homesim.dataset.layout import Layout
from homesim.dataset.read import EncodedEpisode
from homesim.dataset.verify import iter_episodes
from homesim.learn.video.cache import VideoFormat, episode_rows, shard_episodes, small_video
from homesim.render.video import decode_video


def torch_pooled(ep: EncodedEpisode, fmt: VideoFormat) -> np.ndarray:
    """The reference: every frame decoded at full size, then area-pooled."""
    frames = decode_video(ep.video or b"", ep.meta["width"], ep.meta["height"])
    x = torch.from_numpy(frames).permute(0, 3, 1, 2).float()
    return F.adaptive_avg_pool2d(x, (fmt.height, fmt.width)).round().to(torch.uint8).numpy()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, required=True, help="a data set folder")
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    torch.set_num_threads(1)
    fmt = VideoFormat()
    layout = Layout(args.data)
    info = layout.finished_shards()[0]
    shard, rows = layout.shards / info["name"], episode_rows(info["rows"])
    key, members = next(iter_episodes(shard))
    ep = EncodedEpisode(key, members)

    t_torch = best_of(lambda: torch_pooled(ep, fmt), args.repeat)
    t_ffmpeg = best_of(lambda: small_video(ep.video or b"", fmt), args.repeat)
    print(f"scaling {ep.num_frames} frames of {ep.meta['width']}x{ep.meta['height']} to "
          f"{fmt.width}x{fmt.height}: decode + torch pool {t_torch:.2f} s, ffmpeg area filter "
          f"{t_ffmpeg:.2f} s; ratio {t_torch / t_ffmpeg:.1f}x")

    with tempfile.TemporaryDirectory() as cache:
        t_reduce = best_of(lambda: shard_episodes(shard, rows, fmt, Path(cache)), 1)
        t_read = best_of(lambda: shard_episodes(shard, rows, fmt, Path(cache)), args.repeat)
    print(f"shard of {len(rows)} episodes: reducing {t_reduce:.1f} s, reading the cache "
          f"{t_read:.2f} s; ratio {t_reduce / t_read:.0f}x (goal >= 20x)")


if __name__ == "__main__":
    main()
