"""Small-request latency of ``homesim serve`` at 16 concurrency, alone and beside each
adversary.

Starts the real server (``homesim serve``: uvicorn, worker pools) in a subprocess on a free
loopback port. A timing process keeps 16 keep-alive connections busy with small requests
(a Check and a Run of "watch TV", 5 steps, scene1, alternating; a light asyncio client, so
the client's own CPU stays small) and times each. Scenarios:

- alone;
- slow clients: 64 clients trickling headers or bodies, one byte every 0.5 s;
- big bodies: 16 clients sending 256 KiB one-line programs back to back;
- renders: 48 clients asking for renders (320x240 key frames of "watch TV") and fetching
  their frames;
- 40 writes: 40 clients asking ``POST /api/write`` back to back (the writer's model must
  be fitted: ``homesim learn fit-writer``; the table says how many were written);
- 4 gen-N clients: 4 clients each listing the objects of, and running "watch TV" in, a new
  generated home (``gen-SEED``, seeds counting up) back to back.

Each load runs in its own process. Prints p50/p99/max per scenario and each p99's ratio to
the p99 alone; the goal is p99 <= 50 ms in every scenario. Loopback only; bounded in
requests and time; stops by itself. Time it on a quiet machine and say the load.

    nice python benchmarks/serve_load.py [--requests 50] [--warmup 3]
"""

from __future__ import annotations

import argparse
import asyncio
import json
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
CONCURRENCY = 16
SRC = Path(__file__).resolve().parents[1] / "src"
LOAD_LIMIT_S = 180.0  # a load process stops by itself after this, whatever happens


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


_COUNTING = threading.Lock()


def _count(counts: dict, key: object) -> None:
    with _COUNTING:
        counts[key] = counts.get(key, 0) + 1


