"""Synthetic programs as JSON lines: one `SynthProgram.to_json()` object per line."""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path

from homesim.errors import DataError, HomesimError
from homesim.synth.grammar import SynthProgram


def write_jsonl(programs: Iterable[SynthProgram], path: Path) -> int:
    """Write the programs to `path` (replacing it); return how many were written."""
    count = 0
    tmp = path.with_name(path.name + ".part")
    with tmp.open("w", encoding="utf-8") as f:
        for sp in programs:
            f.write(json.dumps(sp.to_json()) + "\n")
            count += 1
    tmp.replace(path)
    return count


def read_jsonl(path: Path) -> list[SynthProgram]:
    """Read programs written by `write_jsonl`; a bad line raises `DataError` naming it."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise DataError(f"{path}: cannot read synthetic programs ({e})") from None
    out = []
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            out.append(SynthProgram.from_json(json.loads(line)))
        except (ValueError, KeyError, TypeError, HomesimError) as e:
            raise DataError(f"{path}:{number}: not a synthetic program ({e})") from None
    return out
