"""`homesim data fetch` stopped by a signal: pip dies with it and no folder is left."""

import os
import signal
import sys
import time

import pytest

from tests.cli.subprocess_cli import start_cli, wait_for

FAKE_PIP = """
import os, sys, time
dest = sys.argv[sys.argv.index("-d") + 1]
with open(os.path.join(dest, "eai_eval-1.0.5-py3-none-any.whl.part"), "wb") as f:
    f.write(b"x" * 100000)
with open(os.environ["FAKE_PIP_PID"] + ".tmp", "w") as f:
    f.write(str(os.getpid()))
os.replace(os.environ["FAKE_PIP_PID"] + ".tmp", os.environ["FAKE_PIP_PID"])
time.sleep(600)
"""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_interrupted_fetch_kills_pip_and_leaves_nothing(tmp_path, signum):
    data, pid_file, fake = tmp_path / "data", tmp_path / "pip.pid", tmp_path / "fake_pip.py"
    data.mkdir()
    fake.write_text(FAKE_PIP)
    prelude = ("import sys, homesim.knowledge.fetch as f\n"
               f"f.PIP = (sys.executable, {str(fake)!r})")
    proc = start_cli(["data", "fetch", "--force"], prelude=prelude,
                     env={"HOMESIM_DATA": str(data), "FAKE_PIP_PID": str(pid_file)})
    wait_for(pid_file.exists, proc)
    pip = int(pid_file.read_text())
    assert [p.name.startswith(".homesim-fetch-") for p in data.iterdir()] == [True]
    proc.send_signal(signum)
    assert proc.wait(timeout=60) == 128 + signum
    deadline = time.monotonic() + 10
    while _alive(pip) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _alive(pip)
    assert list(data.iterdir()) == []
