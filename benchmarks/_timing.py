"""Timing helper shared by the benchmarks."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any


def best_of(fn: Callable[[], Any], repeat: int,
            clock: Callable[[], float] = time.perf_counter) -> float:
    """Best time of `repeat` calls by `clock`, in seconds. With `time.process_time`, time
    spent waiting for a core on a busy machine does not count, so it is close to a quiet
    machine's wall time for single-threaded work like loading."""
    best = math.inf
    for _ in range(repeat):
        t0 = clock()
        fn()
        best = min(best, clock() - t0)
    return best
