"""Replay an episode of a data set: render it again from its recorded spec."""

from __future__ import annotations

import json
from pathlib import Path

from homesim.dataset.episode import Outcome
from homesim.dataset.generate import load_programs, replay_episode
from homesim.dataset.layout import Layout, read_json
from homesim.dataset.manifest import read_manifest
from homesim.dataset.spec import DatasetConfig, EpisodeSpec, episode_key, plan_episodes
from homesim.dataset.verify import iter_episodes
from homesim.errors import DataError


def find_spec(root: str | Path, key: str) -> tuple[EpisodeSpec, DatasetConfig, str | None]:
    """The spec of episode `key` (or its index), the config, and its recorded checksum.

    A made episode's spec is read from its json member; a failed one's is drawn again
    from the config (the same seed gives the same spec)."""
    layout = Layout(root)
    info = read_json(layout.config_path) if layout.config_path.exists() else None
    if info is None:
        raise DataError(f"{root}: not a homesim data set (no dataset.json)")
    config = DatasetConfig.from_dict(info["config"])
    key = episode_key(int(key)) if key.isdigit() else key
    rows = {r["key"]: r for r in read_manifest(layout.manifest_path)}
    if key not in rows:
        raise DataError(f"{root}: no episode {key} (ep-000000 .. "
                        f"{episode_key(config.n - 1)})")
    row = rows[key]
    index = int(row["index"])
    if row["status"] == "ok":
        shard = layout.shards / f"shard-{index // config.shard_size:06d}.tar"
        for k, members in iter_episodes(shard):
            if k == key:
                meta = json.loads(dict(members)[f"{key}.json"])
                return EpisodeSpec.from_dict(meta["spec"]), config, row["sha256"]
    programs = load_programs(config.programs, config.n, config.seed)
    return plan_episodes(config, programs)[index], config, row["sha256"]


def recorded_format(root: str | Path) -> str | None:
    """The format the data set at `root` was written in (None where it records none)."""
    info = read_json(Layout(root).config_path)
    return info.get("format") if isinstance(info, dict) else None


def replay_from_dataset(root: str | Path, key: str, out: str | Path
                        ) -> tuple[Outcome, str | None]:
    """Render episode `key` of the data set at `root` into `out`; returns its outcome and
    the checksum the data set recorded (equal when the replay is exact)."""
    spec, config, expected = find_spec(root, key)
    return replay_episode(spec, config, Path(out)), expected
