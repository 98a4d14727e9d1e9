"""The `homesim` command. Each command lives in its own module and is registered here."""

from __future__ import annotations

import os
import sys

import typer
from rich.markup import escape

from homesim.cli import data, learn, render, run, serve, synth
from homesim.cli.common import console, err_console
from homesim.errors import HomesimError
from homesim.world.homes import home_names

app = typer.Typer(
    name="homesim",
    help="Simulate household activities described as programs.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
)
app.command("run")(run.run)
app.command("serve")(serve.serve)
app.add_typer(data.app, name="data")
app.command("render")(render.render)
app.command("synth")(synth.synth)
app.add_typer(learn.app, name="learn")


@app.command("homes")
def homes() -> None:
    """List the built-in homes."""
    for name in home_names():
        console.print(name)


def main(argv: list[str] | None = None) -> int:
    """Entry point: run the CLI; print one line for a `HomesimError`, never a traceback."""
    try:
        app(args=argv, prog_name="homesim")  # standalone: always ends in SystemExit
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except HomesimError as e:
        err_console.print(f"[red]error[/]: {escape(str(e))}")
        return 2
    except Exception as e:  # a bug of ours: one line, the traceback only on request
        if os.environ.get("HOMESIM_DEBUG"):
            raise
        err_console.print(f"[red]internal error[/]: {type(e).__name__}: {escape(str(e))} "
                          "(set HOMESIM_DEBUG=1 for the traceback, and please report it)")
        return 70
    return 0


if __name__ == "__main__":
    sys.exit(main())
