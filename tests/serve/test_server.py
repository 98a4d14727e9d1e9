"""uvicorn settings of ``homesim serve``: slow clients are cut off, stopping is quick."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx

from tests.serve.conftest import start_server
from tests.serve.test_limits import trickle

SRC = Path(__file__).resolve().parents[2] / "src"


def test_headers_trickled_slower_than_their_deadline_are_cut_off(tmp_path):
    from homesim.serve import create_app

    url, server, thread = start_server(app=create_app(static_dir=tmp_path), header_timeout=0.5)
    try:
        answer, seconds = trickle(url, b"GET /api/homes HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
        assert seconds < 3 and answer.startswith(b"HTTP/1.1 408")
        # after an answer, the next request's headers get the deadline too
        with httpx.Client(base_url=url) as client:
            assert client.get("/api/homes").status_code == 200
        answer, seconds = trickle(url, b"GET /api/homes HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"
                                  b"GET /api/homes HTTP/1.1\r\nX-Slow: ")
        assert seconds < 3 and answer.count(b"HTTP/1.1 ") == 2 and b"HTTP/1.1 408" in answer
    finally:
        server.should_exit = True
        thread.join(timeout=10)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_sigterm_stops_the_server_with_slow_clients_open():
    port = _free_port()
    env = {**os.environ, "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    server = subprocess.Popen([sys.executable, "-m", "homesim.cli.main", "serve", "--port",
                               str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True)
    slow = []
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                httpx.get(f"http://127.0.0.1:{port}/api/homes", timeout=1)
                break
            except httpx.TransportError:
                assert time.monotonic() < deadline and server.poll() is None
                time.sleep(0.1)
        for start in (b"GET /api/homes HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ",
                      b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                      b"content-length: 1000\r\n\r\n{", b""):
            sock = socket.create_connection(("127.0.0.1", port))
            sock.sendall(start)
            slow.append(sock)
        time.sleep(1.0)  # the server's start-up thread (imports, fork server) is done by now
        t0 = time.monotonic()
        server.send_signal(signal.SIGTERM)
        _, err = server.communicate(timeout=30)
        # The goal is 5 s (about 2.3 s measured at load average 14); the margin keeps a
        # starved CPU from failing the test, while a server that waits for its slow
        # clients (the bug) never stops at all.
        assert time.monotonic() - t0 <= 10
        assert "Traceback" not in err  # requests cut off by the stop get a 503, not a trace
    finally:
        for sock in slow:
            sock.close()
        if server.poll() is None:
            server.kill()
            server.wait()


def _descendants(pid: int) -> set[int]:
    from tests.dataset.test_ray import _descendants as below

    return below(pid)


def test_a_killed_server_leaves_no_process_and_no_frames(tmp_path):
    """D14: SIGKILL of serve left the fork server, the resource tracker and a render worker
    alive 31 min later, and a homesim-render-* folder in the temporary directory."""
    from homesim.limits import INLINE_PROGRAM_CHARS
    from tests.dataset.test_ray import _wait_gone

    port = _free_port()
    env = {**os.environ, "TMPDIR": str(tmp_path),
           "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    server = subprocess.Popen([sys.executable, "-m", "homesim.cli.main", "serve", "--port",
                               str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                httpx.get(f"http://127.0.0.1:{port}/api/homes", timeout=1)
                break
            except httpx.TransportError:
                assert time.monotonic() < deadline and server.poll() is None
                time.sleep(0.1)
        large = "[Walk] <tv> (1.410)\n" * (INLINE_PROGRAM_CHARS // 20 + 1)
        r = httpx.post(f"http://127.0.0.1:{port}/api/validate", timeout=60,
                       json={"program": large, "home": "scene1"})
        assert r.status_code == 200  # answered by a program worker
        below = _descendants(server.pid)
        assert len(below) >= 3  # the reaper, the fork server, a worker (and more)
        assert [p.name for p in tmp_path.iterdir() if p.name.startswith("homesim-render-")]
        server.kill()
        server.wait()
        assert _wait_gone(below, 10) == set()
        assert [p.name for p in tmp_path.iterdir()] == []
    finally:
        if server.poll() is None:
            server.kill()
            server.wait()


def test_a_render_worker_ends_itself_past_its_time_limit(tmp_path):
    """A render worker outlived its 120 s limit when the server that should stop it was
    gone: the worker now stops itself a little after its limit."""
    import multiprocessing

    from homesim.serve.renders import run_job

    process = multiprocessing.get_context("fork").Process(
        target=run_job, args=(_forever, None, str(tmp_path), 0.5))
    t0 = time.monotonic()
    process.start()
    process.join(timeout=20)
    assert process.exitcode == -signal.SIGALRM and time.monotonic() - t0 < 10


def _forever(request):
    time.sleep(60)
    yield 0, None
