"""Worker processes, so CPU-heavy work never holds up the event loop or other requests.

Python threads share one interpreter lock: a thread parsing a 256 KiB program slows every
other request. Heavy requests therefore run in the bounded pools of `homesim.serve.pool`
(large programs and generated homes; writing); render jobs (`homesim.serve.renders`) get
one process each.
Processes come from a fork server that has imported homesim once, so starting one costs
milliseconds, and none of them inherits the server's threads.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
from collections.abc import Callable
from multiprocessing.context import ForkServerContext, SpawnContext
from multiprocessing.process import BaseProcess
from typing import Any, Protocol

from homesim.limits import WORKER_MEMORY_BYTES
from homesim.processes import rasterize_in_drawing_thread
from homesim.serve.errors import ApiError, error_body, error_of, json_bytes

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


WORKER_NICE = 19
"""Worker processes run at the lowest priority: on a core the server also wants, a worker
gets about 1.5 % of it (nice 10: about 10 %, which showed in small requests' p99)."""


def lower_priority() -> None:
    """Nice the calling worker process (where allowed), and let OSMesa rasterize in the
    drawing thread rather than in a thread per core beside the server's."""
    rasterize_in_drawing_thread()
    with contextlib.suppress(OSError):
        os.nice(WORKER_NICE)


def limit_memory(memory: int) -> None:
    """Limit the calling worker's data (heap and private mappings: ``RLIMIT_DATA``) to
    `memory` bytes, where the platform allows; past it, allocations raise MemoryError."""
    with contextlib.suppress(ImportError, ValueError, OSError):
        import resource

        resource.setrlimit(resource.RLIMIT_DATA, (memory, memory))


def busy(what: str, retry_after: int = RETRY_AFTER_S) -> ApiError:
    """The 503 answer when a queue is full."""
    return ApiError(503, "busy", f"the server is busy: {what}; retry in {retry_after} s",
                    headers={"Retry-After": str(retry_after)})


def answer_in_worker(handler: Callable[[Any], dict[str, Any]], request: Any
                     ) -> tuple[int, bytes]:
    """Run `handler(request)` and encode its answer, or the error it raises, as JSON."""
    try:
        return 200, json_bytes(handler(request))
    except MemoryError:  # over the worker's RLIMIT_DATA
        return 503, json_bytes(error_body(
            "limit", "the request needed more memory than a worker process may use "
            f"({WORKER_MEMORY_BYTES >> 20} MiB, WORKER_MEMORY_BYTES)",
            limit="WORKER_MEMORY_BYTES"))
    except Exception as e:  # mapped to the same answer the app's handlers give
        status, body = error_of(e)
        return status, json_bytes(body)


