"""`homesim learn`: train description -> program models and print the paper's Table 3."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated

import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)
from rich.table import Table

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.files import check_target, write_text

app = typer.Typer(help="Learn to write programs from descriptions (paper section 5).",
                  no_args_is_help=True)

TASKS = ("text2prog",)


def _datasets(data: str) -> tuple[str, ...]:
    from homesim.learn.table import DATASETS

    if data == "both":
        return DATASETS
    if data not in DATASETS:
        raise HomesimError(f"--data {data}: choose real, synthetic or both")
    return (data,)


def _torch(threads: int) -> None:
    try:
        import numpy  # noqa: F401
        import torch
    except ImportError:
        raise HomesimError("learning needs PyTorch and numpy: install homesim with its "
                           "'learn' extra") from None
    if threads < 1:
        raise HomesimError(f"--threads must be at least 1, got {threads}")
    torch.set_num_threads(threads)  # the thread count changes float sums: keep it fixed
    torch.use_deterministic_algorithms(True)  # refuse ops without a deterministic kernel


def _bar() -> Progress:
    return Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                    TextColumn("{task.fields[value]}"), TimeElapsedColumn(), console=console)


class _Reporter:
    """Progress callback that keeps one bar per stage."""

    def __init__(self, bar: Progress, prefix: str):
        self.bar, self.prefix = bar, prefix
        self.tasks: dict[str, TaskID] = {}

    def __call__(self, stage: str, done: int, total: int, value: float) -> None:
        label = f"{self.prefix} {stage}"
        if label not in self.tasks:
            self.tasks[label] = self.bar.add_task(label, total=total, value="")
        what = "loss" if stage == "MLE" else "reward" if stage.startswith("PG") else "steps"
        self.bar.update(self.tasks[label], completed=done, total=total,
                        value=f"{what} {value:.3f}")


@app.command("train")
def train(
    out: Annotated[Path, typer.Option(help="Run folder; checkpoints go to OUT/<data set>/.")],
    task: Annotated[str, typer.Option(help="What to learn.")] = "text2prog",
    data: Annotated[str, typer.Option(help="real, synthetic or both.")] = "both",
    seed: Annotated[int, typer.Option(help="Seed of splits, synthetic data and training.")] = 0,
    synth_n: Annotated[int, typer.Option(help="Synthetic programs to generate.")] = 5000,
    mle_epochs: Annotated[int | None, typer.Option(
        help="MLE epochs (default: 40 real, 10 synthetic).")] = None,
    pg_epochs: Annotated[int | None, typer.Option(
        help="Policy-gradient epochs per PG model (default: 5 real, 2 synthetic).")] = None,
    batch_size: Annotated[int, typer.Option(help="Examples per batch.")] = 32,
    embeddings: Annotated[str, typer.Option(
        help="Word embeddings: minilm (pretrained), word2vec (trained here) or none.")
    ] = "minilm",
    threads: Annotated[int, typer.Option(help="CPU threads for torch.")] = 1,
    force: Annotated[bool, typer.Option(help="Replace existing checkpoints.")] = False,
) -> None:
    """Train MLE, PG(LCS) and PG(LCS+Sim) seq2seq models; checkpoints keep their config."""
    if task not in TASKS:
        raise HomesimError(f"--task {task}: only {', '.join(TASKS)} is available")
    _torch(threads)
    datasets = _datasets(data)
    from homesim.learn.table import MODELS, RunConfig, train_dataset

    _check_run_folder(out, datasets, tuple(f"{m}.pt" for m in MODELS), force)

    total_start = time.perf_counter()
    for name in datasets:
        config = RunConfig(name, seed, synth_n, mle_epochs, pg_epochs, batch_size,
                           embeddings=embeddings)
        start = time.perf_counter()
        with _bar() as bar:
            paths = train_dataset(config, out / name, _Reporter(bar, name))
        console.print(f"[green]ok[/]: {name}: {', '.join(str(p) for p in paths.values())} "
                      f"in {time.perf_counter() - start:.0f} s")
    console.print(f"trained in {time.perf_counter() - total_start:.0f} s wall time")


def _check_run_folder(out: Path, datasets: tuple[str, ...], files: tuple[str, ...],
                      force: bool) -> None:
    """Fail before training when OUT (or OUT/<data set>) is a file, or holds a checkpoint."""
    for folder in (out, *(out / name for name in datasets)):
        if folder.exists() and not folder.is_dir():
            raise HomesimError(f"{folder}: not a folder; --out names the run folder")
    for name in datasets:
        for file in files:
            if (out / name / file).exists() and not force:
                raise HomesimError(f"{out / name / file}: already exists; pass --force to "
                                   "replace the checkpoints")


@app.command("eval")
def evaluate(
    runs: Annotated[Path, typer.Option(help="Run folder written by 'homesim learn train'.")],
    data: Annotated[str, typer.Option(help="real, synthetic or both.")] = "both",
    markdown: Annotated[Path | None, typer.Option(help="Also write the tables here.")] = None,
    force: Annotated[bool, typer.Option(help="Replace the markdown file if it exists.")] = False,
    threads: Annotated[int, typer.Option(help="CPU threads for torch.")] = 1,
) -> None:
    """Score every row of Table 3 on the test splits and print it.

    With --data both, a data set with no checkpoints in RUNS/<data set> is left out with
    a note; the others are scored.
    """
    _torch(threads)
    datasets = _datasets(data)
    if markdown is not None:
        check_target(markdown, force)
    from homesim.learn.report import markdown_table
    from homesim.learn.table import evaluate_dataset, trained, write_json

    if data == "both":
        present = tuple(name for name in datasets if trained(runs / name))
        for name in datasets:
            if name not in present:
                console.print(f"[yellow]skipped[/] {name}: nothing trained in {runs / name}")
        datasets = present or datasets  # none trained: evaluate_dataset names what is missing

    results = []
    start = time.perf_counter()
    for name in datasets:
        with _bar() as bar:
            result = evaluate_dataset(runs / name, _Reporter(bar, "scoring rows"))
        write_json(result, runs / name / "results.json")
        results.append(result)
        console.print(_rich_table(result))
    seconds = time.perf_counter() - start
    console.print(f"evaluated in {seconds:.0f} s wall time")
    if markdown is not None:
        write_text(markdown, markdown_table(results, eval_seconds=seconds, machine=_machine()),
                   force=force)
        console.print(f"[green]ok[/]: wrote {markdown}")


def _machine() -> str:
    import os
    import platform

    import torch

    return (f"{platform.machine()} CPU, {os.cpu_count()} cores, torch {torch.__version__} "
            f"with {torch.get_num_threads()} thread(s), no GPU")


def _rich_table(result: dict) -> Table:
    table = Table(title=f"Table 3 — {result['dataset']} (test, n={result['n_test']})")
    for col in ("Method", "Action", "Objects", "Steps", "Mean", "Simulator %"):
        table.add_column(col, justify="left" if col == "Method" else "right")
    for row, s in result["rows"].items():
        table.add_row(row, f"{s['action']:.3f}", f"{s['objects']:.3f}", f"{s['steps']:.3f}",
                      f"{s['mean']:.3f}", f"{s['simulator']:.1f}")
    return table
