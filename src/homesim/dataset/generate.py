"""`generate_dataset`: make (or resume) a data set; `replay_episode`: one episode again.

Resumable and exact: each episode's choices come from the seed and its index alone, each
file is written atomically, and a restart with the same options skips what is done (shards
whose checksum matches, staged episodes whose members hash as recorded). So a run killed at
any point and restarted, at once or later, gives the same bytes as a run never stopped.

Options, homes and programs are checked before the folder is touched: a mistyped command
leaves nothing that would block the corrected one.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Generator, Sequence
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from homesim.dataset.episode import Outcome, write_episode_file
from homesim.dataset.layout import Layout, dumps, shard_name
from homesim.dataset.manifest import write_manifest
from homesim.dataset.plan import PLAN_FILE, Plan, part_configs, plan_record
from homesim.dataset.runners import Notice, RayOptions, ray_outcomes, serial_outcomes
from homesim.dataset.spec import FORMAT, DatasetConfig, EpisodeSpec, plan_episodes
from homesim.errors import DataError, HomesimError
from homesim.files import write_text

Progress = Callable[[int, int, Outcome | None], None]
"""Called as ``progress(episodes_done, episodes_total, outcome)``; outcome is None for
episodes found done (a resumed run reports those first)."""


@dataclass(frozen=True)
class Summary:
    """What a finished data set holds."""

    root: Path
    episodes: int
    ok: int
    failed: int
    frames: int
    bytes: int  # members of the made episodes
    shards: int
    disk_bytes: int = 0  # the shard files (members plus tar headers and padding)

    @property
    def bytes_per_frame(self) -> float:
        """Shard bytes on disk per frame (what the data set costs)."""
        return self.disk_bytes / self.frames if self.frames else 0.0


def check_homes(homes: Sequence[str]) -> None:
    """Every home loads: a built-in name, ``gen-N`` or a graph file (``.json``,
    ``.json.gz``; the errors of ``homesim run --graph``), before any episode is planned."""
    from homesim.world.homes import open_home

    for home in dict.fromkeys(homes):
        open_home(home)


def load_programs(config: DatasetConfig, count: int | None = None) -> list[tuple[str, str]]:
    """(id, text) of the config's programs: ``synth`` samples `n` (or the first `count`)
    from the grammar with the config's seed, drawing each in one of its homes; else a data
    set file (JSONL), a folder of program files or one program file."""
    if config.programs == "synth":
        from homesim.synth import generate

        return [(p.id, str(p.program))
                for p in generate(count or config.n, config.seed, homes=config.homes)]
    from homesim.knowledge.datasets import ActivityDataset

    source = config.programs
    path = Path(source)
    if path.is_dir():
        ds = ActivityDataset.from_folder(path)
    elif path.suffix == ".jsonl":
        ds = ActivityDataset.from_jsonl(path)
    elif path.exists():  # a file, or something else: read_limited says what
        ds = ActivityDataset.from_file(path)
    else:
        raise HomesimError(f"--programs {source}: no such file or folder (or 'synth')")
    return [(p.id, str(p.program)) for p in ds]


def generate_dataset(config: DatasetConfig, out: str | Path, *, workers: int = 2,
                     ray_address: str | None = None, progress: Progress | None = None,
                     notice: Notice | None = None) -> Summary:
    """Make the data set `config` describes in `out` (resuming what is there).

    ``workers=0`` makes episodes one by one in this process; otherwise each is a Ray task
    (Ray started here with `workers` CPUs, or the cluster at `ray_address`; a local Ray
    that does not start: in this process, and `notice` gets one line saying so)."""
    if workers < 0:
        raise HomesimError(f"--workers must be 0 (no Ray) or more, got {workers}")
    check_homes(config.homes)  # these three before the folder is touched
    specs = plan_episodes(config, load_programs(config))
    layout = Layout(out)
    layout.open(config)
    try:
        job = _Job(layout, config, specs, progress)
        todo = job.resume()
        if workers == 0 and ray_address is None:
            outcomes: Generator[Outcome, None, None] = serial_outcomes(todo, config,
                                                                       layout.root)
        else:
            outcomes = ray_outcomes(todo, config, layout.root,
                                    RayOptions(workers, ray_address), notice)
        with closing(outcomes):  # stops Ray before the tidying below, however we leave
            for outcome in outcomes:
                job.record(outcome)
        return job.finish()
    finally:
        layout.tidy()
        layout.close()


class _Job:
    """The bookkeeping of one run: which episodes and shards are done."""

    def __init__(self, layout: Layout, config: DatasetConfig, specs: list[EpisodeSpec],
                 progress: Progress | None):
        self.layout, self.config, self.specs = layout, config, specs
        self.progress = progress or (lambda done, total, outcome: None)
        self.shards: dict[int, dict[str, Any]] = {}
        self.rows: dict[str, dict[str, Any]] = {}
        self.done = 0

    def shard_specs(self, k: int) -> Sequence[EpisodeSpec]:
        s = self.config.shard_size
        return self.specs[k * s:(k + 1) * s]

    def resume(self) -> list[EpisodeSpec]:
        """Find finished shards and staged episodes; return the episodes still to make."""
        todo = []
        for k in range(self.config.num_shards):
            info = self.layout.shard_info(k)
            if info is not None:
                self.shards[k] = info
                self.done += len(info["rows"])
                continue
            for spec in self.shard_specs(k):
                row = self.layout.staged_row(spec.key)
                if row is None:
                    todo.append(spec)
                else:
                    self.rows[spec.key] = row
                    self.done += 1
            self._maybe_write_shard(k)
        self.progress(self.done, len(self.specs), None)
        return todo

    def record(self, outcome: Outcome) -> None:
        spec = self.specs[outcome.index]
        self.rows[spec.key] = outcome.to_row(spec)
        self.done += 1
        self._maybe_write_shard(outcome.index // self.config.shard_size)
        self.progress(self.done, len(self.specs), outcome)

    def _maybe_write_shard(self, k: int) -> None:
        specs = self.shard_specs(k)
        if k not in self.shards and all(s.key in self.rows for s in specs):
            self.shards[k] = self.layout.write_shard(k, specs, self.rows)

    def finish(self) -> Summary:
        missing = [shard_name(k) for k in range(self.config.num_shards) if k not in self.shards]
        if missing:
            raise DataError(f"{self.layout.root}: shard {missing[0]} was not completed")
        rows = [r for k in sorted(self.shards) for r in self.shards[k]["rows"]]
        write_manifest(rows, self.layout.manifest_path)
        ok = [r for r in rows if r["status"] == "ok"]
        summary = Summary(self.layout.root, len(rows), len(ok), len(rows) - len(ok),
                          sum(r["num_frames"] for r in ok), sum(r["bytes"] for r in ok),
                          len(self.shards), sum(s["bytes"] for s in self.shards.values()))
        shards = [{k: v for k, v in self.shards[k].items() if k != "rows"}
                  for k in sorted(self.shards)]
        write_text(self.layout.config_path, dumps({
            "format": FORMAT, "config": self.config.to_dict(), "complete": True,
            "counts": {"episodes": summary.episodes, "ok": summary.ok,
                       "failed": summary.failed, "frames": summary.frames,
                       "bytes": summary.bytes, "disk_bytes": summary.disk_bytes},
            "shards": shards}))
        return summary


def replay_episode(spec: EpisodeSpec, config: DatasetConfig, path: str | Path) -> Outcome:
    """Render one episode again from its spec into a tar at `path` (same members, same
    bytes as in its shard)."""
    return write_episode_file(spec, config, Path(path))


PlanProgress = Callable[[str, int, int, Any], None]
"""Called as ``progress(part, episodes_done, episodes_total, outcome)`` (as
`homesim.dataset.generate.Progress`, with the part's name first)."""


def generate_plan(plan: Plan, n: int, out: str | Path, base: DatasetConfig, *,
                  seed: int = 0, workers: int = 2, ray_address: str | None = None,
                  progress: PlanProgress | None = None) -> dict[str, Summary]:
    """Make (or resume) every part of `plan` in ``out/<part>``, `n` episodes in all."""
    root = Path(out)
    record = plan_record(plan, n, seed, base)
    path = root / PLAN_FILE
    if path.is_file():
        if json.loads(path.read_text(encoding="utf-8")) != json.loads(dumps(record)):
            raise HomesimError(f"{root}: holds a plan made with other options; use another "
                               "--out folder, or the same options to resume")
    elif root.exists() and any(root.iterdir()):
        raise HomesimError(f"{root}: not empty and not a homesim plan folder")
    check_homes(tuple(h for p in plan.parts for h in p.homes))
    root.mkdir(parents=True, exist_ok=True)
    write_text(path, dumps(record), force=True)
    out_summaries = {}
    for name, config in part_configs(plan, n, seed, base).items():
        def report(done: int, total: int, outcome: Any, name: str = name) -> None:
            if progress:
                progress(name, done, total, outcome)
        out_summaries[name] = generate_dataset(config, root / name, workers=workers,
                                               ray_address=ray_address, progress=report)
    return out_summaries
