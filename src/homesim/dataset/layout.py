"""The folder of a data set, and the resumable steps that fill it.

    DIR/dataset.json            format, config, then (when complete) shards and counts
    DIR/episodes.parquet        the manifest: one row per episode (when complete)
    DIR/shards/shard-NNNNNN.tar WebDataset shard: the episodes NNNNNN*S .. +S-1 that worked
    DIR/shards/shard-NNNNNN.json  its rows and checksum, written after the tar
    DIR/staging/ep-NNNNNN.tar   an episode made but not yet in its shard (staging/ is
                                removed when a run ends with it empty)
    DIR/staging/ep-NNNNNN.json  its row (written after the tar; alone for a failure)

Every file is written atomically (`homesim.files`): a kill leaves a complete file or none
(plus a ``.homesim-*`` temporary, removed on restart). A shard counts as done when its json
exists and the tar's SHA-256 matches it; an episode counts as made when its staging json
exists (and, if it worked, its tar's members hash to the recorded checksum).

Two locks (``flock`` on the folders themselves: no lock files) keep runs apart. The run
holds DIR exclusively: a second run in the same folder is refused. Each episode's writer
holds ``staging/`` shared while it writes; a run starting (or finishing) takes it
exclusively for a moment, so it waits for writers that outlived a killed run (a Ray
worker lives on for seconds after its driver is killed) before it cleans and resumes.
"""

from __future__ import annotations

import fcntl
import json
import os
import re
import shutil
import tarfile
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any

from homesim.dataset.spec import FORMAT, DatasetConfig, EpisodeSpec
from homesim.dataset.tarfiles import MemberHash, add_member, file_sha256, iter_members, open_writer
from homesim.errors import DataError, HomesimError, excerpt
from homesim.files import TEMP_PREFIX, atomic_write, read_text_limited, write_text
from homesim.limits import MAX_DATA_FILE_BYTES

WRITERS_WAIT_S = 120.0
"""Longest a run waits for the episode writers of a stopped run to end."""


def shard_name(k: int) -> str:
    return f"shard-{k:06d}"


def dumps(data: Any) -> str:
    """JSON as every file of a data set writes it (sorted keys: same data, same bytes)."""
    return json.dumps(data, indent=1, sort_keys=True) + "\n"


SHARD_NAME = re.compile(r"shard-[0-9]{6}\.tar")
"""A shard's file name, as `dataset.json` lists it (nothing else is opened)."""


def read_json(path: Path) -> Any:
    """A data set's json file: a regular file (not a link) within `MAX_DATA_FILE_BYTES`;
    `DataError` naming it and why when it cannot be read or parsed."""
    try:
        text = read_text_limited(path, MAX_DATA_FILE_BYTES, "MAX_DATA_FILE_BYTES",
                                 follow_links=False)
        return json.loads(text)
    except HomesimError as e:
        raise DataError(str(e)) from None
    except (ValueError, RecursionError) as e:
        why = "nested too deep" if isinstance(e, RecursionError) else excerpt(str(e))
        raise DataError(f"{path}: not JSON ({why})") from None


