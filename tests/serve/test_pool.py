"""The worker pool of heavy requests: bounded, timed, memory-limited, cancelled when the
client leaves, and never in the way of small requests (D3, D4)."""

from __future__ import annotations

import asyncio
import multiprocessing
import os
import socket
import time

import httpx
import pytest

from homesim.serve import pool as pool_module
from homesim.serve.errors import ApiError
from homesim.serve.pool import PoolLimits, WorkerPool, answer_or_gone

FORK = multiprocessing.get_context("fork")  # workers run this module's functions


def _pool(timeout: float = 10.0, memory: int = 2**40, workers: int = 1, queue: int = 1
          ) -> WorkerPool:
    return WorkerPool(PoolLimits("test", workers, queue, timeout, memory, "TEST_TIMEOUT_S"),
                      context=FORK)


def _data_bytes() -> int:
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmData:"))


def allocate(megabytes: int) -> dict:
    block = bytearray(megabytes * 2**20)
    return {"bytes": len(block)}


def pid(_: object) -> dict:
    return {"pid": os.getpid()}


def _run(coroutine):
    return asyncio.run(coroutine)


def test_a_job_over_its_time_is_stopped_and_the_worker_replaced():
    async def go():
        pool = _pool(timeout=0.5)
        try:
            first = await pool.answer(pid, None)
            t0 = time.monotonic()
            with pytest.raises(ApiError) as e:
                await pool.answer(time.sleep, 30)
            waited = time.monotonic() - t0
            again = await pool.answer(pid, None)
            return first, e.value, waited, again
        finally:
            pool.close()

    first, error, waited, again = _run(go())
    assert error.status == 503 and "longer than 0.5 s" in error.message
    assert error.extra["limit"] == "TEST_TIMEOUT_S" and waited < 5
    assert first.body != again.body  # a new worker


def test_a_job_over_its_memory_fails_with_one_line():
    async def go():
        pool = _pool(memory=_data_bytes() + 256 * 2**20)
        try:
            big = await pool.answer(allocate, 1024)
            small = await pool.answer(allocate, 16)
            return big, small
        finally:
            pool.close()

    big, small = _run(go())
    assert big.status_code == 503 and b"WORKER_MEMORY_BYTES" in big.body
    assert small.status_code == 200


def test_a_client_that_leaves_has_its_job_stopped():
    async def go():
        pool = _pool()
        try:
            first = await pool.answer(pid, None)
            worker = int(first.body.decode().split(":")[1].strip(" }"))
            left_at = time.monotonic() + 0.3

            async def gone() -> bool:
                return time.monotonic() > left_at

            t0 = time.monotonic()
            answer = await answer_or_gone(pool, time.sleep, 30, gone)
            return worker, answer, time.monotonic() - t0
        finally:
            pool.close()

    worker, answer, waited = _run(go())
    assert answer.status_code == 499 and waited < 5
    time.sleep(0.2)
    assert not os.path.exists(f"/proc/{worker}") or _zombie(worker)


def _zombie(pid: int) -> bool:
    with open(f"/proc/{pid}/stat", "rb") as f:
        return f.read().rsplit(b")", 1)[1].split()[0] == b"Z"


def test_a_full_pool_is_503_with_retry_after():
    async def three_at_once() -> list:
        pool = _pool(workers=1, queue=1)
        try:
            return await asyncio.gather(*(pool.answer(time.sleep, 0.5) for _ in range(3)),
                                        return_exceptions=True)
        finally:
            pool.close()

    answers = _run(three_at_once())
    assert [getattr(a, "status_code", None) for a in answers[:2]] == [200, 200]
    assert isinstance(answers[2], ApiError) and answers[2].status == 503
    assert answers[2].headers["Retry-After"] == "2"


def slow_write(request):
    end = time.monotonic() + 3
    while time.monotonic() < end:  # CPU, as a write is
        pass
    return {"program": "", "home": request.home}


def _raw(port: int, method: str, path: str, body: bytes = b"") -> socket.socket:
    """Send one request on a new connection (read its answer later with `_status`): no
    client threads competing with the server for this process's interpreter."""
    sock = socket.create_connection(("127.0.0.1", port), timeout=60)
    sock.sendall(f"{method} {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nconnection: close\r\n"
                 f"content-type: application/json\r\ncontent-length: {len(body)}\r\n\r\n"
                 .encode() + body)
    return sock


