"""Worker processes, so CPU-heavy work never holds up the event loop or other requests.

Python threads share one interpreter lock: a thread parsing a 256 KiB program slows every
other request. Large programs therefore run in `ProgramPool`, a small pool of processes
with a bounded queue; render jobs (`homesim.serve.renders`) get one process each.
Processes come from a fork server that has imported homesim once, so starting one costs
milliseconds, and none of them inherits the server's threads.
"""

from __future__ import annotations

import asyncio
import contextlib
import multiprocessing
import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from multiprocessing.context import ForkServerContext, SpawnContext
from multiprocessing.process import BaseProcess
from typing import Any, Protocol

from fastapi.responses import Response

from homesim.limits import PROGRAM_QUEUE, PROGRAM_WORKERS
from homesim.serve.errors import ApiError, error_of, json_bytes

PRELOAD = ["homesim.serve.renders", "homesim.render"]
"""Modules the fork server imports once for all workers (it skips those that fail)."""

RETRY_AFTER_S = 2
"""What a 503 answer's ``Retry-After`` asks a client to wait, in seconds."""


class ProcessContext(Protocol):
    """What starts a worker process: a multiprocessing context (fork server, spawn, fork)."""

    @property
    def Process(self) -> type[BaseProcess]: ...  # multiprocessing's name


def worker_context() -> ForkServerContext | SpawnContext:
    """A fork server when the platform has one (Linux, macOS), else spawn."""
    if "forkserver" in multiprocessing.get_all_start_methods():
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(PRELOAD)
        return context
    return multiprocessing.get_context("spawn")


WORKER_NICE = 10
"""Worker processes run at a lower priority than the server's request handlers."""


def lower_priority() -> None:
    """Nice the calling worker process (where allowed)."""
    with contextlib.suppress(OSError):
        os.nice(WORKER_NICE)


def warm_up() -> None:
    """Start the fork server now (it imports `PRELOAD`, a second or two), not on the
    first request that needs a worker; and look for the renderer (imports mujoco)."""
    from homesim.serve.errors import ApiError
    from homesim.serve.programs import keyframe_renderer

    with contextlib.suppress(ApiError):  # no renderer: POST /api/render answers 501
        keyframe_renderer()
    context = worker_context()
    if context.get_start_method() == "forkserver":
        from multiprocessing import forkserver

        forkserver.ensure_running()


def busy(what: str, retry_after: int = RETRY_AFTER_S) -> ApiError:
    """The 503 answer when a queue is full."""
    return ApiError(503, "busy", f"the server is busy: {what}; retry in {retry_after} s",
                    headers={"Retry-After": str(retry_after)})


def answer_in_worker(handler: Callable[[Any], dict[str, Any]], request: Any
                     ) -> tuple[int, bytes]:
    """Run `handler(request)` and encode its answer, or the error it raises, as JSON."""
    try:
        return 200, json_bytes(handler(request))
    except Exception as e:  # mapped to the same answer the app's handlers give
        status, body = error_of(e)
        return status, json_bytes(body)


class ProgramPool:
    """`workers` processes that answer program requests; at most `queue` more wait."""

    def __init__(self, workers: int = PROGRAM_WORKERS, queue: int = PROGRAM_QUEUE):
        self.workers = workers
        self.queue = queue
        self._pending = 0
        self._executor: ProcessPoolExecutor | None = None

    async def answer(self, handler: Callable[[Any], dict[str, Any]], request: Any) -> Response:
        """`handler(request)` in a worker process, as a JSON response; 503 when full."""
        if self._pending >= self.workers + self.queue:
            raise busy(f"{self._pending} large programs are being checked")
        if self._executor is None:
            self._executor = ProcessPoolExecutor(self.workers, mp_context=worker_context(),
                                                 initializer=lower_priority)
        self._pending += 1
        try:
            future = self._executor.submit(answer_in_worker, handler, request)
            status, body = await asyncio.wrap_future(future)
        except BrokenProcessPool:  # a worker died (killed, out of memory): start afresh
            self.close()
            raise ApiError(500, "internal", "a program worker process stopped while "
                           "answering; please report it") from None
        finally:
            self._pending -= 1
        return Response(body, status_code=status, media_type="application/json")

    def close(self) -> None:
        """Stop the workers now, even one in the middle of a request."""
        if self._executor is not None:
            # shutdown() alone lets a busy worker finish (and outlive a stopping server)
            processes = list((getattr(self._executor, "_processes", None) or {}).values())
            self._executor.shutdown(wait=False, cancel_futures=True)
            for process in processes:
                process.kill()
            self._executor = None
