"""Safe file output: nothing the user has is overwritten unasked, nothing half-written stays.

Every writer of homesim goes through `atomic_write` (or `write_text` / `write_bytes`):
the data goes to a temporary file with a unique name (`tempfile.mkstemp`) in the target's
folder, and `os.replace` moves it onto the target only once it is complete. An error or an
interrupt (Ctrl-C, or SIGTERM, which the CLI turns into an exception) removes the temporary
file. So the target is either the old file or the new one, never half of one, and no
``*.part`` leftover can clash with a file of the user's.

`check_target` does the up-front checks (is it a folder? does it exist without --force? is
its folder there?) so a command fails before doing its work, not after.

A temporary's name carries the id of the process writing it (``.homesim-NAME.pPID.XXXX.tmp``):
what a killed process (SIGKILL gives no chance to clean up) left is removed by the next
write of the same target once that process is gone (`remove_stale`).

Reading goes through `read_limited` too: regular files only (a FIFO or ``/dev/zero`` is
refused at once, never waited on or read without end), with the size checked while
reading, not only from ``stat``.
"""

from __future__ import annotations

import errno
import os
import re
import stat
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import IO, Any, BinaryIO

from homesim.errors import HomesimError, LimitError

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
    remove_stale(path.parent, path.name)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=_temp_prefix(path.name),
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

    remove_stale(parent, label, folder=True)
    path = Path(tempfile.mkdtemp(dir=parent, prefix=_temp_prefix(label, "-")))
    try:
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


def _temp_prefix(name: str, sep: str = ".") -> str:
    return f"{TEMP_PREFIX}{name}{sep}p{os.getpid()}{sep}"


def _stale_pattern(name: str, folder: bool) -> re.Pattern[str]:
    sep = "-" if folder else "."
    tail = r"[^./]+" if folder else r"[^./]+\.tmp"
    return re.compile(re.escape(f"{TEMP_PREFIX}{name}{sep}p") + r"(\d+)" + re.escape(sep)
                      + tail)


def pid_alive(pid: int) -> bool:
    """Whether a process with this id runs on this machine (ours or another user's)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def remove_stale(parent: str | Path, name: str, folder: bool = False) -> list[Path]:
    """Remove the temporaries of target `name` in `parent` whose writing process is gone
    (killed before it could clean up); returns what was removed. `folder`: temporary
    folders of `temp_dir` with that label instead of files."""
    import shutil

    pattern, removed = _stale_pattern(name, folder), []
    try:
        entries = list(os.scandir(parent))
    except OSError:
        return []
    for entry in entries:
        match = pattern.fullmatch(entry.name)
        if match is None or pid_alive(int(match.group(1))):
            continue
        if folder and entry.is_dir(follow_symlinks=False):
            shutil.rmtree(entry.path, ignore_errors=True)
        elif not folder and entry.is_file(follow_symlinks=False):
            _remove(entry.path)
        else:
            continue
        removed.append(Path(entry.path))
    return removed


def open_regular(path: str | Path, what: str = "file", follow_links: bool = True
                 ) -> BinaryIO:
    """`path` opened for reading in binary, when it is a regular file.

    Anything else (a folder, a FIFO, a device such as ``/dev/zero``; a symbolic link
    unless `follow_links`) is refused before a byte is read, and opening does not block
    on a FIFO. Raises `HomesimError` naming the file and why.
    """
    path, label = Path(path), "file" if what == "file" else f"{what} file"
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0)
    if not follow_links:
        flags |= getattr(os, "O_NOFOLLOW", 0)
    try:
        fd = os.open(path, flags)
    except OSError as e:
        if e.errno == errno.ELOOP and not follow_links:
            raise HomesimError(f"{path}: a symbolic link, not a {label}") from None
        raise HomesimError(f"{path}: cannot read {label} ({e.strerror or e})") from None
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        raise HomesimError(f"{path}: not a regular file ({_kind(mode)}); give a {label}")
    return os.fdopen(fd, "rb")


def read_limited(path: str | Path, limit: int, limit_name: str, what: str = "file",
                 follow_links: bool = True) -> bytes:
    """The bytes of the regular file `path` (`open_regular`), refusing one over `limit`
    bytes. The size is counted while reading, so a file that grows or lies about its size
    cannot pass the limit. Raises `LimitError` naming `limit_name`, or `HomesimError`
    naming the file and why.
    """
    label = "file" if what == "file" else f"{what} file"
    chunks, size = [], 0
    with open_regular(path, what, follow_links) as f:
        while size <= limit:
            try:
                chunk = f.read(min(1 << 20, limit + 1 - size))
            except OSError as e:
                raise HomesimError(f"{path}: cannot read {label} ({e.strerror or e})") from None
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    if size > limit:
        raise LimitError(f"{path}: over the limit of {_size(limit)} for a {what} "
                         f"({limit_name})", limit_name)
    return b"".join(chunks)


def read_text_limited(path: str | Path, limit: int, limit_name: str, what: str = "file",
                      follow_links: bool = True) -> str:
    """`read_limited`, decoded as UTF-8 (a leading BOM dropped); one-line error if not."""
    data = read_limited(path, limit, limit_name, what, follow_links)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise HomesimError(f"{path}: not UTF-8 text (byte {e.start})") from None


def _kind(mode: int) -> str:
    kinds = [(stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR,
             "a character device"), (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK,
             "a socket")]
    return next((name for test, name in kinds if test(mode)), "not a file")


def _size(n: int) -> str:
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= scale:
            return f"{n / scale:g} {unit}"
    return f"{n} bytes"


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