def _status(sock: socket.socket) -> int:
    data = b""
    while b"\r\n" not in data:
        chunk = sock.recv(4096)
        if not chunk:
            break
        data += chunk
    sock.close()
    return int(data.split(b" ", 2)[1])


def test_small_requests_do_not_wait_behind_writes_or_generated_homes(monkeypatch):
    """D3: 40 concurrent writes timed out every route, even GET /api/homes, for 11.5 min
    (each held one of the server's threads); D4: generated homes were made in the server
    process."""
    from homesim.serve import create_app, writer
    from homesim.serve.pool import ProgramPool, WriterPool
    from tests.serve.conftest import start_server

    monkeypatch.setattr(writer, "write", slow_write)
    app = create_app(writer_pool=WriterPool(context=FORK))
    app.state.programs = ProgramPool(context=FORK)
    url, server, thread = start_server(app=app)
    port = int(url.rsplit(":", 1)[1])
    try:
        with httpx.Client(base_url=url, timeout=30) as client:
            time.sleep(2)  # the server's start-up thread imports the renderer meanwhile
            writes = [_raw(port, "POST", "/api/write", b'{"description": "tv"}')
                      for _ in range(40)]
            homes = [_raw(port, "GET", f"/api/homes/gen-{700 + i}/objects") for i in range(4)]
            time.sleep(0.5)
            times = []
            for _ in range(20):
                t0 = time.perf_counter()
                assert client.get("/api/homes").status_code == 200
                times.append(time.perf_counter() - t0)
            codes = [_status(s) for s in writes]
            objects = [_status(s) for s in homes]
    finally:
        server.should_exit = True
        thread.join(timeout=10)
    assert max(times) < 2.0, times  # a write takes 3 s
    assert codes.count(200) >= 1 and codes.count(503) >= 30  # the queue is bounded
    assert set(objects) <= {200, 503} and 200 in objects


def test_a_large_job_is_written_to_its_worker_without_holding_up_the_event_loop():
    """A 1 MiB job does not fit the pipe: written from the event loop, the loop would wait
    for the worker (niced) to read it; a timer due meanwhile must still fire on time."""
    import threading

    ours, theirs = multiprocessing.Pipe(duplex=True)
    got: list[bytes] = []
    reader = threading.Timer(0.5, lambda: got.append(theirs.recv()))  # a slow worker
    reader.start()

    async def main() -> float:
        loop = asyncio.get_running_loop()
        sending = asyncio.ensure_future(pool_module._send(ours, b"x" * 2**20))
        t0 = loop.time()
        await asyncio.sleep(0.05)
        late = loop.time() - t0
        await sending
        return late

    late = _run(main())
    reader.join()
    assert len(got[0]) == 2**20
    assert late < 0.3, f"the event loop was held {late:.2f} s by a job's write"


def test_small_requests_run_one_at_a_time_in_arrival_order():
    """Small requests never share the interpreter lock with each other (run_small)."""
    running, order = [], []

    def handler(i: int) -> dict:
        running.append(i)
        assert len(running) == 1, f"two small requests at once: {running}"
        time.sleep(0.01)
        order.append(i)
        running.remove(i)
        return {"i": i}

    async def main() -> list[dict]:
        jobs = [pool_module.run_small(handler, i) for i in range(8)]
        return await asyncio.gather(*jobs)

    assert [a["i"] for a in _run(main())] == list(range(8))
    assert order == list(range(8))


def test_settling_memory_exempts_what_is_alive_from_later_collections():
    import gc

    keep = [[object()] for _ in range(1000)]
    before = gc.get_freeze_count()
    try:
        pool_module.settle_memory()
        assert gc.get_freeze_count() >= before + len(keep)
    finally:
        gc.unfreeze()


def test_the_server_shortens_the_switch_interval_while_it_runs_and_puts_it_back():
    import sys

    from fastapi.testclient import TestClient

    from homesim.serve.app import SWITCH_INTERVAL_S, create_app

    before = sys.getswitchinterval()
    sys.setswitchinterval(0.005)  # Python's default (another app here may have left its own)
    try:
        with TestClient(create_app(), base_url="http://127.0.0.1"):
            assert sys.getswitchinterval() == SWITCH_INTERVAL_S
        assert sys.getswitchinterval() == 0.005
    finally:
        sys.setswitchinterval(before)
