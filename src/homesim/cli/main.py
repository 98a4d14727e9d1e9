"""The `homesim` command. Each command lives in its own module and is registered here."""

from __future__ import annotations

import inspect
import json
import os
import re
import signal
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Annotated

import typer
from rich.markup import escape

from homesim.cli import data, dataset, goals, homes, learn, render, run, serve, synth
from homesim.cli.common import console, err_console
from homesim.errors import HomesimError
from homesim.version import __version__

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
app.add_typer(dataset.app, name="dataset")
app.command("render")(render.render)
app.command("synth")(synth.synth)
app.add_typer(learn.app, name="learn")
app.add_typer(goals.app, name="goals")
app.add_typer(goals.eval_app, name="eval")
app.add_typer(homes.app, name="homes")


def _show_version(value: bool) -> None:
    if value:
        console.print(f"homesim {__version__}")
        raise typer.Exit(0)


@app.callback()
def _options(
    version: Annotated[bool, typer.Option(
        "--version", callback=_show_version, is_eager=True,
        help="Print the version and exit.")] = False,
) -> None:
    """Simulate household activities described as programs."""


_LITERAL = re.compile(r"``(.+?)``")


def tidy_help(text: str | None) -> str | None:
    """A docstring as help text: paragraphs on one line each, no RST literals, no markup.

    Typer keeps the line breaks of every paragraph but the first, prints ````x```` as is
    and reads ``[Walk]`` as rich markup; the terminal wraps the lines instead.
    """
    if not text:
        return text
    paragraphs = inspect.cleandoc(text).split("\n\n")
    return "\n\n".join(escape(_LITERAL.sub(r"\1", " ".join(p.split()))) for p in paragraphs)


def _tidy(typer_app: typer.Typer) -> None:
    """Apply `tidy_help` to every command and group of `typer_app`, recursively."""
    typer_app.info.help = tidy_help(typer_app.info.help)
    for command in typer_app.registered_commands:
        command.help = tidy_help(command.help or inspect.getdoc(command.callback))
    for group in typer_app.registered_groups:
        group.help = tidy_help(group.help)
        if group.typer_instance is not None:
            _tidy(group.typer_instance)


_tidy(app)


class _Terminated(SystemExit):
    """SIGTERM as an exception, so that `finally` blocks clean up before we exit (143)."""


def _raise_terminated(signum: int, frame: object) -> None:
    raise _Terminated(128 + signum)


@contextmanager
def _terminate_as_exception() -> Iterator[None]:
    """While the command runs, SIGTERM unwinds the stack as Ctrl-C does (main thread only)."""
    try:
        previous = signal.signal(signal.SIGTERM, _raise_terminated)
    except ValueError:  # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _wants_json(argv: list[str] | None) -> bool:
    args = sys.argv[1:] if argv is None else argv
    return "--json" in args[:args.index("--")] if "--" in args else "--json" in args


def main(argv: list[str] | None = None) -> int:
    """Entry point: run the CLI; print one line for a `HomesimError`, never a traceback.

    With ``--json`` the error is a JSON object ``{"error": message}`` on standard output.
    Ctrl-C and SIGTERM stop the command after its clean-up (temporary files, child
    processes: `finally` blocks run) and exit with 130 and 143.
    """
    try:
        with _terminate_as_exception():
            app(args=argv, prog_name="homesim")  # standalone: always ends in SystemExit
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except HomesimError as e:
        if _wants_json(argv):
            console.print_json(json.dumps({"error": str(e)}))
        else:
            err_console.print(f"[red]error[/]: {escape(str(e))}")
        return 2
    except KeyboardInterrupt:  # typer turns Ctrl-C during a command into exit code 130
        return 128 + signal.SIGINT
    except Exception as e:  # a bug of ours: one line, the traceback only on request
        if os.environ.get("HOMESIM_DEBUG"):
            raise
        err_console.print(f"[red]internal error[/]: {type(e).__name__}: {escape(str(e))} "
                          "(set HOMESIM_DEBUG=1 for the traceback, and please report it)")
        return 70
    return 0


if __name__ == "__main__":
    sys.exit(main())
