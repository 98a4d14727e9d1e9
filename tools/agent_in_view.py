"""How well a data set's frames show the agent, from their class maps (docs/dataset.md,
"Framing").

    python tools/agent_in_view.py DATASET_OR_SHARDS... [--first N] [--blocked]

Prints, over every frame with a class map, the share of frames in which the agent covers
less than 0.5% of the image (a figure at the far end of a room, or at the image's edge),
none of it, and the median share it covers, and how often the view cuts (another camera,
or one aimed anew); with --first N, only the first N episodes. With --blocked, also how
often a room camera's view is blocked: more than a fifth of the image nearer than 1 m (a
wall edge or a door beside the camera), from the depth maps.
"""

from __future__ import annotations

import argparse
from itertools import islice

import numpy as np

from homesim.dataset.read import read_episodes

SMALL = 0.005
"""The agent covers less than this share of the image: hardly shown."""
NEAR = 1.0
"""Metres: what is nearer than this to a room camera (other than the agent) blocks it."""
BLOCKED = 0.2
"""A view with more than this share of its pixels near is blocked."""


def agent_mask(episode: dict) -> np.ndarray:
    """(T', H, W) whether each pixel of each mapped frame shows the agent."""
    classes = episode["meta"]["classes"]
    agent = [i for i, name in enumerate(classes) if name == "character"]
    return np.isin(episode["class"], agent)


def near_shares(episode: dict, agent: np.ndarray) -> np.ndarray:
    """(R,) for each mapped frame filmed by a room camera, the share of its pixels nearer
    than `NEAR` that are not the agent."""
    rooms = [bool(c["aimed_at_agent"]) for c in episode["meta"]["cameras"]]
    frames = episode["gt_frames"]
    room_frame = np.asarray([rooms[int(c)] for c in episode["camera"][frames]], bool)
    depth = episode["depth"]
    near = (depth > 0) & (depth < NEAR) & ~agent
    return near.mean(axis=(1, 2))[room_frame]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source", nargs="+", help="A data set folder or shard files.")
    parser.add_argument("--first", type=int, default=None, help="Only the first N episodes.")
    parser.add_argument("--blocked", action="store_true",
                        help="Also measure blocked room-camera views (reads depth maps).")
    args = parser.parse_args()
    source = args.source[0] if len(args.source) == 1 else args.source
    modalities = ("class", "depth") if args.blocked else ("class",)
    per_episode, near, cuts, seconds = [], [], 0, 0.0
    for episode in islice(read_episodes(source, modalities=modalities), args.first):
        agent = agent_mask(episode)
        per_episode.append(agent.mean(axis=(1, 2)))
        if args.blocked:
            near.append(near_shares(episode, agent))
        cuts += int(np.count_nonzero(episode["cut"]))
        seconds += len(episode["cut"]) / episode["meta"]["fps"]
    shares = np.concatenate(per_episode)
    print(f"{shares.size} frames: agent on < {100 * SMALL:.1f}% of the image in "
          f"{100 * np.mean(shares < SMALL):.1f}%, not seen in {100 * np.mean(shares == 0):.1f}%;"
          f" median share {100 * np.median(shares):.2f}%; {60 * cuts / seconds:.1f} cuts a "
          f"minute")
    if near:
        blocked = np.concatenate(near)
        print(f"{blocked.size} room-camera frames: more than {100 * BLOCKED:.0f}% of the image "
              f"nearer than {NEAR:g} m in {100 * np.mean(blocked > BLOCKED):.1f}% "
              f"(more than half in {100 * np.mean(blocked > 0.5):.1f}%)")


if __name__ == "__main__":
    main()
