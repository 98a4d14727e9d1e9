"""Tar files with fixed headers (mtime 0, uid 0, mode 0644): the same members give the
same bytes, so a shard written twice is identical (WebDataset reads plain tar)."""

from __future__ import annotations

import hashlib
import io
import tarfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO

TAR_FORMAT = tarfile.USTAR_FORMAT


def add_member(tar: tarfile.TarFile, name: str, data: bytes) -> None:
    """Append one file member with fixed metadata."""
    info = tarfile.TarInfo(name)
    info.size = len(data)
    info.mtime = 0
    info.mode = 0o644
    info.uid = info.gid = 0
    info.uname = info.gname = ""
    tar.addfile(info, io.BytesIO(data))


def open_writer(fileobj: IO[bytes]) -> tarfile.TarFile:
    return tarfile.open(fileobj=fileobj, mode="w", format=TAR_FORMAT)


def iter_members(source: str | Path | IO[bytes]) -> Iterator[tuple[str, bytes]]:
    """(name, bytes) of every file member, in order, streaming (no seeks)."""
    if isinstance(source, (str, Path)):
        with open(source, "rb") as f:
            yield from iter_members(f)
        return
    with tarfile.open(fileobj=source, mode="r|") as tar:
        for info in tar:
            if not info.isfile():
                continue
            member = tar.extractfile(info)
            assert member is not None  # a regular file member
            yield info.name, member.read()


class MemberHash:
    """SHA-256 over members (name and content, in order): the checksum of an episode."""

    def __init__(self) -> None:
        self._h = hashlib.sha256()

    def add(self, name: str, data: bytes) -> None:
        self.start(name, len(data))
        self._h.update(data)

    def start(self, name: str, size: int) -> None:
        """Begin a member of `size` bytes (then `update` with its bytes, in pieces)."""
        self._h.update(f"{name}\0{size}\0".encode(errors="surrogateescape"))

    def update(self, data: bytes) -> None:
        self._h.update(data)

    def hexdigest(self) -> str:
        return self._h.hexdigest()


def file_sha256(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()
