"""``homesim homes``: list the built-in homes, generate new ones, draw a home's plan."""

from __future__ import annotations

import time
from typing import Annotated

import typer

from homesim.cli.common import console
from homesim.errors import HomesimError
from homesim.files import check_target
from homesim.world.homes import home_names, open_home

app = typer.Typer(help="List, generate and draw homes.", invoke_without_command=True,
                  no_args_is_help=False)


@app.callback()
def homes(ctx: typer.Context) -> None:
    """List the built-in homes (``homesim homes``); see the subcommands for more."""
    if ctx.invoked_subcommand is None:
        for name in home_names():
            console.print(name)


@app.command("generate")
def generate(
    seed: Annotated[int, typer.Option(help="Random seed: same seed, same home.")] = 0,
    rooms: Annotated[str | None, typer.Option(
        help="Comma-separated room kinds, e.g. living_room,kitchen,bathroom,bedroom "
             "(default: the four core kinds and up to four more).")] = None,
    out: Annotated[str | None, typer.Option(
        help="Write the home here (.json or .json.gz); default gen-SEED.json.gz.")] = None,
    force: Annotated[bool, typer.Option(help="Replace OUT if it exists.")] = False,
) -> None:
    """Generate a home from a seed; it is written only if it passes every check."""
    from homesim.world.procedural import generate_home, write_home

    path = out or f"gen-{seed}.json.gz"
    if not path.endswith((".json", ".json.gz")):
        raise HomesimError(f"--out {path}: a home file ends in .json or .json.gz")
    check_target(path, force)  # before the work, not after it
    t0 = time.perf_counter()
    kinds = [r.strip() for r in rooms.split(",") if r.strip()] if rooms else None
    graph = generate_home(seed, kinds)
    write_home(graph, path)
    console.print(f"{path}: {len(graph.rooms())} rooms "
                  f"({', '.join(r.class_name for r in graph.rooms())}), {len(graph)} nodes, "
                  f"{graph.num_edges()} edges, {time.perf_counter() - t0:.2f} s")


@app.command("show")
def show(
    home: Annotated[str, typer.Argument(help="A built-in home, gen-SEED, or a home file.")],
    out: Annotated[str, typer.Option(help="PNG file to write.")] = "home.png",
    force: Annotated[bool, typer.Option(help="Replace OUT if it exists.")] = False,
) -> None:
    """Draw a labelled top-down plan of a home (rooms, furniture, doors, windows)."""
    from homesim.world.show import draw_plan

    check_target(out, force)
    draw_plan(open_home(home), out, title=home)
    console.print(f"wrote {out}")
