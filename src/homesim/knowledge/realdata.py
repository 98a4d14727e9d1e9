"""The real program data set (fetched by `homesim.knowledge.fetch`), as `ActivityProgram`s."""

from __future__ import annotations

from pathlib import Path

from homesim.errors import DataError
from homesim.knowledge.datasets import ActivityProgram, _check, _read_text
from homesim.knowledge.fetch import dataset_dir, verify
from homesim.program.parse import parse_program


def real_programs(directory: Path | None = None, check: bool = False) -> list[ActivityProgram]:
    """All real programs, sorted by id, each with its stored graphs; `check` verifies
    checksums first.

    Ids are file stems, e.g. ``file1003_2`` (script 1003, second annotation); refs are
    grounded (``<computer> (1.417)``).
    """
    directory = directory or dataset_dir()
    if check:
        verify(directory)
    programs_dir = directory / "programs"
    if not programs_dir.is_dir():
        raise DataError(f"{directory}: the real data set is not here; run 'homesim data fetch'")
    out = []
    for path in sorted(programs_dir.glob("*.txt")):
        program = _check(parse_program(_read_text(path), source=str(path)), str(path))
        out.append(ActivityProgram(path.stem, program, str(path),
                                   directory / "graphs" / f"{path.stem}.json"))
    return out
