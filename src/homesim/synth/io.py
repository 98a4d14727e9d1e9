"""Synthetic programs as JSON lines: the data set JSONL format of `homesim.knowledge.datasets`
(one `ActivityProgram.to_json()` record per line, with ``home`` and ``bindings``)."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from homesim.knowledge.datasets import ActivityDataset, ActivityProgram
from homesim.knowledge.datasets import write_jsonl as _write


def write_jsonl(programs: Iterable[ActivityProgram], path: Path, force: bool = True) -> int:
    """Write the programs to `path` atomically; return how many were written.

    Refuses to replace an existing file unless `force`; an error or interrupt while the
    programs are generated leaves `path` as it was and no temporary file behind.
    """
    return _write(programs, path, force=force)


def read_jsonl(path: Path) -> list[ActivityProgram]:
    """Read programs written by `write_jsonl` (any data set JSONL file); a bad line raises
    `DataError` naming it."""
    return list(ActivityDataset.from_jsonl(path))
