"""Generation on Ray as users meet it: a Ray that does not start, Ctrl-C and SIGTERM, a
SIGKILL followed at once by the same command, and a real two-node cluster losing a node
in the middle of an episode. Each ends with the bytes of the serial run (`tiny_dataset`)
and nothing left behind: no temporaries, no processes."""

from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import pytest

from homesim.dataset import generate_dataset
from homesim.dataset import runners as runners_mod
from tests.cli.subprocess_cli import start_cli, wait_for
from tests.dataset.conftest import tiny_config, tree_hashes

ray = pytest.importorskip("ray")


def _cli_args(out: Path, program_file: Path, workers: int = 2) -> list[str]:
    return ["dataset", "generate", "--out", str(out), "--programs", str(program_file),
            "--n", "3", "--width", "32", "--height", "24", "--fps", "2", "--homes", "scene1",
            "--shard-size", "2", "--workers", str(workers)]


def _descendants(pid: int) -> set[int]:
    """Processes below `pid` (read from /proc)."""
    children: dict[int, list[int]] = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat", "rb") as f:
                    ppid = int(f.read().rsplit(b")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(name))
    found, todo = set(), [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            if child not in found:
                found.add(child)
                todo.append(child)
    return found


def _alive(pids: set[int]) -> set[int]:
    alive = set()
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat", "rb") as f:
                if f.read().rsplit(b")", 1)[1].split()[0] not in (b"Z", b"X"):
                    alive.add(pid)
        except OSError:
            pass
    return alive


def _wait_gone(pids: set[int], seconds: float) -> set[int]:
    deadline = time.monotonic() + seconds
    while _alive(pids) and time.monotonic() < deadline:
        time.sleep(0.2)
    return _alive(pids)


def _temporaries(root: Path) -> list[str]:
    return [p.name for p in root.rglob(".homesim-*")]


# ------------------------------------------------------------------ start-up
def test_a_ray_that_does_not_start_falls_back_to_this_process(
        tiny_dataset, program_file, tmp_path, monkeypatch):
    """Local Ray failed twice at load ~18 ("node timed out during startup", exit 70)."""
    calls = []

    def init(**kwargs):
        calls.append(kwargs)
        raise RuntimeError("node timed out during startup\n(more lines)")

    monkeypatch.setattr(ray, "init", init)
    monkeypatch.setattr(runners_mod, "RAY_START_PAUSE_S", 0.0)
    notes: list[str] = []
    out = tmp_path / "fallback"
    summary = generate_dataset(tiny_config(program_file), out, workers=2, notice=notes.append)
    assert summary.ok == 3 and len(calls) == runners_mod.RAY_START_ATTEMPTS
    assert notes == [f"a local Ray did not start ({runners_mod.RAY_START_ATTEMPTS} tries): "
                     "node timed out during startup; making the episodes in this process "
                     "instead (as --workers 0)"]
    assert tree_hashes(out) == tree_hashes(tiny_dataset)


def test_ray_start_is_tried_again(monkeypatch):
    tries = []

    class FakeRay:
        def init(self, **kwargs):
            tries.append(kwargs)
            if len(tries) < 3:
                raise ConnectionError("GCS did not answer")

        def shutdown(self):
            pass

    runners_mod._start(FakeRay(), runners_mod.RayOptions(workers=1), pause=0.0)
    assert len(tries) == 3


def test_local_workers_run_at_the_drivers_priority():
    """Ray started its workers at nice 15 over the driver's (19 under `nice -n 5`): with
    any other load on the machine generation crawled. They get the driver's now."""
    runners_mod._init(ray, runners_mod.RayOptions(workers=1))
    try:
        assert ray.get(ray.remote(lambda: os.nice(0)).remote()) == os.nice(0)
    finally:
        ray.shutdown()


# ------------------------------------------------------------------ signals
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signalled_ray_run_stops_clean(program_file, tmp_path, signum):
    """SIGINT/SIGTERM left staging/.homesim-ep-*.tmp (20 MB) and printed Ray's
    "*** SIGTERM received ... PC: @" dump."""
    out = tmp_path / "D"
    proc = start_cli(_cli_args(out, program_file, workers=1))
    staging = out / "staging"
    wait_for(lambda: staging.is_dir() and any(p.name.startswith(".homesim-ep-")
                                              for p in staging.iterdir()), proc, 240)
    below = _descendants(proc.pid)
    proc.send_signal(signum)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 128 + signum, err
    assert "received at time" not in err and "PC: @" not in err, err
    assert _temporaries(out) == []
    assert _wait_gone(below, 30) == set()


# ------------------------------------------------------------------ SIGKILL, at once
def test_killed_then_run_again_at_once_gives_the_same_bytes(tiny_dataset, program_file,
                                                            tmp_path):
    """The same command run at once after a SIGKILL met the killed run's Ray workers:
    internal error: FileNotFoundError: ... staging/ep-000000.tar. Ray's agents lived on
    for ~75 s."""
    out = tmp_path / "D"
    proc = start_cli(_cli_args(out, program_file))
    staging = out / "staging"
    wait_for(lambda: staging.is_dir() and any(p.name.endswith(".json")
                                              for p in staging.iterdir()), proc, 240)
    below = _descendants(proc.pid)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    again = start_cli(_cli_args(out, program_file))
    _, err = again.communicate(timeout=600)
    assert again.returncode == 0, err
    assert tree_hashes(out) == tree_hashes(tiny_dataset)
    assert _wait_gone(below, 10) == set()


# ------------------------------------------------------------------ two nodes, one lost
def test_a_two_node_cluster_losing_a_node_mid_episode_gives_the_serial_bytes(
        tiny_dataset, program_file, tmp_path):
    from ray.cluster_utils import Cluster

    cluster = Cluster(initialize_head=True, head_node_args={"num_cpus": 1})
    doomed = cluster.add_node(num_cpus=1)
    cluster.wait_for_nodes()
    out = tmp_path / "D"
    raylet = doomed.all_processes["raylet"][0].process.pid
    killed: list[str] = []
    stop = threading.Event()

    def kill_mid_episode():
        """Once the doomed node writes an episode (a temporary of one of its workers)."""
        while not stop.wait(0.05):
            workers = _descendants(raylet)
            staging = out / "staging"
            writing = [p.name for p in staging.glob(".homesim-ep-*")
                       if any(f".p{pid}." in p.name for pid in workers)]
            if writing:
                cluster.remove_node(doomed, allow_graceful=False)
                killed.extend(writing)
                return

    watcher = threading.Thread(target=kill_mid_episode, daemon=True)
    watcher.start()
    try:
        summary = generate_dataset(tiny_config(program_file), out,
                                   ray_address=cluster.address)
    finally:
        stop.set()
        watcher.join()
        ray.shutdown()
        cluster.shutdown()
    assert killed, "no episode of the second node was seen in the making"
    assert summary.ok == 3
    assert tree_hashes(out) == tree_hashes(tiny_dataset)
    assert _temporaries(out) == []
