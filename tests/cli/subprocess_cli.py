"""Run `homesim` in a child process, to interrupt it for real (SIGINT, SIGTERM)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import homesim

SRC = str(Path(homesim.__file__).resolve().parents[1])
_CHILDREN: list[subprocess.Popen] = []


def start_cli(args: list[str], env: dict[str, str] | None = None,
              prelude: str = "") -> subprocess.Popen:
    """`homesim ARGS` in a child process of this Python, with this checkout's sources;
    `prelude` is Python code run first (e.g. to put a stand-in for pip)."""
    full_env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [SRC, *filter(None, [os.environ.get("PYTHONPATH")])]), **(env or {})}
    code = (f"{_INTERRUPTIBLE}\n{prelude}\nimport sys\nfrom homesim.cli.main import main\n"
            f"sys.exit(main({args!r}))")
    proc = subprocess.Popen([sys.executable, "-c", code], env=full_env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _CHILDREN.append(proc)
    return proc


_INTERRUPTIBLE = "import signal\nsignal.signal(signal.SIGINT, signal.default_int_handler)"
"""The child's first line: Ctrl-C raises KeyboardInterrupt, as in a terminal. A test run
started in the background (``cmd &`` without job control) inherits SIGINT ignored, and
Python then never turns Ctrl-C into KeyboardInterrupt. Set in the child's own code, not
with Popen's ``preexec_fn``: that runs between fork and exec, where a lock held by another
thread of this process at the fork (the renderer's rasterizer threads, a thread pool)
deadlocks the child before exec, and Popen then waits for the exec for ever: a likely
cause of CI stop 49, which hung until its time limit in the render-interrupt tests, after
an in-process render had left such threads."""


def kill_leftover_children() -> None:
    """Kill the children `start_cli` started that still run (a test that failed before
    stopping its child must not leave it working on in the background)."""
    while _CHILDREN:
        proc = _CHILDREN.pop()
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def wait_for(condition: Callable[[], bool], proc: subprocess.Popen,
             timeout: float = 60.0) -> None:
    """Poll `condition` until it holds; fail if the child exits or time runs out first."""
    deadline = time.monotonic() + timeout
    while not condition():
        if proc.poll() is not None:
            _, err = proc.communicate()
            raise AssertionError(f"homesim exited with {proc.returncode} too early: {err}")
        if time.monotonic() > deadline:
            proc.kill()
            raise AssertionError("timed out waiting for homesim")
        time.sleep(0.05)
