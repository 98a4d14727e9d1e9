"""`homesim run`: execute a program on a home and show each step's outcome."""

from __future__ import annotations

import json
from typing import Annotated

import typer
from rich.markup import escape
from rich.table import Table

from homesim.cli.common import console, demo_program, read_graph, read_program
from homesim.errors import HomesimError
from homesim.examples import DEMO_HOME
from homesim.ground.pipeline import run_program
from homesim.ground.prepare import Prepared
from homesim.ground.search import Grounding
from homesim.sim.execute import ExecutionResult
from homesim.world.graph import EnvironmentGraph


def _show_grounding(g: EnvironmentGraph, prepared: Prepared, grounding: Grounding) -> None:
    def where(node: int) -> str:
        room = g.room_of(node)
        return "" if room is None or room == node else f" in {g.node(room).label()}"

    for a in prepared.added:
        dest = "the floor" if a.destination_id == a.room else g.node(a.destination_id).label()
        console.print(f"[cyan]added[/] {g.node(a.node_id).label()} {a.relation} {dest}"
                      f"{where(a.node_id)}")
    for node, before, after in prepared.states:
        gone = ",".join(sorted(before - after)) or "-"
        new = ",".join(sorted(after - before)) or "-"
        console.print(f"[cyan]initial state[/] {g.node(node).label()}: {gone} → {new}")
    chosen = ", ".join(f"<{name}> ({inst}) → {g.node(node).label()}{where(node)}"
                       for (name, inst), node in grounding.bindings.items())
    console.print(f"[cyan]grounded[/] {chosen}")
    if grounding.standing:
        spots = ", ".join(f"{i + 1}: ({x:.2f}, {z:.2f})"
                          for i, (x, z) in sorted(grounding.standing.items()))
        console.print(f"[cyan]agent stands at[/] (x, z per step) {spots}")


def run(
    program: Annotated[str | None, typer.Argument(
        help="Program file (ActivityPrograms format or steps only); '-' reads stdin. "
             "Without it, runs the built-in demo.")] = None,
    graph: Annotated[str | None, typer.Option(help="Environment graph JSON file.")] = None,
    home: Annotated[str | None, typer.Option(
        help="Built-in home (see 'homesim homes'); default scene1.")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")]
    = False,
    all_changes: Annotated[bool, typer.Option(
        "--all-changes", help="List every CLOSE edge instead of counting them.")] = False,
    seed: Annotated[int, typer.Option(
        help="Seed of scene preparation and grounding (ungrounded programs).")] = 0,
    no_ground: Annotated[bool, typer.Option(
        "--no-ground", help="Run an ungrounded program as is, reading (N) as node N, as "
                            "the reference simulator does.")] = False,
    with_repair: Annotated[bool, typer.Option(
        "--repair/--no-repair", help="When the program cannot run as written, insert the "
                                     "commonsense steps it misses (walk to an object before "
                                     "grabbing it, ...) and list each with its reason "
                                     "(default); --no-repair gives the strict answer.")]
    = True,
) -> None:
    """Execute a program step by step and show what each step did or why it failed.

    Runs `homesim.run_program`: an ungrounded program (``<cup> (1)``, no node ids) is first
    prepared (objects the home lacks are added) and grounded (each object bound to an
    instance of the home); a grounded one is checked (its nodes exist and are of its
    classes) and run as it is.

    A program that cannot run as written is repaired (unless ``--no-repair``): each
    inserted step is listed with its reason. ``--json`` prints `Run.to_dict()`, as the
    web API answers.
    """
    g, gname = read_graph(graph, home, DEMO_HOME)
    prog = read_program(program) if program else demo_program(gname)
    if not prog.steps:
        raise HomesimError(f"{program or 'demo'}: the program has no steps")
    ran = run_program(prog, g, seed=seed, trace=True, reference=no_ground,
                      repair=with_repair)
    if as_json:
        console.print_json(json.dumps(ran.to_dict()))
        raise typer.Exit(0 if ran.executable else 1)
    result = ran.result
    if result is None:
        console.print(f"[red]cannot ground[/] in {escape(gname)}: {escape(ran.message)}")
        raise typer.Exit(1)
    if ran.strict is not None:
        console.print(f"[yellow]as written[/]: {escape(ran.strict.message)}")
    for ins in ran.insertions:
        console.print(f"[cyan]inserted[/] step {ins.index + 1} {escape(str(ins.step))}: "
                      f"{escape(ins.reason)}")
    if ran.prepared is not None and ran.grounding is not None:
        _show_grounding(ran.graph, ran.prepared, ran.grounding)
    title = result.program.title or (program or "demo")
    console.print(_step_table(result, f"{title} — {gname} ({len(ran.graph)} nodes)",
                              all_changes))
    if result.executable:
        console.print(f"[green]executable[/]: all {len(result.program.steps)} steps ran")
    else:
        console.print(f"[red]not executable[/]: {escape(result.message)}")
        raise typer.Exit(1)


def _step_table(result: ExecutionResult, title: str, all_changes: bool) -> Table:
    """One row per step: ✓ and what it changed, ✗ and why, or · not run."""
    prog = result.program
    label = result.state.label
    table = Table(title=title, title_justify="left", show_header=False, box=None,
                  pad_edge=False)
    table.add_column(justify="right", style="dim")
    table.add_column()
    table.add_column()
    table.add_column(overflow="fold")
    for rec in result.trace or []:
        mark = "[green]✓[/]" if rec.ok else "[red]✗[/]"
        detail = rec.changes.describe(label, all_changes) if rec.ok \
            else f"[red]{escape(rec.reason or '')}[/]"
        table.add_row(str(rec.index + 1), mark, escape(str(rec.step)), detail)
    for index in range(result.steps_run + 1, len(prog.steps)):
        table.add_row(str(index + 1), "[dim]·[/]", f"[dim]{escape(str(prog.steps[index]))}[/]",
                      "[dim]not run[/]")
    return table
