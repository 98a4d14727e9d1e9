"""Editor API latency: one "Run" of the editor against calling the library directly.

All three run in this one invocation on the demo program (watch TV, 5 steps, scene1):

- library: ``parse_program`` + ``run_program(trace=True)`` + its JSON view (``to_dict``);
- in-process: ``POST /api/execute`` through FastAPI's TestClient (no sockets);
- HTTP: ``POST /api/execute`` to uvicorn on loopback with a keep-alive httpx client.

It prints median and 95th-percentile milliseconds and the ratio of each to the library
call; the goal is an interactive Run: HTTP median under 50 ms. Also the first (loads the home) and
the cached ``GET /api/homes/scene1/objects``.

    python benchmarks/serve.py [--requests 300]
"""

from __future__ import annotations

import argparse
import statistics
import threading
import time

import httpx
import uvicorn
from fastapi.testclient import TestClient

from homesim.examples import DEMO_HOME, load_example
from homesim.ground import run_program
from homesim.program import parse_program
from homesim.serve import create_app
from homesim.serve.results import step_lines
from homesim.world import load_home

GOAL_MS = 50.0


def timings(call, n: int) -> list[float]:
    call()  # warm up (loads and caches the home)
    out = []
    for _ in range(n):
        t0 = time.perf_counter()
        call()
        out.append((time.perf_counter() - t0) * 1000)
    return out


def start_uvicorn(app) -> tuple[str, uvicorn.Server, threading.Thread]:
    config = uvicorn.Config(app, host="127.0.0.1", port=0, log_level="warning")
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    while not server.started:
        time.sleep(0.02)
    port = server.servers[0].sockets[0].getsockname()[1]
    return f"http://127.0.0.1:{port}", server, thread


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=300)
    args = parser.parse_args()
    text = str(load_example("watch_tv"))
    body = {"program": text, "home": DEMO_HOME}

    def library() -> None:
        program = parse_program(text)
        run_program(program, graph, trace=True).to_dict(step_lines(text))

    app = create_app()
    client = TestClient(app, base_url="http://127.0.0.1")  # a loopback Host
    t0 = time.perf_counter()
    first = client.get(f"/api/homes/{DEMO_HOME}/objects")
    first_ms = (time.perf_counter() - t0) * 1000
    assert first.status_code == 200
    cached = timings(lambda: client.get(f"/api/homes/{DEMO_HOME}/objects"), 50)
    graph = load_home(DEMO_HOME)  # cached by now: the first request above loaded it

    def in_process() -> None:
        assert client.post("/api/execute", json=body).json()["executable"]

    url, server, thread = start_uvicorn(app)
    rows = []
    with httpx.Client(base_url=url) as http:
        def over_http() -> None:
            assert http.post("/api/execute", json=body).json()["executable"]

        for name, call in (("library", library), ("in-process", in_process),
                           ("HTTP (uvicorn)", over_http)):
            rows.append((name, timings(call, args.requests)))
    server.should_exit = True
    thread.join(timeout=10)

    base = statistics.median(rows[0][1])
    print(f"{'POST /api/execute (watch TV)':<30} {'median ms':>10} {'p95 ms':>8} {'ratio':>7}")
    for name, ms in rows:
        p95 = statistics.quantiles(ms, n=20)[-1]
        med = statistics.median(ms)
        print(f"{name:<30} {med:>10.2f} {p95:>8.2f} {med / base:>6.1f}x")
    http_median = statistics.median(rows[-1][1])
    verdict = "meets" if http_median < GOAL_MS else "MISSES"
    print(f"\nHTTP median {http_median:.2f} ms: {verdict} the {GOAL_MS:.0f} ms goal")
    print(f"GET /api/homes/{DEMO_HOME}/objects: first {first_ms:.1f} ms, "
          f"cached median {statistics.median(cached):.2f} ms")


if __name__ == "__main__":
    main()
