"""A bounded pool of worker processes for the API's heavy requests.

Heavy work (a large program, a generated home, writing a program) never runs in the
server process: there it would hold the interpreter lock and every small request would
wait behind it. A `WorkerPool` keeps a few long-lived processes (so what they load, a
writer's model or generated homes, stays loaded) and gives each job:

- a place in a bounded queue: `workers` run, `queue` more wait, others get 503 at once;
- a time limit: a job over `timeout` seconds has its worker killed (and replaced), and
  the client gets a one-line error naming the limit;
- a memory limit: each worker runs under ``RLIMIT_DATA`` of `memory` bytes, so a job that
  needs more fails with a one-line error instead of starving the machine;
- cancellation: a client that goes away while its job runs gets its worker killed.

Workers are started from the fork server of `homesim.serve.workers` (cheap to start, no
threads of the server inherited) and niced below the server. A worker reads jobs from its
end of a pipe and exits when the server's end closes (the server stopped or was killed).
"""

from __future__ import annotations

import asyncio
import contextlib
import gc
import multiprocessing.connection
import time
from collections.abc import Awaitable, Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from multiprocessing.reduction import ForkingPickler
from typing import Any

from fastapi.responses import Response

from homesim.limits import (
    PROGRAM_QUEUE,
    PROGRAM_TIMEOUT_S,
    PROGRAM_WORKERS,
    WORKER_MEMORY_BYTES,
    WRITE_QUEUE,
    WRITE_TIMEOUT_S,
    WRITE_WORKERS,
)
from homesim.serve.errors import ApiError, error_body, json_bytes
from homesim.serve.workers import (
    ProcessContext,
    answer_in_worker,
    busy,
    limit_memory,
    lower_priority,
)

DisconnectCheck = Callable[[], Awaitable[bool]]
"""``await check()`` is True once the client has gone."""

_POLL_S = 0.1


@dataclass(frozen=True)
class PoolLimits:
    """What a pool allows: `workers` jobs at a time, `queue` more waiting, each at most
    `timeout` seconds in a worker of at most `memory` bytes; `name` says what the pool
    does and `limit` names the time limit in `homesim.limits` (for messages)."""

    name: str
    workers: int
    queue: int
    timeout: float
    memory: int
    limit: str


def worker_main(conn: multiprocessing.connection.Connection, memory: int) -> None:
    """The body of a pool worker: answer jobs one at a time until the pipe closes."""
    lower_priority()
    limit_memory(memory)
    while True:
        try:
            handler, request = conn.recv()
        except (EOFError, OSError):
            return
        conn.send(answer_in_worker(handler, request))


@dataclass
class _Worker:
    process: Any
    conn: multiprocessing.connection.Connection
    jobs: int = 0

    def alive(self) -> bool:
        return self.process.is_alive()

    def kill(self) -> None:
        with contextlib.suppress(OSError, ValueError):
            self.conn.close()
        if self.process.is_alive():
            self.process.kill()
        self.process.join(timeout=5)


@dataclass
class WorkerPool:
    """Worker processes answering heavy requests within `limits` (module docstring)."""

    limits: PoolLimits
    context: ProcessContext | None = None
    _idle: list[_Worker] = field(default_factory=list)
    _running: int = 0
    _waiting: int = 0
    _free: asyncio.Event | None = None

    async def answer(self, handler: Callable[[Any], dict[str, Any]], request: Any,
                     gone: DisconnectCheck | None = None) -> Response:
        """`handler(request)` in a worker, as a JSON response: 503 when the pool is full,
        an error naming the limit when the job runs too long or needs too much memory."""
        limits = self.limits
        if self._running + self._waiting >= limits.workers + limits.queue:
            raise busy(f"{self._running + self._waiting} {limits.name} jobs are running or "
                       "waiting")
        self._waiting += 1
        try:
            await self._turn(gone)
        finally:
            self._waiting -= 1
        self._running += 1
        try:
            status, body = await self._run(handler, request, gone)
        finally:
            self._running -= 1
            self._wake()
        return Response(body, status_code=status, media_type="application/json")

    async def _turn(self, gone: DisconnectCheck | None) -> None:
        """Wait until fewer than `workers` jobs run (in arrival order, roughly)."""
        while self._running >= self.limits.workers:
            if self._free is None or self._free.is_set():
                self._free = asyncio.Event()
            with contextlib.suppress(asyncio.TimeoutError):
                await asyncio.wait_for(self._free.wait(), _POLL_S * 5)
            if gone is not None and await gone():
                raise _ClientGone

    def _wake(self) -> None:
        if self._free is not None:
            self._free.set()

    def _worker(self) -> _Worker:
        while self._idle:
            worker = self._idle.pop()
            if worker.alive():
                return worker
            worker.kill()
        from homesim.serve.workers import worker_context

        ours, theirs = multiprocessing.Pipe(duplex=True)
        process = (self.context or worker_context()).Process(
            target=worker_main, args=(theirs, self.limits.memory), daemon=True,
            name=f"homesim-{self.limits.name.replace(' ', '-')}")
        process.start()
        theirs.close()
        return _Worker(process, ours)

    async def _run(self, handler: Callable[[Any], dict[str, Any]], request: Any,
                   gone: DisconnectCheck | None) -> tuple[int, bytes]:
        worker = self._worker()
        try:
            await _send(worker.conn, (handler, request))
            answer = await self._wait(worker, gone)
        except BaseException:
            worker.kill()  # cancelled, timed out, client gone, or the worker died
            raise
        worker.jobs += 1
        self._idle.append(worker)
        return answer

    async def _wait(self, worker: _Worker, gone: DisconnectCheck | None
                    ) -> tuple[int, bytes]:
        loop = asyncio.get_running_loop()
        ready = asyncio.Event()
        fd = worker.conn.fileno()
        loop.add_reader(fd, ready.set)
        deadline = time.monotonic() + self.limits.timeout
        try:
            while not ready.is_set():
                left = deadline - time.monotonic()
                if left <= 0:
                    raise self._too_long()
                with contextlib.suppress(asyncio.TimeoutError):
                    await asyncio.wait_for(ready.wait(), min(left, _POLL_S * 5))
                if not ready.is_set() and gone is not None and await gone():
                    raise _ClientGone
        finally:
            loop.remove_reader(fd)
        try:
            status, body = worker.conn.recv()
        except (EOFError, OSError):
            code = worker.process.exitcode
            raise self._died(code) from None
        return status, body

    def _too_long(self) -> ApiError:
        limits = self.limits
        return ApiError(503, "limit", f"the {limits.name} job took longer than "
                        f"{limits.timeout:g} s and was stopped ({limits.limit})",
                        limit=limits.limit)

    def _died(self, code: int | None) -> ApiError:
        limits = self.limits
        why = (f"it needed more than {limits.memory >> 20} MiB of memory" if code in (1, -9)
               else f"exit code {code}")
        return ApiError(503, "worker", f"the {limits.name} worker stopped before answering "
                        f"({why}); retry, or send less")

    def close(self) -> None:
        """Stop every worker now (idle ones; running jobs' workers are killed by their
        requests' cancellation)."""
        while self._idle:
            self._idle.pop().kill()


