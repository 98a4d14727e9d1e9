"""The record of every locked-test run (`homesim learn table --final`; `splits` says which
seeds are locked and why).

A final run is written, before it scores anything (so an interrupted one counts too), as one
JSON line to ``OUT/final-runs.jsonl``: when (UTC), the commit, the data sets and the locked
seeds. The table's markdown lists every final run it knows of, from that file and from the
list the markdown it replaces already holds (so deleting OUT forgets none), and so says how
many times the locked figures it shows were looked at.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

from homesim.errors import DataError

LEDGER = "final-runs.jsonl"
"""The ledger's file name in the table's run folder."""
START, END = "<!-- final-runs:start -->", "<!-- final-runs:end -->"
"""Markers around the list of final runs in the table's markdown."""
_ITEM = re.compile(r"^- (\S+), commit (\S+), data (\S+), seeds (\d+)-(\d+)$")


@dataclass(frozen=True)
class FinalRun:
    """One ``--final`` run: when it started (ISO 8601 UTC, to the microsecond: two runs within
    one second are two runs), the commit, data sets, seeds."""

    when: str
    commit: str
    datasets: tuple[str, ...]
    seeds: tuple[int, ...]

    @classmethod
    def now(cls, commit: str, datasets: tuple[str, ...], seeds: tuple[int, ...]) -> FinalRun:
        """A run starting now (to the microsecond: two runs in one second are two runs)."""
        when = datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%S.%fZ")
        return cls(when, commit, tuple(datasets), tuple(seeds))

    def item(self) -> str:
        """The run as one markdown list item (`from_item` reads it back)."""
        return (f"- {self.when}, commit {self.commit}, data {','.join(self.datasets)}, "
                f"seeds {self.seeds[0]}-{self.seeds[-1]}")

    @classmethod
    def from_item(cls, line: str) -> FinalRun | None:
        """The run a line written by `item` names, or None for another line."""
        m = _ITEM.match(line.strip())
        if m is None:
            return None
        first, last = int(m[4]), int(m[5])
        return cls(m[1], m[2], tuple(m[3].split(",")), tuple(range(first, last + 1)))


def record(out: Path, run: FinalRun) -> None:
    """Append `run` to the ledger of the run folder `out`."""
    out.mkdir(parents=True, exist_ok=True)
    with (out / LEDGER).open("a", encoding="utf-8") as f:
        f.write(json.dumps({"when": run.when, "commit": run.commit,
                            "datasets": list(run.datasets), "seeds": list(run.seeds)}) + "\n")


def read(out: Path) -> list[FinalRun]:
    """The final runs the ledger of `out` holds (none when it has no ledger)."""
    path = out / LEDGER
    if not path.is_file():
        return []
    runs = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        try:
            d = json.loads(line)
            runs.append(FinalRun(d["when"], d["commit"], tuple(d["datasets"]),
                                 tuple(d["seeds"])))
        except (ValueError, KeyError, TypeError):
            raise DataError(f"{path}:{number}: not a final-run record") from None
    return runs


def listed(markdown: str) -> list[FinalRun]:
    """The final runs a table's markdown lists (between `START` and `END`)."""
    if START not in markdown or END not in markdown:
        return []
    block = markdown.split(START, 1)[1].split(END, 1)[0]
    return [r for r in map(FinalRun.from_item, block.splitlines()) if r is not None]


def merged(*lists: list[FinalRun]) -> list[FinalRun]:
    """Every run of `lists` once (the same start and commit is the same run), oldest first."""
    return sorted({(r.when, r.commit): r for runs in lists for r in runs}.values(),
                  key=lambda r: (r.when, r.commit))


def section(runs: list[FinalRun]) -> list[str]:
    """The markdown lines that list `runs` (between the markers) and count them."""
    return [f"`homesim learn table --final` was run {len(runs)} time"
            f"{'' if len(runs) == 1 else 's'} for the locked figures below (each run is "
            "recorded before it scores anything; every one is listed):", "", START,
            *(r.item() for r in runs), END, ""]
