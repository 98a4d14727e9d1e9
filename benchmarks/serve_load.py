"""Small-request latency of ``homesim serve`` while heavy and adversarial clients run.

Starts the real server (``homesim serve``: uvicorn, worker processes) in a subprocess on a
free loopback port, then times small requests (a Check and a Run of "watch TV", 5 steps,
scene1, alternating) one after another in four scenarios:

- alone;
- under 16 clients sending 256 KiB one-line programs back to back;
- under 48 clients asking for renders (320x240 key frames of "watch TV") and fetching
  their frames;
- under 64 slow clients trickling headers or bodies, one byte every 0.5 s.

The load runs in a separate process, so its threads do not slow the timing client. Prints
p50/p99 per scenario and each p99's ratio to the p99 alone; the goal is p99 <= 50 ms in
every scenario. Loopback only; bounded in requests and time; stops by itself.

    nice python benchmarks/serve_load.py [--requests 200] [--warmup 3]
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import socket
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

import httpx

from homesim.examples import DEMO_HOME, load_example

GOAL_MS = 50.0
SRC = Path(__file__).resolve().parents[1] / "src"
LOAD_LIMIT_S = 120.0  # a load process stops by itself after this, whatever happens


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port: int) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    server = subprocess.Popen([sys.executable, "-m", "homesim.cli.main", "serve", "--port",
                               str(port), "--log-level", "error"], env=env,
                              stdout=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            httpx.get(f"http://127.0.0.1:{port}/api/homes", timeout=1)
            return server
        except httpx.TransportError:
            time.sleep(0.2)
    server.kill()
    raise SystemExit("the server did not start within 60 s")


# ------------------------------------------------------------------ load (own process)
def _until(stop, seconds: float = LOAD_LIMIT_S) -> Callable[[], bool]:
    end = time.monotonic() + seconds
    return lambda: not stop.is_set() and time.monotonic() < end


def _large_client(url: str, running: Callable[[], bool], counts: dict) -> None:
    program = "[Walk] <tv> (1) " * (250 * 1024 // 16)  # one line, about 250 KiB
    with httpx.Client(base_url=url, timeout=60) as client:
        while running():
            r = client.post("/api/validate", json={"program": program, "home": DEMO_HOME})
            counts[r.status_code] = counts.get(r.status_code, 0) + 1
            if r.status_code == 503:
                time.sleep(0.1)


def _render_client(url: str, running: Callable[[], bool], counts: dict) -> None:
    body = {"program": str(load_example("watch_tv")), "home": DEMO_HOME}
    with httpx.Client(base_url=url, timeout=60) as client:
        while running():
            r = client.post("/api/render", json=body)
            counts[r.status_code] = counts.get(r.status_code, 0) + 1
            if r.status_code != 202:
                time.sleep(0.5)
                continue
            job = r.json()
            shown = 0
            while running() and job["status"] in ("queued", "running"):
                time.sleep(0.3)
                job = client.get(job["url"]).json()
                for frame in job["frames"][shown:]:
                    client.get(frame["url"])
                shown = len(job["frames"])


def _slow_client(url: str, running: Callable[[], bool], counts: dict, body: bool) -> None:
    port = int(url.rsplit(":", 1)[1])
    start = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\ncontent-length: 100000\r\n\r\n{"
             if body else b"GET /api/homes HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
    while running():
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=5) as sock:
                sock.sendall(start)
                counts["connections"] = counts.get("connections", 0) + 1
                while running():
                    time.sleep(0.5)
                    sock.sendall(b"a")
        except OSError:  # the server cut us off: come back
            counts["cut off"] = counts.get("cut off", 0) + 1


def run_load(kind: str, url: str, clients: int, stop, ready, report) -> None:
    """Start `clients` threads of one kind; report what they got when told to stop."""
    running = _until(stop)
    counts: dict = {}
    targets = {"large": lambda i: _large_client(url, running, counts),
               "render": lambda i: _render_client(url, running, counts),
               "slow": lambda i: _slow_client(url, running, counts, body=bool(i % 2))}
    threads = [threading.Thread(target=targets[kind], args=(i,), daemon=True)
               for i in range(clients)]
    for t in threads:
        t.start()
    ready.set()
    stop.wait(LOAD_LIMIT_S)
    for t in threads:
        t.join(timeout=10)
    report.put(counts)


# ------------------------------------------------------------------ timing
def time_small(url: str, n: int) -> list[float]:
    text = str(load_example("watch_tv"))
    requests = [("/api/validate", {"program": text, "home": DEMO_HOME}),
                ("/api/execute", {"program": text, "home": DEMO_HOME})]
    out = []
    with httpx.Client(base_url=url, timeout=60) as client:
        for i in range(n):
            path, body = requests[i % 2]
            t0 = time.perf_counter()
            r = client.post(path, json=body)
            out.append((time.perf_counter() - t0) * 1000)
            assert r.status_code == 200, r.text
    return out


def percentile(values: list[float], q: float) -> float:
    return statistics.quantiles(values, n=100, method="inclusive")[q - 1] if len(values) > 1 \
        else values[0]


def scenario(url: str, kind: str | None, clients: int, n: int, warmup: float) -> tuple:
    if kind is None:
        return time_small(url, n), {}
    ctx = multiprocessing.get_context("spawn")
    stop, ready, report = ctx.Event(), ctx.Event(), ctx.Queue()
    load = ctx.Process(target=run_load, args=(kind, url, clients, stop, ready, report),
                       daemon=True)
    load.start()
    ready.wait(60)
    time.sleep(warmup)  # let the load reach its steady state
    try:
        times = time_small(url, n)
    finally:
        stop.set()
        counts = report.get(timeout=60)
        load.join(timeout=30)
        if load.is_alive():
            load.kill()
    return times, counts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=200, help="small requests timed")
    parser.add_argument("--warmup", type=float, default=3.0, help="seconds of load first")
    args = parser.parse_args()
    port = free_port()
    server = start_server(port)
    url = f"http://127.0.0.1:{port}"
    try:
        # Warm up: the server's start-up thread imports the renderer and starts the fork
        # server of its workers (seconds of CPU); then load the home and fill caches.
        time.sleep(2 * args.warmup)
        time_small(url, 50)
        rows = []
        for name, kind, clients in [("alone", None, 0),
                                    ("16 large programs", "large", 16),
                                    ("48 renders", "render", 48),
                                    ("64 slow clients", "slow", 64)]:
            times, counts = scenario(url, kind, clients, args.requests, args.warmup)
            rows.append((name, percentile(times, 50), percentile(times, 99), max(times),
                         counts))
    finally:
        server.terminate()
        server.wait(timeout=15)
    base = rows[0][2]
    print(f"small requests (Check/Run of watch TV), {args.requests} per scenario, "
          f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f}")
    print(f"{'scenario':<20} {'p50 ms':>7} {'p99 ms':>7} {'max ms':>7} {'p99/alone':>9}  "
          "load answers")
    for name, p50, p99, worst, counts in rows:
        print(f"{name:<20} {p50:7.1f} {p99:7.1f} {worst:7.1f} {p99 / base:9.2f}  "
              f"{dict(sorted(counts.items(), key=str))}")
    met = all(p99 <= GOAL_MS for _, _, p99, _, _ in rows)
    print(f"goal p99 <= {GOAL_MS:g} ms in every scenario: {'met' if met else 'NOT met'}")


if __name__ == "__main__":
    main()
