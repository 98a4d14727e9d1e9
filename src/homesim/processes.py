"""Child processes that do not outlive us, even when we are killed with SIGKILL.

A process killed with SIGKILL runs no clean-up: what it started (a local Ray's agents and
workers, a server's fork server and render workers) goes on running, and its temporary
folders stay. `Reaper` starts a small watchdog process in its own session that holds
the read end of a pipe from us. It notes our descendants every `SNAPSHOT_S` seconds;
when the pipe closes without our saying ``done`` (we died, however), it kills the
descendants it noted (each checked by its start time, so a reused process id is never
hit) and removes the paths we gave it. Linux only (it reads ``/proc``); elsewhere it does
nothing.

`rasterize_in_drawing_thread` is for worker processes that draw with OSMesa.
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
from pathlib import Path

RASTER_THREADS = "0"
"""llvmpipe (OSMesa) rasterizer threads besides the drawing one, for a worker process
(``LP_NUM_THREADS``): a worker has one core, where rasterizer threads would only wait on
each other over small frames, or take the core of a server beside it. The pixels are the
same."""


def rasterize_in_drawing_thread() -> None:
    """Set `RASTER_THREADS` for this process unless ``LP_NUM_THREADS`` is set; call it
    before the first draw."""
    os.environ.setdefault("LP_NUM_THREADS", RASTER_THREADS)


SNAPSHOT_S = 0.25
"""How often the watchdog notes our descendants (a process that lived less is missed)."""

_WATCHDOG = r"""
import os, select, shutil, signal, sys, time
parent, every = int(sys.argv[1]), float(sys.argv[2])
me = os.getpid()

def stat(pid):
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        if fields[0] in (b"Z", b"X"):  # dead, not yet reaped
            return None
        return int(fields[1]), int(fields[19])  # ppid, start time
    except (OSError, IndexError, ValueError):
        return None

def descendants():
    children = {}
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) != me:
            s = stat(int(name))
            if s is not None:
                children.setdefault(s[0], []).append((int(name), s[1]))
    found, todo = {}, [parent]
    while todo:
        for pid, start in children.get(todo.pop(), []):
            if pid not in found:
                found[pid] = start
                todo.append(pid)
    return found

noted, paths, buffer = {}, [], b""
while True:
    ready, _, _ = select.select([0], [], [], every)
    if ready:
        data = os.read(0, 4096)
        if not data:
            break
        buffer += data
        *lines, buffer = buffer.split(b"\n")
        for line in lines:
            if line == b"done":
                sys.exit(0)
            paths.append(os.fsdecode(line))
        continue
    if stat(parent) is None:
        break
    noted.update(descendants())
for pid, start in noted.items():
    s = stat(pid)
    if s is not None and s[1] == start:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
for path in paths:
    if os.path.isdir(path) and not os.path.islink(path):
        shutil.rmtree(path, ignore_errors=True)
    else:
        try:
            os.unlink(path)
        except OSError:
            pass
"""


class Reaper:
    """The watchdog of this process's descendants (see the module docstring).

    Use as a context manager, or call `close` when the children were stopped in the
    ordinary way; `remove_on_death` adds a path to delete if we are killed.
    """

    def __init__(self, every: float = SNAPSHOT_S) -> None:
        self._proc: subprocess.Popen[bytes] | None = None
        if not Path("/proc/self/stat").exists():
            return
        self._proc = subprocess.Popen(
            [sys.executable, "-c", _WATCHDOG, str(os.getpid()), str(every)],
            stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            start_new_session=True, close_fds=True)

    def remove_on_death(self, path: str | Path) -> None:
        """Delete `path` (a file or folder) if this process dies without `close`."""
        self._send(os.fsencode(str(path)) + b"\n")

    def close(self) -> None:
        """Stop the watchdog without killing anything."""
        if self._proc is None:
            return
        self._send(b"done\n")
        with contextlib.suppress(OSError):
            assert self._proc.stdin is not None
            self._proc.stdin.close()
        try:
            self._proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()
        self._proc = None

    def _send(self, data: bytes) -> None:
        if self._proc is not None and self._proc.stdin is not None:
            with contextlib.suppress(OSError):
                self._proc.stdin.write(data)
                self._proc.stdin.flush()

    def __enter__(self) -> Reaper:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
