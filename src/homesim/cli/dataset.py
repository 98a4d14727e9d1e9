"""`homesim dataset`: make the activity video data set, replay an episode, verify a folder."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated

import typer
from rich.markup import escape
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    Task,
    TaskID,
    TextColumn,
    TimeRemainingColumn,
)
from rich.text import Text

from homesim.cli.common import console
from homesim.errors import HomesimError

app = typer.Typer(help="The activity video data set: generate, replay, verify.",
                  no_args_is_help=True)


def _split(value: str) -> tuple[str, ...]:
    return tuple(v.strip() for v in value.split(",") if v.strip())


class _Rate(ProgressColumn):
    """Episodes per second over this run (episodes found done are not counted)."""

    def __init__(self, start: float):
        super().__init__()
        self.start = start

    def render(self, task: Task) -> Text:
        made = task.fields.get("made", 0)
        elapsed = time.perf_counter() - self.start
        return Text(f"{made / elapsed:.3f} ep/s" if made and elapsed > 0 else "-- ep/s")


@app.command()
def generate(
    out: Annotated[Path, typer.Option(help="Data set folder (created; resumed if it holds "
                                      "a run with the same options).")],
    programs: Annotated[str, typer.Option(
        help="'synth' (the grammar) or a program file, folder or JSONL data set.")] = "synth",
    n: Annotated[int, typer.Option(help="Episodes (with --plan: of all parts).")] = 200,
    seed: Annotated[int, typer.Option(help="Seed of every random choice.")] = 0,
    profile: Annotated[str, typer.Option(
        help="What episodes keep: 'full' (320x240, 15 fps, every modality) or 'learn' "
             "(64x48, 4 fps, rgb and class: what the video models read); the options "
             "below override it.")] = "full",
    width: Annotated[int | None, typer.Option(help="Image width (even).")] = None,
    height: Annotated[int | None, typer.Option(help="Image height (even).")] = None,
    fps: Annotated[int | None, typer.Option(help="Frames per second.")] = None,
    modalities: Annotated[str | None, typer.Option(
        help="Per-frame images to keep, comma separated (rgb,depth,class,instance,flow).")]
    = None,
    gt_stride: Annotated[int | None, typer.Option(
        help="Keep depth, class, instance and flow every k-th frame.")] = None,
    homes: Annotated[str | None, typer.Option(
        help="Homes to draw from, comma separated: built-in names, gen-N or graph files "
             "(.json, .json.gz); default scene1..5, gen-0..4.")] = None,
    agents: Annotated[str | None, typer.Option(
        help="Agents to draw from, comma separated (default: all four).")] = None,
    plan: Annotated[str | None, typer.Option(
        help="Make a plan's parts (train, val, tests; 'paper' or a plan file) in "
             "OUT/<part>, each with its own homes, agents and share of --n.")] = None,
    shard_size: Annotated[int, typer.Option(help="Episodes per shard.")] = 8,
    workers: Annotated[int, typer.Option(
        help="Local Ray workers (CPUs); 0 runs in this process without Ray.")] = 2,
    ray_address: Annotated[str | None, typer.Option(
        help="Address of a running Ray cluster ('auto', 'ray://head:10001').")] = None,
) -> None:
    """Render N randomised episodes (home, agent, cameras, object placement, start, speed,
    grounding) with all ground truth into WebDataset shards and a Parquet manifest.

    Killed and run again with the same options, it continues and gives the same bytes as
    a run that never stopped. An episode that fails is recorded with its reason."""
    from homesim.dataset import DatasetConfig
    from homesim.dataset.spec import AGENT_NAMES, DEFAULT_HOMES

    if plan is not None and (homes or agents):
        raise HomesimError("--plan gives each part its homes and agents: leave out --homes "
                           "and --agents")
    given = {"width": width, "height": height, "fps": fps, "gt_stride": gt_stride,
             "modalities": None if modalities is None else _split(modalities)}
    config = DatasetConfig.from_profile(
        profile, programs=programs, n=n, seed=seed, shard_size=shard_size,
        homes=_split(homes) if homes else DEFAULT_HOMES,
        agents=_split(agents) if agents else AGENT_NAMES,
        **{k: v for k, v in given.items() if v is not None})
    t0 = time.perf_counter()
    if plan is None:
        summaries = {"": _generate_one(config, out, workers, ray_address, t0)}
    else:
        summaries = _generate_plan(plan, config, out, workers, ray_address, t0)
    seconds = time.perf_counter() - t0
    for part, summary in summaries.items():
        console.print(
            f"[green]ok[/]: {summary.ok} episodes ({summary.failed} failed), {summary.frames} "
            f"frames, {summary.disk_bytes / 1e6:.1f} MB ({summary.bytes_per_frame / 1e3:.1f} "
            f"KB per frame) in {summary.shards} shards in {out / part if part else out}")
    console.print(f"{seconds:.0f} s")


def _bar(t0: float) -> Progress:
    return Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                    _Rate(t0), TextColumn("{task.fields[failed]} failed"),
                    TimeRemainingColumn(), console=console)


def _advance(bar: Progress, task: TaskID, done: int, total: int, outcome) -> None:
    fields = bar.tasks[task].fields
    if outcome is not None:
        fields["made"] += 1
        fields["failed"] += 0 if outcome.ok else 1
    bar.update(task, completed=done, total=total)


def _generate_one(config, out: Path, workers: int, ray_address: str | None, t0: float):
    from homesim.dataset import generate_dataset

    with _bar(t0) as bar:
        tasks: list[TaskID] = []  # the bar's row appears with the first progress: a run
        # refused for its options prints no empty bar before the error

        def progress(done: int, total: int, outcome) -> None:
            if not tasks:
                tasks.append(bar.add_task("episodes", total=total, made=0, failed=0))
            _advance(bar, tasks[0], done, total, outcome)

        return generate_dataset(config, out, workers=workers, ray_address=ray_address,
                                progress=progress, notice=lambda line: bar.console.print(
                                    f"note: {escape(line)}"))


def _generate_plan(name: str, config, out: Path, workers: int, ray_address: str | None,
                   t0: float) -> dict:
    from homesim.dataset.generate import generate_plan
    from homesim.dataset.plan import load_plan

    plan = load_plan(name)
    with _bar(t0) as bar:
        tasks: dict[str, TaskID] = {}

        def progress(part: str, done: int, total: int, outcome) -> None:
            if part not in tasks:
                tasks[part] = bar.add_task(part, total=total, made=0, failed=0)
            _advance(bar, tasks[part], done, total, outcome)

        return generate_plan(plan, config.n, out, config, seed=config.seed, workers=workers,
                             ray_address=ray_address, progress=progress)


@app.command()
def replay(
    root: Annotated[Path, typer.Argument(help="Data set folder.")],
    key: Annotated[str, typer.Argument(help="Episode key (ep-000042) or index.")],
    out: Annotated[Path, typer.Option(help="Tar file to write the episode to.")],
    force: Annotated[bool, typer.Option(help="Replace --out if it exists.")] = False,
) -> None:
    """Render one episode again from its recorded choices and say whether its bytes equal
    the stored ones. OUT is written only when the episode is made."""
    from homesim.dataset.replay import replay_from_dataset
    from homesim.dataset.spec import FORMAT

    outcome, recorded = replay_from_dataset(root, key, out, force)
    expected = recorded.sha256
    if not outcome.ok:
        raise HomesimError(f"{outcome.key}: failed again ({outcome.stage}: {outcome.reason})")
    same = "identical to" if outcome.sha256 == expected else "DIFFERENT from"
    console.print(f"[green]ok[/]: {outcome.key}, {outcome.num_frames} frames in {out}; "
                  f"members {same} the data set's")
    if outcome.sha256 != expected:
        if recorded.format != FORMAT:
            console.print(f"the data set is in format {recorded.format}; this homesim "
                          f"writes {FORMAT}, whose bytes differ: replay it with the homesim "
                          "that made it")
        raise typer.Exit(1)


@app.command()
def verify(root: Annotated[Path, typer.Argument(help="Data set folder, or a plan folder "
                                                   "(every part is verified).")]) -> None:
    """Check every shard's checksum, every episode's checksum and frame counts, and the
    manifest; each fault found is one line naming the file (and member)."""
    from homesim.dataset.plan import read_plan
    from homesim.dataset.verify import verify_dataset

    plan = read_plan(root)
    folders = [root] if plan is None else [plan.folder(p.name) for p in plan.plan.parts]
    problems = 0
    for folder in folders:
        report = verify_dataset(folder)
        for p in report.problems:
            console.print(f"[red]problem[/]: {escape(p)}")
        problems += len(report.problems)
        if not report.problems:
            console.print(f"[green]ok[/]: {folder}: {report.shards} shards, "
                          f"{report.episodes} episodes ({report.ok} made), {report.frames} "
                          "frames; checksums match")
    if problems:
        raise HomesimError(f"{root}: {problems} problems")


@app.command()
def card(
    root: Annotated[Path, typer.Argument(help="Data set folder, or a plan folder.")],
    out: Annotated[Path, typer.Option(help="Folder for stats.json and the figures.")],
    seed: Annotated[int, typer.Option(help="Seed of the episodes on the contact sheet.")] = 0,
) -> None:
    """Figures of the data set card: counts and Table 1(a) (stats.json), action and object
    histograms, and a contact sheet of 12 random episodes."""
    from homesim.dataset.card import write_card, write_plan_card
    from homesim.dataset.plan import read_plan

    write = write_card if read_plan(root) is None else write_plan_card
    for path in write(root, out, seed):
        console.print(f"wrote {path}")