class _ClientGone(Exception):
    """The client left while its job waited or ran."""


def gone_answer() -> Response:
    """What a request whose client left gets (nobody reads it)."""
    return Response(json_bytes(error_body("gone", "the client went away")), status_code=499,
                    media_type="application/json")


async def answer_or_gone(pool: WorkerPool, handler: Callable[[Any], dict[str, Any]],
                         request: Any, gone: DisconnectCheck | None) -> Response:
    """`pool.answer`, with `gone_answer` when the client left meanwhile."""
    try:
        return await pool.answer(handler, request, gone)
    except _ClientGone:
        return gone_answer()


_SEND_INLINE_BYTES = 16 * 1024
"""Jobs pickled to at most this many bytes are written to a worker from the event loop;
larger ones (a 256 KiB program) from a thread: the pipe holds less than them, and the
event loop would wait for the worker (niced below the server) to read."""


async def _send(conn: multiprocessing.connection.Connection, job: object) -> None:
    data = ForkingPickler.dumps(job)
    if len(data) <= _SEND_INLINE_BYTES:
        conn.send_bytes(data)
    else:
        await asyncio.to_thread(conn.send_bytes, data)


_SMALL_LANE = ThreadPoolExecutor(max_workers=1, thread_name_prefix="homesim-small")
_YIELD_S = 0.0002


def _then_yield(handler: Callable[[Any], dict[str, Any]], request: Any) -> dict[str, Any]:
    try:
        return handler(request)
    finally:
        time.sleep(_YIELD_S)  # the event loop takes the interpreter lock before the next job


async def run_small(handler: Callable[[Any], dict[str, Any]], request: Any) -> dict[str, Any]:
    """`handler(request)` for a small request, in the small-request thread: one at a time,
    in arrival order.

    A small request takes about a millisecond of CPU. Run in many threads at once they
    pass the interpreter lock around and each waits for all: at 16 concurrency on 2 cores
    the p99 was 67 ms in the thread pool against about 20 ms in one thread
    (``benchmarks/serve_load.py``). Between two jobs the thread sleeps a moment so the
    event loop, which reads requests and writes answers, is not starved."""
    return await asyncio.get_running_loop().run_in_executor(_SMALL_LANE, _then_yield, handler,
                                                            request)


def settle_memory() -> None:
    """Collect garbage once, then exempt every object alive now from later collections
    (`gc.freeze`): the server's long-lived objects (modules, knowledge base, loaded homes)
    are not scanned again. A full collection over them took ~60 ms, which showed as
    small-request p99 spikes of 75-90 ms; with them frozen, p99 stays under 50 ms."""
    gc.collect()
    gc.freeze()


class ProgramPool(WorkerPool):
    """The pool of large programs and of requests on generated homes."""

    def __init__(self, workers: int = PROGRAM_WORKERS, queue: int = PROGRAM_QUEUE,
                 timeout: float = PROGRAM_TIMEOUT_S, memory: int = WORKER_MEMORY_BYTES,
                 context: ProcessContext | None = None):
        super().__init__(PoolLimits("program", workers, queue, timeout, memory,
                                    "PROGRAM_TIMEOUT_S"), context)


class WriterPool(WorkerPool):
    """The pool of ``POST /api/write``: its workers keep the writer's model loaded."""

    def __init__(self, workers: int = WRITE_WORKERS, queue: int = WRITE_QUEUE,
                 timeout: float = WRITE_TIMEOUT_S, memory: int = WORKER_MEMORY_BYTES,
                 context: ProcessContext | None = None):
        super().__init__(PoolLimits("write", workers, queue, timeout, memory,
                                    "WRITE_TIMEOUT_S"), context)
