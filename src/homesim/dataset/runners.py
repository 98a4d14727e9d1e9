"""Where episodes are made: in this process (`serial_outcomes`) or as Ray tasks
(`ray_outcomes`), local by default or on a cluster. Both yield outcomes as episodes finish;
the worker writes the episode's staging files itself, so only small rows travel back.

A local Ray that does not start is tried `RAY_START_ATTEMPTS` times, then the episodes are
made in this process, with one line saying so. A task lost with its worker or node is
submitted again (`TASK_ATTEMPTS`). A local Ray's processes are watched by a
`homesim.processes.Reaper`, so they end with us even when we are killed; Ray's handlers
of SIGINT and SIGTERM are replaced by the ones we had (Ctrl-C and SIGTERM unwind our stack,
without Ray's crash dump)."""

from __future__ import annotations

import signal
import threading
import time
from collections.abc import Callable, Generator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from homesim.dataset.episode import Outcome, write_episode_file
from homesim.dataset.layout import Layout, dumps
from homesim.dataset.spec import DatasetConfig, EpisodeSpec
from homesim.errors import HomesimError
from homesim.files import write_text
from homesim.processes import RASTER_THREADS, Reaper

TASK_MEMORY = 2 * 1024**3
"""Memory (bytes) each episode task declares to Ray: the scheduler runs no more tasks on a
node than its memory allows. Rendering at 640x480 peaks below 1 GiB."""
TASK_GPU = 0.25
"""GPU share per task where the cluster has GPUs (four renderers share one GPU with EGL)."""
OBJECT_STORE_BYTES = 256 * 1024**2
"""Object store of a local Ray (its default takes 30% of the memory)."""
TAIL_PER_SLOT = 4
"""The last ``TAIL_PER_SLOT x slots`` episodes of a run are submitted longest first."""
WORKER_NICENESS = 0
"""Local Ray workers' niceness above the driver's (Ray's own default is 15)."""
MAX_CALLS = 16
"""A Ray worker process is replaced after this many episodes: whatever a renderer leaks
(GL contexts, caches) is given back."""
RAY_START_ATTEMPTS = 3
"""Tries to start a local Ray (at a high load it can time out) before making the
episodes in this process instead."""
RAY_START_PAUSE_S = 2.0
"""Seconds between two tries."""
TASK_ATTEMPTS = 3
"""Submissions of an episode whose worker or node was lost, before the run stops."""

Notice = Callable[[str], None]
"""Called with one line for the user (the CLI prints it)."""


def stage_episode(spec: EpisodeSpec, config: DatasetConfig, root: str) -> Outcome:
    """Make one episode into the staging folder of the data set at `root`: its tar (if it
    worked), then its row; holding ``staging/`` shared meanwhile (`Layout.writing`)."""
    layout = Layout(root)
    with layout.writing():
        outcome = write_episode_file(spec, config, layout.staged_tar(spec.key))
        if not outcome.ok:  # a tar of an earlier try that no longer hashes as recorded
            layout.staged_tar(spec.key).unlink(missing_ok=True)
        write_text(layout.staging / f"{spec.key}.json", dumps(outcome.to_row(spec)))
    return outcome


def serial_outcomes(specs: Sequence[EpisodeSpec], config: DatasetConfig, root: Path
                    ) -> Generator[Outcome, None, None]:
    """Episodes one after another in this process (``--workers 0``)."""
    for spec in specs:
        yield stage_episode(spec, config, str(root))


@dataclass(frozen=True)
class RayOptions:
    workers: int = 2  # local Ray: CPUs it may use (one episode per CPU)
    address: str | None = None  # an existing cluster ("auto", "ray://host:10001")


def ray_outcomes(specs: Sequence[EpisodeSpec], config: DatasetConfig, root: Path,
                 options: RayOptions, notice: Notice | None = None
                 ) -> Generator[Outcome, None, None]:
    """Episodes as Ray tasks (one CPU each, a GPU share with EGL where there are GPUs),
    at most two per worker in flight. A local Ray that does not start: the episodes are
    made in this process (`notice` gets one line saying so)."""
    ray = _import_ray()
    started = not ray.is_initialized()
    reaper = Reaper() if started and not options.address else None
    try:
        if started:
            try:
                _start(ray, options)
            except RayStartFailed as e:
                if options.address:
                    raise HomesimError(str(e)) from None
                (notice or (lambda line: None))(
                    f"{e}; making the episodes in this process instead (as --workers 0)")
                yield from serial_outcomes(specs, config, root)
                return
        with _Signals() as signals:
            try:
                yield from _ray_tasks(ray, specs, config, root)
            except SystemExit:
                signals.raise_caught()  # what our handler raised, before Ray replaced it
                raise
    finally:
        if started:
            ray.shutdown()
        if reaper is not None:
            reaper.close()


def _ray_tasks(ray: Any, specs: Sequence[EpisodeSpec], config: DatasetConfig, root: Path
               ) -> Generator[Outcome, None, None]:
    gpus = float(ray.cluster_resources().get("GPU", 0))
    task = ray.remote(max_calls=MAX_CALLS)(stage_episode).options(
        num_cpus=1, num_gpus=TASK_GPU if gpus > 0 else 0, memory=TASK_MEMORY,
        max_retries=0, runtime_env={"env_vars": task_environment(gpus > 0)})
    slots = max(1, int(ray.cluster_resources().get("CPU", 1))) * 2
    todo = submission_stack(specs, tail=TAIL_PER_SLOT * slots)
    pending: dict[Any, EpisodeSpec] = {}
    tries: dict[int, int] = {}
    folder = str(root.resolve())
    while todo or pending:
        while todo and len(pending) < slots:
            spec = todo.pop()
            tries[spec.index] = tries.get(spec.index, 0) + 1
            pending[task.remote(spec, config, folder)] = spec
        done, _ = ray.wait(list(pending), num_returns=1)
        spec = pending.pop(done[0])
        try:
            yield ray.get(done[0])
        except ray.exceptions.RayError as e:  # the worker or its node was lost
            if tries[spec.index] >= TASK_ATTEMPTS:
                raise HomesimError(f"{spec.key}: its Ray task failed {TASK_ATTEMPTS} times; "
                                   f"the last: {_first_line(e)}") from None
            todo.append(spec)


