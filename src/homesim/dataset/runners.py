"""Where episodes are made: in this process (`serial_outcomes`) or as Ray tasks
(`ray_outcomes`), local by default or on a cluster. Both yield outcomes as episodes finish;
the worker writes the episode's staging files itself, so only small rows travel back."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

from homesim.dataset.episode import Outcome, write_episode_file
from homesim.dataset.layout import Layout, dumps
from homesim.dataset.spec import DatasetConfig, EpisodeSpec
from homesim.errors import HomesimError
from homesim.files import write_text

TASK_MEMORY = 2 * 1024**3
"""Memory (bytes) each episode task declares to Ray: the scheduler runs no more tasks on a
node than its memory allows. Rendering at 640x480 peaks below 1 GiB."""
TASK_GPU = 0.25
"""GPU share per task where the cluster has GPUs (four renderers share one GPU with EGL)."""
OBJECT_STORE_BYTES = 256 * 1024**2
"""Object store of a local Ray (its default takes 30% of the memory)."""
TAIL_PER_SLOT = 4
"""The last ``TAIL_PER_SLOT x slots`` episodes of a run are submitted longest first."""
MAX_CALLS = 16
"""A Ray worker process is replaced after this many episodes: whatever a renderer leaks
(GL contexts, caches) is given back."""


def stage_episode(spec: EpisodeSpec, config: DatasetConfig, root: str) -> Outcome:
    """Make one episode into the staging folder of the data set at `root`: its tar (if it
    worked), then its row."""
    layout = Layout(root)
    outcome = write_episode_file(spec, config, layout.staged_tar(spec.key))
    write_text(layout.staging / f"{spec.key}.json", dumps(outcome.to_row(spec)))
    return outcome


def serial_outcomes(specs: Sequence[EpisodeSpec], config: DatasetConfig, root: Path
                    ) -> Iterator[Outcome]:
    """Episodes one after another in this process (``--workers 0``)."""
    for spec in specs:
        yield stage_episode(spec, config, str(root))


@dataclass(frozen=True)
class RayOptions:
    workers: int = 2  # local Ray: CPUs it may use (one episode per CPU)
    address: str | None = None  # an existing cluster ("auto", "ray://host:10001")


def ray_outcomes(specs: Sequence[EpisodeSpec], config: DatasetConfig, root: Path,
                 options: RayOptions) -> Iterator[Outcome]:
    """Episodes as Ray tasks (one CPU each, a GPU share with EGL where there are GPUs),
    at most two per worker in flight."""
    ray = _import_ray()
    started = not ray.is_initialized()
    if started:
        _init(ray, options)
    try:
        gpus = float(ray.cluster_resources().get("GPU", 0))
        task = ray.remote(max_calls=MAX_CALLS)(stage_episode).options(
            num_cpus=1, num_gpus=TASK_GPU if gpus > 0 else 0, memory=TASK_MEMORY,
            max_retries=1, runtime_env={"env_vars": task_environment(gpus > 0)})
        slots = max(1, int(ray.cluster_resources().get("CPU", 1))) * 2
        todo = submission_stack(specs, tail=TAIL_PER_SLOT * slots)
        pending: list = []
        while todo or pending:
            while todo and len(pending) < slots:
                pending.append(task.remote(todo.pop(), config, str(root.resolve())))
            done, pending = ray.wait(pending, num_returns=1)
            yield ray.get(done[0])
    finally:
        if started:
            ray.shutdown()


def task_environment(gpu: bool) -> dict[str, str]:
    """Environment of an episode task: EGL on GPU nodes; on CPU, OSMesa rasterizing in the
    task's own thread (llvmpipe otherwise adds a thread per core), so a task uses the one
    CPU it declares and N workers do N times the work of one."""
    return {"MUJOCO_GL": "egl"} if gpu else {"MUJOCO_GL": "osmesa", "LP_NUM_THREADS": "0"}


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


def _init(ray, options: RayOptions) -> None:
    if options.address:
        ray.init(address=options.address, log_to_driver=False, configure_logging=False)
        return
    if options.workers < 1:
        raise HomesimError("--workers must be at least 1 for Ray (0 runs without Ray)")
    # Tasks return small rows (the episodes go to disk): a small object store will do.
    ray.init(num_cpus=options.workers, num_gpus=_local_gpus(), include_dashboard=False,
             log_to_driver=False, configure_logging=False,
             object_store_memory=OBJECT_STORE_BYTES)


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
