"""The folder of a data set, and the resumable steps that fill it.

    DIR/dataset.json            format, config, then (when complete) shards and counts
    DIR/episodes.parquet        the manifest: one row per episode (when complete)
    DIR/shards/shard-NNNNNN.tar WebDataset shard: the episodes NNNNNN*S .. +S-1 that worked
    DIR/shards/shard-NNNNNN.json  its rows and checksum, written after the tar
    DIR/staging/ep-NNNNNN.tar   an episode made but not yet in its shard
    DIR/staging/ep-NNNNNN.json  its row (written after the tar; alone for a failure)

Every file is written atomically (`homesim.files`): a kill leaves a complete file or none
(plus a ``.homesim-*`` temporary, removed on restart). A shard counts as done when its json
exists and the tar's SHA-256 matches it; an episode counts as made when its staging json
exists (and, if it worked, its tar's members hash to the recorded checksum).
"""

from __future__ import annotations

import json
import shutil
import tarfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from homesim.dataset.spec import FORMAT, DatasetConfig, EpisodeSpec
from homesim.dataset.tarfiles import MemberHash, add_member, file_sha256, iter_members, open_writer
from homesim.errors import DataError, HomesimError
from homesim.files import TEMP_PREFIX, atomic_write, write_text


def shard_name(k: int) -> str:
    return f"shard-{k:06d}"


def dumps(data: Any) -> str:
    """JSON as every file of a data set writes it (sorted keys: same data, same bytes)."""
    return json.dumps(data, indent=1, sort_keys=True) + "\n"


def read_json(path: Path) -> Any:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise DataError(f"{path}: cannot read ({e})") from None


def _with_defaults(stored: Any) -> Any:
    """A stored config with the options added since it was written at their defaults
    (`--agents`), so that an older folder still resumes."""
    if not isinstance(stored, dict):
        return stored
    try:
        return DatasetConfig.from_dict(stored).to_dict()
    except (HomesimError, TypeError, KeyError):
        return stored


class Layout:
    """Paths and steps of one data set folder."""

    def __init__(self, root: str | Path):
        self.root = Path(root)
        self.staging = self.root / "staging"
        self.shards = self.root / "shards"
        self.config_path = self.root / "dataset.json"
        self.manifest_path = self.root / "episodes.parquet"

    # -- opening ------------------------------------------------------------------
    def open(self, config: DatasetConfig) -> None:
        """Create the folder for `config`, or check that it was begun with the same one."""
        if self.root.exists() and not self.root.is_dir():
            raise HomesimError(f"{self.root}: not a folder")
        if self.config_path.exists():
            stored = read_json(self.config_path)
            if stored.get("format") != FORMAT:
                raise HomesimError(f"{self.root}: holds a data set in format "
                                   f"{stored.get('format')}, not {FORMAT}; use another --out "
                                   "folder")
            old = _with_defaults(stored.get("config"))
            if old != config.to_dict():
                diff = sorted(k for k in config.to_dict() if (old or {}).get(k) !=
                              config.to_dict()[k])
                raise HomesimError(
                    f"{self.root}: holds a data set made with other options ({', '.join(diff)}"
                    "); use another --out folder, or the same options to resume")
        elif self.root.exists() and any(self.root.iterdir()):
            raise HomesimError(f"{self.root}: not empty and not a homesim data set")
        self.staging.mkdir(parents=True, exist_ok=True)
        self.shards.mkdir(parents=True, exist_ok=True)
        if not self.config_path.exists():
            write_text(self.config_path, dumps({"format": FORMAT, "config": config.to_dict()}))
        self.remove_temporaries()

    def remove_temporaries(self) -> None:
        """Temporary files and folders a killed run left (ours: ``.homesim-*``)."""
        for folder in (self.root, self.staging, self.shards):
            for p in folder.glob(f"{TEMP_PREFIX}*"):
                if p.is_dir():
                    shutil.rmtree(p, ignore_errors=True)
                else:
                    p.unlink(missing_ok=True)

    def finished_shards(self) -> list[dict[str, Any]]:
        """The json of every finished shard, in order: from dataset.json when the run is
        complete, else from the shards written so far (a run still going, or stopped)."""
        info = read_json(self.config_path) if self.config_path.exists() else {}
        if info.get("complete"):
            return [read_json(self.shards / f"{Path(s['name']).stem}.json")
                    for s in info["shards"]]
        return [read_json(p) for p in sorted(self.shards.glob("shard-*.json"))]

    def finished_rows(self) -> list[dict[str, Any]]:
        """Manifest rows of the finished shards' episodes (all of them once complete)."""
        return [row for shard in self.finished_shards() for row in shard["rows"]]

    # -- episodes -------------------------------------------------------------------
    def staged_tar(self, key: str) -> Path:
        return self.staging / f"{key}.tar"

    def staged_row(self, key: str) -> dict[str, Any] | None:
        """The row of an episode made and not yet in a shard, or None."""
        path = self.staging / f"{key}.json"
        if not path.exists():
            return None
        row = read_json(path)
        if row["status"] == "ok" and episode_hash(self.staged_tar(row["key"])) != row["sha256"]:
            return None  # its tar is missing or not the one recorded: make it again
        return dict(row)

    def stage_row(self, row: dict[str, Any]) -> None:
        write_text(self.staging / f"{row['key']}.json", dumps(row))

    # -- shards ---------------------------------------------------------------------------
    def shard_info(self, k: int) -> dict[str, Any] | None:
        """The json of shard k when the shard is complete and intact, else None."""
        meta = self.shards / f"{shard_name(k)}.json"
        tar = self.shards / f"{shard_name(k)}.tar"
        if not meta.exists() or not tar.exists():
            return None
        info = read_json(meta)
        return dict(info) if file_sha256(tar) == info["sha256"] else None

    def write_shard(self, k: int, specs: Iterable[EpisodeSpec],
                    rows: dict[str, dict[str, Any]]) -> dict[str, Any]:
        """Join the staged episodes of shard k into its tar, then its json; then drop them."""
        name = shard_name(k)
        tar_path = self.shards / f"{name}.tar"
        keys = [s.key for s in specs]
        with atomic_write(tar_path, "wb") as f:
            out = open_writer(f)
            for key in keys:
                if rows[key]["status"] == "ok":
                    for member, data in iter_members(self.staged_tar(key)):
                        add_member(out, member, data)
            out.close()
        info = {"name": f"{name}.tar", "sha256": file_sha256(tar_path),
                "bytes": tar_path.stat().st_size, "rows": [rows[key] for key in keys]}
        write_text(self.shards / f"{name}.json", dumps(info))
        for key in keys:
            self.staged_tar(key).unlink(missing_ok=True)
            (self.staging / f"{key}.json").unlink(missing_ok=True)
        return info


def episode_hash(path: Path) -> str | None:
    """`MemberHash` of a staged episode tar; None when it is missing or unreadable."""
    if not path.exists():
        return None
    h = MemberHash()
    try:
        for name, data in iter_members(path):
            h.add(name, data)
    except (OSError, EOFError, tarfile.TarError):
        return None
    return h.hexdigest()
