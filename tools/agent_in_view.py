"""How well a data set's frames show the agent, from their class maps (docs/dataset.md,
"Framing").

    python tools/agent_in_view.py DATASET_OR_SHARDS... [--first N]

Prints, over every frame with a class map, the share of frames in which the agent covers
less than 0.5% of the image (a figure at the far end of a room, or at the image's edge),
none of it, and the median share it covers, and how often the view cuts (another camera,
or one aimed anew); with --first N, only the first N episodes.
"""

from __future__ import annotations

import argparse
from itertools import islice

import numpy as np

from homesim.dataset.read import read_episodes

SMALL = 0.005
"""The agent covers less than this share of the image: hardly shown."""


def agent_shares(episode: dict) -> np.ndarray:
    """(T',) the share of each mapped frame's pixels that belong to the agent."""
    classes = episode["meta"]["classes"]
    agent = [i for i, name in enumerate(classes) if name == "character"]
    return np.isin(episode["class"], agent).mean(axis=(1, 2))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source", nargs="+", help="A data set folder or shard files.")
    parser.add_argument("--first", type=int, default=None, help="Only the first N episodes.")
    args = parser.parse_args()
    source = args.source[0] if len(args.source) == 1 else args.source
    per_episode, cuts, seconds = [], 0, 0.0
    for episode in islice(read_episodes(source, modalities=("class",)), args.first):
        per_episode.append(agent_shares(episode))
        cuts += int(np.count_nonzero(episode["cut"]))
        seconds += len(episode["cut"]) / episode["meta"]["fps"]
    shares = np.concatenate(per_episode)
    print(f"{shares.size} frames: agent on < {100 * SMALL:.1f}% of the image in "
          f"{100 * np.mean(shares < SMALL):.1f}%, not seen in {100 * np.mean(shares == 0):.1f}%;"
          f" median share {100 * np.median(shares):.2f}%; {60 * cuts / seconds:.1f} cuts a "
          f"minute")


if __name__ == "__main__":
    main()
