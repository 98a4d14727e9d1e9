"""Replay an episode of a data set: render it again from its recorded spec."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from homesim.dataset.episode import Outcome
from homesim.dataset.generate import load_programs, replay_episode
from homesim.dataset.layout import Layout, read_json
from homesim.dataset.manifest import read_manifest
from homesim.dataset.spec import DatasetConfig, EpisodeSpec, episode_key, plan_episodes
from homesim.dataset.verify import iter_episodes
from homesim.errors import DataError


@dataclass(frozen=True)
class Recorded:
    """What a data set recorded of one episode: its spec, the run's config, the episode's
    checksum (None for a failed one) and the format the data set was written in."""

    spec: EpisodeSpec
    config: DatasetConfig
    sha256: str | None
    format: str | None


def find_spec(root: str | Path, key: str) -> Recorded:
    """What the data set at `root` recorded of episode `key` (or its index).

    A made episode's spec is read from its json member; a failed one's is drawn again
    from the config (the same seed gives the same spec)."""
    layout = Layout(root)
    info = read_json(layout.config_path) if layout.config_path.exists() else None
    if not isinstance(info, dict):
        raise DataError(f"{root}: not a homesim data set (no dataset.json)")
    config = DatasetConfig.from_dict(info["config"])
    key = episode_key(int(key)) if key.isdigit() else key
    rows = {r["key"]: r for r in read_manifest(layout.manifest_path)}
    if key not in rows:
        raise DataError(f"{root}: no episode {key} (ep-000000 .. "
                        f"{episode_key(config.n - 1)})")
    row = rows[key]
    return Recorded(_spec(layout, config, key, row), config, row["sha256"], info.get("format"))


def _spec(layout: Layout, config: DatasetConfig, key: str, row: dict) -> EpisodeSpec:
    index = int(row["index"])
    if row["status"] == "ok":
        shard = layout.shards / f"shard-{index // config.shard_size:06d}.tar"
        for k, members in iter_episodes(shard):
            if k == key:
                meta = json.loads(dict(members)[f"{key}.json"])
                return EpisodeSpec.from_dict(meta["spec"])
    programs = load_programs(config)
    return plan_episodes(config, programs)[index]


def replay_from_dataset(root: str | Path, key: str, out: str | Path
                        ) -> tuple[Outcome, Recorded]:
    """Render episode `key` of the data set at `root` into `out`; returns its outcome and
    what the data set recorded (the checksums are equal when the replay is exact)."""
    recorded = find_spec(root, key)
    return replay_episode(recorded.spec, recorded.config, Path(out)), recorded
