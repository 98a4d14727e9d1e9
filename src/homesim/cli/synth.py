"""`homesim synth`: write synthetic programs with descriptions as a JSONL data set."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.files import check_target
from homesim.synth import DEFAULT_HOMES, generate, write_jsonl
from homesim.synth.grammar import STYLES
from homesim.world.homes import home_names, is_generated


def synth(
    out: Annotated[Path, typer.Option(help="JSONL file to write.")],
    n: Annotated[int, typer.Option(help="How many programs.")] = 5000,
    seed: Annotated[int, typer.Option(help="Random seed (same seed, same programs).")] = 0,
    home: Annotated[list[str] | None, typer.Option(
        help="Built-in home to use (repeat for several; default: the five apartments).")] = None,
    descriptions: Annotated[str, typer.Option(
        help="Description style: people (a paraphrase grammar) or templates (the fixed "
             "phrases of the earlier learning figures). Same programs either way.")] = "people",
    force: Annotated[bool, typer.Option(help="Replace OUT if it exists.")] = False,
) -> None:
    """Sample programs from the grammar over the 12 animated actions, executable by
    construction in the homes, each with a description (docs/knowledge.md).

    OUT is a JSONL data set (docs/knowledge.md) that every homesim loader reads. It is
    written to a temporary file first and only replaces OUT once complete, so an
    interrupted run leaves nothing behind.
    """
    if n < 1:
        raise HomesimError(f"--n must be at least 1, got {n}")
    if descriptions not in STYLES:
        raise HomesimError(f"--descriptions {descriptions}: choose {' or '.join(STYLES)}")
    check_target(out, force)  # before the work, not after it
    homes = tuple(home) if home else DEFAULT_HOMES
    unknown = [h for h in homes if h not in home_names() and not is_generated(h)]
    if unknown:
        raise HomesimError(f"--home {unknown[0]}: not a built-in home or gen-SEED "
                           f"(choose from {', '.join(home_names())}, gen-0, gen-1, ...)")
    with Progress(TextColumn("sampling programs"), BarColumn(), MofNCompleteColumn(),
                  console=console) as bar:
        task = bar.add_task("synth", total=n)

        def counted():
            for sp in generate(n, seed, homes, style=descriptions):
                yield sp
                bar.advance(task)

        written = write_jsonl(counted(), out, force=force)
    console.print(f"[green]ok[/]: {written} programs in {out} (seed {seed})")