def shard_names(info: Any, where: str = "dataset.json") -> list[str]:
    """The shard file names a complete data set's json lists; `DataError` for a list of
    another shape or a name that is not ``shard-NNNNNN.tar`` (never a path)."""
    shards = info.get("shards") if isinstance(info, dict) else None
    if not isinstance(shards, list):
        raise DataError(f"{where}: 'shards' must be a list")
    names = []
    for i, shard in enumerate(shards):
        name = shard.get("name") if isinstance(shard, dict) else None
        if not isinstance(name, str) or not SHARD_NAME.fullmatch(name):
            raise DataError(f"{where}: shards[{i}]: the name must be shard-NNNNNN.tar, got "
                            f"{excerpt(str(name), 60)!r}")
        names.append(name)
    return names


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
        """Create the folder for `config`, or check that it was begun with the same one
        (a folder where nothing was made yet is begun again with `config`); then hold it
        for this run (`close` lets go) and clear what stopped runs left."""
        if self.root.exists() and not self.root.is_dir():
            raise HomesimError(f"{self.root}: not a folder")
        fresh = not self.config_path.exists()
        if not fresh:
            self._check_stored(config)
        elif self.root.exists() and any(self.root.iterdir()):
            raise HomesimError(f"{self.root}: not empty and not a homesim data set")
        self.staging.mkdir(parents=True, exist_ok=True)
        self.shards.mkdir(parents=True, exist_ok=True)
        self._hold()
        try:
            self.wait_for_writers()
            self.remove_temporaries()
            stored = None if fresh else _with_defaults(read_json(self.config_path)["config"])
            if stored != config.to_dict():
                write_text(self.config_path, dumps({"format": FORMAT,
                                                    "config": config.to_dict()}))
        except BaseException:
            self.close()
            raise

    def _check_stored(self, config: DatasetConfig) -> None:
        stored = read_json(self.config_path)
        if not isinstance(stored, dict):
            raise DataError(f"{self.config_path}: not a data set's json (expected an object)")
        if stored.get("format") != FORMAT:
            raise HomesimError(f"{self.root}: holds a data set in format "
                               f"{str(stored.get('format'))[:40]}, not {FORMAT}; use another "
                               "--out folder")
        old = _with_defaults(stored.get("config"))
        if old == config.to_dict() or not self.made_anything():
            return
        old = old if isinstance(old, dict) else {}
        diff = sorted(k for k, v in config.to_dict().items() if old.get(k) != v)
        raise HomesimError(
            f"{self.root}: holds a data set made with other options ({', '.join(diff)}); "
            "use another --out folder, or the same options to resume")

    def made_anything(self) -> bool:
        """Whether a run made an episode or shard here (else its options may change)."""
        return any(p.name.startswith(("ep-", "shard-"))
                   for folder in (self.staging, self.shards) if folder.is_dir()
                   for p in folder.iterdir())

    def _hold(self) -> None:
        fd = os.open(self.root, os.O_RDONLY | os.O_DIRECTORY)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise HomesimError(f"{self.root}: another homesim run is making this data set "
                               "now; wait for it to end or stop it") from None
        self._lock_fd: int | None = fd

    def close(self) -> None:
        """Let go of the folder (`open` held it)."""
        fd, self._lock_fd = getattr(self, "_lock_fd", None), None
        if fd is not None:
            os.close(fd)

    def wait_for_writers(self, timeout: float = WRITERS_WAIT_S) -> None:
        """Wait until no episode writer holds ``staging/`` (see the module docstring)."""
        fd = os.open(self.staging, os.O_RDONLY | os.O_DIRECTORY)
        try:
            deadline = time.monotonic() + timeout
            while True:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    return
                except BlockingIOError:
                    if time.monotonic() > deadline:
                        raise HomesimError(
                            f"{self.staging}: episodes of a stopped run are still being "
                            f"written after {timeout:g} s; stop its workers, then run "
                            "again") from None
                    time.sleep(0.05)
        finally:
            os.close(fd)

    @contextmanager
    def writing(self) -> Iterator[None]:
        """Hold ``staging/`` shared while an episode is written into it."""
        fd = os.open(self.staging, os.O_RDONLY | os.O_DIRECTORY)
        try:
            fcntl.flock(fd, fcntl.LOCK_SH)
            yield
        finally:
            os.close(fd)

    def remove_temporaries(self) -> None:
        """Temporary files and folders stopped runs left (ours: ``.homesim-*``); call it
        when no writer holds ``staging/`` (`wait_for_writers`)."""
        for folder in (self.root, self.staging, self.shards):
            for p in folder.glob(f"{TEMP_PREFIX}*"):
                if p.is_dir() and not p.is_symlink():
                    shutil.rmtree(p, ignore_errors=True)
                else:
                    p.unlink(missing_ok=True)

    def tidy(self) -> None:
        """After a run stopped or finished: wait for its writers, remove their temporaries,
        and the staging folder if it is empty."""
        with suppress(HomesimError, OSError):
            self.wait_for_writers()
            self.remove_temporaries()
            if not any(self.staging.iterdir()):
                self.staging.rmdir()

    def finished_shards(self) -> list[dict[str, Any]]:
        """The json of every finished shard, in order: from dataset.json when the run is
        complete, else from the shards written so far (a run still going, or stopped)."""
        info = read_json(self.config_path) if self.config_path.exists() else {}
        if isinstance(info, dict) and info.get("complete"):
            paths = [self.shards / f"{Path(name).stem}.json" for name in shard_names(info)]
        else:
            paths = sorted(self.shards.glob("shard-*.json"))
        shards = [read_json(p) for p in paths]
        for path, shard in zip(paths, shards, strict=True):
            if not (isinstance(shard, dict) and isinstance(shard.get("rows"), list)):
                raise DataError(f"{path}: expected an object with a list of 'rows'")
        return shards

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
        try:
            row = read_json(path)
        except DataError:
            return None  # not ours to trust: make it again
        if not (isinstance(row, dict) and row.get("key") == key):
            return None
        if row.get("status") == "ok" and episode_hash(self.staged_tar(key)) != row.get(
                "sha256"):
            return None  # its tar is missing or not the one recorded: make it again
        return dict(row)

    def stage_row(self, row: dict[str, Any]) -> None:
        write_text(self.staging / f"{row['key']}.json", dumps(row))

    # -- shards ---------------------------------------------------------------------------
    def shard_info(self, k: int) -> dict[str, Any] | None:
        """The json of shard k when the shard is complete and intact, else None."""
        meta = self.shards / f"{shard_name(k)}.json"
        tar = self.shards / f"{shard_name(k)}.tar"
        if not meta.exists() or not tar.is_file():
            return None
        try:
            info = read_json(meta)
        except DataError:
            return None  # written again from its episodes
        if not isinstance(info, dict) or not isinstance(info.get("rows"), list):
            return None
        return dict(info) if file_sha256(tar) == info.get("sha256") else None

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
