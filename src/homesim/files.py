"""Safe file output: nothing the user has is overwritten unasked, nothing half-written stays.

Every writer of homesim goes through `atomic_write` (or `write_text` / `write_bytes`):
the data goes to a temporary file with a unique name (`tempfile.mkstemp`) in the target's
folder, and `os.replace` moves it onto the target only once it is complete. An error or an
interrupt (Ctrl-C, or SIGTERM, which the CLI turns into an exception) removes the temporary
file. So the target is either the old file or the new one, never half of one, and no
``*.part`` leftover can clash with a file of the user's.

`check_target` does the up-front checks (is it a folder? does it exist without --force? is
its folder there?) so a command fails before doing its work, not after.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import IO, Any

from homesim.errors import HomesimError

TEMP_PREFIX = ".homesim-"
"""Prefix of every temporary file and folder homesim makes next to its outputs."""


def check_target(path: str | Path, force: bool = False, option: str = "--force") -> Path:
    """Check that `path` may be written as a file; return it as a `Path`.

    Raises `HomesimError` when it is a folder, when it exists and `force` is false, or when
    its folder does not exist.
    """
    path = Path(path)
    if path.is_dir():
        raise HomesimError(f"{path}: is a folder; give a file name")
    if path.exists() and not force:
        raise HomesimError(f"{path}: already exists; pass {option} to replace it")
    parent = path.parent
    if not parent.is_dir():
        what = "not a folder" if parent.exists() else "no such folder"
        raise HomesimError(f"{parent}: {what}")
    return path


@contextmanager
def atomic_write(path: str | Path, mode: str = "w", *, force: bool = True,
                 encoding: str | None = "utf-8") -> Iterator[IO[Any]]:
    """Open a temporary file to write; on success it replaces `path` in one step.

    `mode` is ``"w"`` (text) or ``"wb"`` (bytes). With ``force=False`` an existing `path`
    raises `HomesimError` before anything is written. On any exception, including
    `KeyboardInterrupt`, the temporary file is removed and `path` is left as it was.
    """
    if mode not in ("w", "wb"):
        raise ValueError(f"mode must be 'w' or 'wb', got {mode!r}")
    path = check_target(path, force)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f"{TEMP_PREFIX}{path.name}.",
                               suffix=".tmp")
    try:
        with os.fdopen(fd, mode, encoding=None if "b" in mode else encoding) as f:
            yield f
        if not force and path.exists():  # appeared while we wrote: still not ours to replace
            raise HomesimError(f"{path}: already exists; pass --force to replace it")
        os.chmod(tmp, _default_mode())
        os.replace(tmp, path)
    except BaseException:
        _remove(tmp)
        raise


def write_text(path: str | Path, text: str, *, force: bool = True) -> Path:
    """Write `text` (UTF-8) to `path` atomically; see `atomic_write`."""
    with atomic_write(path, "w", force=force) as f:
        f.write(text)
    return Path(path)


def write_bytes(path: str | Path, data: bytes, *, force: bool = True) -> Path:
    """Write `data` to `path` atomically; see `atomic_write`."""
    with atomic_write(path, "wb", force=force) as f:
        f.write(data)
    return Path(path)


@contextmanager
def temp_dir(parent: str | Path, label: str = "tmp") -> Iterator[Path]:
    """A fresh folder inside `parent` (``.homesim-<label>-XXXX``), removed on any exit."""
    import shutil

    path = Path(tempfile.mkdtemp(dir=parent, prefix=f"{TEMP_PREFIX}{label}-"))
    try:
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


def _remove(path: str) -> None:
    with suppress(FileNotFoundError):
        os.unlink(path)


def _read_umask() -> int:
    umask = os.umask(0o022)  # read once at import: os.umask can only be read by setting it
    os.umask(umask)
    return umask


_UMASK = _read_umask()


def _default_mode() -> int:
    """0o666 less the umask: what `open()` would have given (mkstemp makes files 0o600)."""
    return 0o666 & ~_UMASK