class _Signals:
    """Notes which of SIGINT and SIGTERM arrived, then calls our handler as before. Ray
    turns an exception raised by a handler while it waits into ``SystemExit(1)``;
    `raise_caught` raises the handler's own again (KeyboardInterrupt, or the CLI's
    exit 143)."""

    def __init__(self) -> None:
        self.caught: int | None = None
        self.handlers: dict[int, Callable[[int, Any], Any]] = {}

    def __enter__(self) -> _Signals:
        for signum, handler in _our_handlers().items():
            if callable(handler):
                self.handlers[signum] = handler
                signal.signal(signum, self._note)
        return self

    def _note(self, signum: int, frame: Any) -> None:
        self.caught = signum
        self.handlers[signum](signum, frame)

    def raise_caught(self) -> None:
        if self.caught is not None:
            self.handlers[self.caught](self.caught, None)

    def __exit__(self, *exc: object) -> None:
        for signum, handler in self.handlers.items():
            signal.signal(signum, handler)


def _first_line(e: BaseException) -> str:
    return (str(e).strip().splitlines() or [type(e).__name__])[0][:300]


class RayStartFailed(Exception):
    """Ray did not start (after `RAY_START_ATTEMPTS` tries, for a local one)."""


def task_environment(gpu: bool) -> dict[str, str]:
    """Environment of an episode task: EGL on GPU nodes; on CPU, OSMesa rasterizing in the
    task's own thread (llvmpipe otherwise adds a thread per core), so a task uses the one
    CPU it declares and N workers do N times the work of one."""
    return ({"MUJOCO_GL": "egl"} if gpu
            else {"MUJOCO_GL": "osmesa", "LP_NUM_THREADS": RASTER_THREADS})


def submission_stack(specs: Sequence[EpisodeSpec], tail: int) -> list[EpisodeSpec]:
    """The episodes in submission order from the end (``pop()`` takes the next): in index
    order, so shards complete one after another, except the last `tail`, which go longest
    first so that no worker is left alone with a long one at the end (LPT scheduling; an
    episode's length is about its number of steps; ties keep index order)."""
    head, last = list(specs[:max(len(specs) - tail, 0)]), specs[max(len(specs) - tail, 0):]
    ending = sorted(last, key=lambda s: (-program_steps(s.program), s.index))
    return (head + ending)[::-1]


def program_steps(text: str) -> int:
    """Lines of a program's text that are steps (``[Action] ...``)."""
    return sum(1 for line in text.splitlines() if line.lstrip().startswith("["))


def _import_ray():
    try:
        import ray
    except ImportError:
        raise HomesimError("Ray is not installed: pip install 'homesim[dataset]', or run "
                           "with --workers 0") from None
    return ray


def _start(ray: Any, options: RayOptions, attempts: int = RAY_START_ATTEMPTS,
           pause: float = RAY_START_PAUSE_S) -> None:
    """Start (or join) Ray, trying a local one `attempts` times; keep our SIGINT and
    SIGTERM handlers (Ray's own print a crash dump)."""
    if not options.address and options.workers < 1:
        raise HomesimError("--workers must be at least 1 for Ray (0 runs without Ray)")
    handlers = _our_handlers()
    last: Exception | None = None
    try:
        for attempt in range(1, (1 if options.address else attempts) + 1):
            try:
                _init(ray, options)
                return
            except Exception as e:  # Ray raises many kinds; all mean "not up"
                ray.shutdown()  # whatever part of it did start
                last = e
                if attempt < attempts:
                    time.sleep(pause)
        where = options.address or "a local Ray"
        tries = "" if options.address else f" ({attempts} tries)"
        raise RayStartFailed(f"{where} did not start{tries}: "
                             f"{_first_line(last) if last else 'no reason given'}")
    finally:
        for signum, handler in handlers.items():
            signal.signal(signum, handler)


def _our_handlers() -> dict[int, Any]:
    """Python's SIGINT and SIGTERM handlers now (none off the main thread: signals are
    the main thread's)."""
    if threading.current_thread() is not threading.main_thread():
        return {}
    return {s: h for s in (signal.SIGINT, signal.SIGTERM)
            if (h := signal.getsignal(s)) is not None}


def _init(ray: Any, options: RayOptions) -> None:
    if options.address:
        ray.init(address=options.address, log_to_driver=False, configure_logging=False)
        return
    # Tasks return small rows (the episodes go to disk): a small object store will do.
    # Ray starts its workers 15 nicer than the driver; they get the driver's priority
    # instead (what `nice` gave the command), or under any other load they starve.
    ray.init(num_cpus=options.workers, num_gpus=_local_gpus(), include_dashboard=False,
             log_to_driver=False, configure_logging=False,
             object_store_memory=OBJECT_STORE_BYTES,
             _system_config={"worker_niceness": WORKER_NICENESS})


def _local_gpus() -> int:
    """GPUs this machine has (nvidia-smi's count), 0 without."""
    import shutil
    import subprocess

    if shutil.which("nvidia-smi") is None:
        return 0
    try:
        out = subprocess.run(["nvidia-smi", "-L"], capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return 0
    return sum(1 for line in out.stdout.splitlines() if line.startswith("GPU "))
