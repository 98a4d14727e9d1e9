"""The real program data set (fetched by `homesim.knowledge.fetch`), as homesim values."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from homesim.errors import DataError
from homesim.knowledge.fetch import dataset_dir, verify
from homesim.program.model import Program
from homesim.program.parse import parse_program
from homesim.world.graph import EnvironmentGraph


@dataclass(frozen=True)
class RealProgram:
    """One real program with the graphs the original simulator stored for it.

    Attributes:
        id: file stem, e.g. ``file1003_2`` (script 1003, second annotation).
        program: the parsed program; refs are grounded (``<computer> (1.417)``).
        graph_path: JSON file holding ``init_graph`` and ``final_graph``.
    """

    id: str
    program: Program
    graph_path: Path

    def graph_dicts(self) -> tuple[dict, dict]:
        """The stored initial and final graphs as raw VirtualHome dicts."""
        try:
            data = json.loads(self.graph_path.read_text())
            return data["init_graph"], data["final_graph"]
        except (OSError, ValueError, KeyError) as e:
            raise DataError(f"{self.graph_path}: cannot read stored graphs ({e})") from None

    def graphs(self) -> tuple[EnvironmentGraph, EnvironmentGraph]:
        """The stored initial and final graphs."""
        init, final = self.graph_dicts()
        where = str(self.graph_path)
        return (EnvironmentGraph.from_dict(init, f"{where}:init_graph"),
                EnvironmentGraph.from_dict(final, f"{where}:final_graph"))


def real_programs(directory: Path | None = None, check: bool = False) -> list[RealProgram]:
    """All real programs, sorted by id; `check` verifies checksums first."""
    directory = directory or dataset_dir()
    if check:
        verify(directory)
    programs_dir = directory / "programs"
    if not programs_dir.is_dir():
        raise DataError(f"{directory}: the real data set is not here; run 'homesim data fetch'")
    out = []
    for path in sorted(programs_dir.glob("*.txt")):
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            raise DataError(f"{path}: not UTF-8 text") from None
        program = parse_program(text, source=str(path))
        out.append(RealProgram(path.stem, program, directory / "graphs" / f"{path.stem}.json"))
    return out
