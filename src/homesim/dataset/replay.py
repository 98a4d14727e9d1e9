"""Replay an episode of a data set: render it again from its recorded spec."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from homesim.dataset.episode import Outcome
from homesim.dataset.generate import load_programs, replay_episode
from homesim.dataset.layout import Layout, read_json
from homesim.dataset.manifest import read_manifest
from homesim.dataset.spec import DatasetConfig, EpisodeSpec, draw_spec, episode_key
from homesim.dataset.verify import scan_shard
from homesim.errors import DataError, HomesimError, excerpt
from homesim.files import check_target


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
    from the config (the same seed gives the same spec). `DataError` in one line when the
    data set cannot tell (a file missing or damaged: ``homesim dataset verify`` says
    more)."""
    layout = Layout(root)
    if not layout.config_path.exists() and not layout.config_path.is_symlink():
        raise DataError(f"{root}: not a homesim data set (no dataset.json)")
    info = read_json(layout.config_path)
    if not isinstance(info, dict):
        raise DataError(f"{layout.config_path}: expected a JSON object")
    config = DatasetConfig.from_dict(info.get("config"))
    key = _key(key, root, config)
    rows = [r for r in read_manifest(layout.manifest_path) if r.get("key") == key]
    if not rows:
        raise DataError(f"{root}: no episode {excerpt(key, 40)} (ep-000000 .. "
                        f"{episode_key(config.n - 1)})")
    row = rows[0]
    index, status = row.get("index"), row.get("status")
    if type(index) is not int or not 0 <= index < config.n or status not in ("ok", "failed"):
        raise DataError(f"{layout.manifest_path}: the row of {key} is damaged")
    sha = row.get("sha256") if isinstance(row.get("sha256"), str) else None
    format = info.get("format") if isinstance(info.get("format"), str) else None
    return Recorded(_spec(layout, config, key, index, status == "ok"), config, sha, format)


def _key(key: str, root: str | Path, config: DatasetConfig) -> str:
    if key.isascii() and key.isdigit():
        if len(key) > 9:
            raise DataError(f"{root}: no episode {excerpt(key, 20)} (ep-000000 .. "
                            f"{episode_key(config.n - 1)})")
        return episode_key(int(key))
    return key


def _spec(layout: Layout, config: DatasetConfig, key: str, index: int, ok: bool
          ) -> EpisodeSpec:
    if ok:
        shard = layout.shards / f"shard-{index // config.shard_size:06d}.tar"
        try:
            meta = next((e.meta for e in scan_shard(shard) if e.key == key), None)
            if meta is None:
                raise DataError(f"{shard.name}: {key}.json: missing")
            data = json.loads(meta)
        except HomesimError as e:
            raise DataError(f"{layout.root}: cannot read episode {key}: {e}") from None
        except (ValueError, RecursionError):
            raise DataError(f"{shard.name}: {key}.json: not JSON") from None
        spec = data.get("spec") if isinstance(data, dict) else None
        try:
            return EpisodeSpec.from_dict(spec)
        except DataError as e:
            raise DataError(f"{shard.name}: {key}.json: {e}") from None
    programs = load_programs(config, count=index + 1)  # a synth data set: only those
    if not programs:
        raise DataError(f"{config.programs}: no programs")
    return draw_spec(config, index, *programs[index % len(programs)])


def replay_from_dataset(root: str | Path, key: str, out: str | Path, force: bool = False
                        ) -> tuple[Outcome, Recorded]:
    """Render episode `key` of the data set at `root` into `out`; returns its outcome and
    what the data set recorded (the checksums are equal when the replay is exact). An
    existing `out` is replaced only with `force`, and never by a replay that fails."""
    check_target(out, force)
    recorded = find_spec(root, key)
    return replay_episode(recorded.spec, recorded.config, Path(out)), recorded