def _large_client(url: str, running: Callable[[], bool], counts: dict, i: int) -> None:
    program = "[Walk] <tv> (1) " * (250 * 1024 // 16)  # one line, about 250 KiB
    with httpx.Client(base_url=url, timeout=60) as client:
        while running():
            r = client.post("/api/validate", json={"program": program, "home": DEMO_HOME})
            _count(counts, r.status_code)
            if r.status_code == 503:
                time.sleep(0.1)


def _render_client(url: str, running: Callable[[], bool], counts: dict, i: int) -> None:
    body = {"program": str(load_example("watch_tv")), "home": DEMO_HOME}
    with httpx.Client(base_url=url, timeout=60) as client:
        while running():
            r = client.post("/api/render", json=body)
            _count(counts, r.status_code)
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


def _slow_client(url: str, running: Callable[[], bool], counts: dict, i: int) -> None:
    port = int(url.rsplit(":", 1)[1])
    start = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\ncontent-length: 100000\r\n\r\n{"
             if i % 2 else b"GET /api/homes HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
    while running():
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=5) as sock:
                sock.sendall(start)
                _count(counts, "connections")
                while running():
                    time.sleep(0.5)
                    sock.sendall(b"a")
        except OSError:  # the server cut us off: come back
            _count(counts, "cut off")


def _write_client(url: str, running: Callable[[], bool], counts: dict, i: int) -> None:
    body = {"title": "Watch TV", "description": "Turn on the TV and watch it from the sofa."}
    with httpx.Client(base_url=url, timeout=120) as client:
        while running():
            r = client.post("/api/write", json=body)
            _count(counts, r.status_code if r.status_code != 200 else "written")
            if r.status_code == 503:
                time.sleep(0.2)


def _generated_client(url: str, running: Callable[[], bool], counts: dict, i: int) -> None:
    program = str(load_example("watch_tv"))
    seed = 1000 + 1000 * i
    with httpx.Client(base_url=url, timeout=60) as client:
        while running():
            home = f"gen-{seed}"
            seed += 1
            r = client.get(f"/api/homes/{home}/objects")
            _count(counts, r.status_code)
            r = client.post("/api/execute", json={"program": program, "home": home,
                                                  "ground": True})
            _count(counts, r.status_code)
            if r.status_code == 503:
                time.sleep(0.1)


LOADS = {"large": _large_client, "render": _render_client, "slow": _slow_client,
         "write": _write_client, "generated": _generated_client}


def run_load(kind: str, url: str, clients: int, stop, ready, report) -> None:
    """Start `clients` threads of one kind; report what they got when told to stop."""
    running = _until(stop)
    counts: dict = {}
    threads = [threading.Thread(target=LOADS[kind], args=(url, running, counts, i),
                                daemon=True) for i in range(clients)]
    for t in threads:
        t.start()
    ready.set()
    stop.wait(LOAD_LIMIT_S)
    deadline = time.monotonic() + 10  # all threads together: the parent waits 30 s, then
    for t in threads:  # kills this process (whose queue's semaphore would then leak)
        t.join(timeout=max(0.0, deadline - time.monotonic()))
    with _COUNTING:  # threads still out may count on
        report.put(dict(counts))


# ------------------------------------------------------------------ timing
def _requests() -> list[bytes]:
    text = str(load_example("watch_tv"))
    out = []
    for path, body in (("/api/validate", {"program": text, "home": DEMO_HOME}),
                       ("/api/execute", {"program": text, "home": DEMO_HOME})):
        data = json.dumps(body).encode()
        out.append(f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1\r\ncontent-type: application/"
                   f"json\r\ncontent-length: {len(data)}\r\n\r\n".encode() + data)
    return out


async def _connection(port: int, n: int, offset: int, times: list[float]) -> None:
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    requests = _requests()
    try:
        for i in range(n):
            t0 = time.perf_counter()
            writer.write(requests[(i + offset) % 2])
            head = await reader.readuntil(b"\r\n\r\n")
            length = next(int(line.split(b":")[1]) for line in head.split(b"\r\n")
                          if line.lower().startswith(b"content-length:"))
            await reader.readexactly(length)
            times.append((time.perf_counter() - t0) * 1000)
            if not head.startswith(b"HTTP/1.1 200"):
                raise SystemExit(f"a small request failed: {head[:80]!r}")
    finally:
        writer.close()


def time_small(port: int, n: int) -> list[float]:
    """`n` small requests on each of `CONCURRENCY` connections at once; milliseconds."""
    times: list[float] = []

    async def all_of_them() -> None:
        await asyncio.gather(*(_connection(port, n, c, times) for c in range(CONCURRENCY)))

    asyncio.run(all_of_them())
    return times


def percentile(values: list[float], q: int) -> float:
    return statistics.quantiles(values, n=100, method="inclusive")[q - 1] if len(values) > 1 \
        else values[0]


def scenario(url: str, kind: str | None, clients: int, n: int, warmup: float) -> tuple:
    port = int(url.rsplit(":", 1)[1])
    if kind is None:
        return time_small(port, n), {}
    ctx = multiprocessing.get_context("spawn")
    stop, ready, report = ctx.Event(), ctx.Event(), ctx.Queue()
    load = ctx.Process(target=run_load, args=(kind, url, clients, stop, ready, report),
                       daemon=True)
    load.start()
    ready.wait(60)
    time.sleep(warmup)  # let the load reach its steady state
    try:
        times = time_small(port, n)
    finally:
        stop.set()
        counts = report.get(timeout=120)
        load.join(timeout=30)
        if load.is_alive():
            load.kill()
    return times, counts


SCENARIOS = [("alone", None, 0), ("64 slow clients", "slow", 64),
             ("16 big bodies", "large", 16), ("48 renders", "render", 48),
             ("40 writes", "write", 40), ("4 gen-N clients", "generated", 4)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=50,
                        help=f"small requests timed per connection ({CONCURRENCY} at once)")
    parser.add_argument("--warmup", type=float, default=3.0, help="seconds of load first")
    parser.add_argument("--only", default="", help="comma-separated scenario names to run "
                        "(e.g. 'alone,40 writes'; default: all)")
    args = parser.parse_args()
    chosen = [s for s in SCENARIOS if not args.only or s[0] in args.only.split(",")]
    if not chosen or chosen[0][0] != "alone":
        chosen = [SCENARIOS[0], *chosen]  # ratios are to "alone"
    load_before = os.getloadavg()[0]
    port = free_port()
    server = start_server(port)
    url = f"http://127.0.0.1:{port}"
    try:
        # Warm up: the server's start-up thread imports the renderer and starts the fork
        # server of its workers (seconds of CPU); then load the home and fill caches.
        time.sleep(2 * args.warmup)
        time_small(port, 10)
        rows = []
        for name, kind, clients in chosen:
            times, counts = scenario(url, kind, clients, args.requests, args.warmup)
            rows.append((name, percentile(times, 50), percentile(times, 99), max(times),
                         counts))
    finally:
        server.terminate()
        server.wait(timeout=15)
    base = rows[0][2]
    print(f"small requests (Check/Run of watch TV), {CONCURRENCY} at once, "
          f"{args.requests * CONCURRENCY} per scenario; {os.cpu_count()} CPUs, load average "
          f"{load_before:.1f} before, {os.getloadavg()[0]:.1f} after")
    print(f"{'scenario':<18} {'p50 ms':>7} {'p99 ms':>7} {'max ms':>7} {'p99/alone':>9}  "
          "load answers")
    for name, p50, p99, worst, counts in rows:
        print(f"{name:<18} {p50:7.1f} {p99:7.1f} {worst:7.1f} {p99 / base:9.2f}  "
              f"{dict(sorted(counts.items(), key=str))}")
    met = all(p99 <= GOAL_MS for _, _, p99, _, _ in rows)
    print(f"goal p99 <= {GOAL_MS:g} ms in every scenario: {'met' if met else 'NOT met'}")


if __name__ == "__main__":
    main()
