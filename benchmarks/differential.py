"""Differential test: homesim against the VirtualHome reference on the 518 real programs.

Runs the reference (``virtualhome==2.3.0`` in a side venv, see `reference.py`) as shipped
and with its three crashing bugs patched in memory, and homesim, each from the stored
initial graph of every program. For each program it records whether each one executes
it and, for every pair among (homesim, patched reference, stored final graph), whether
node states and each relation (INSIDE, ON, HOLDS_RH, HOLDS_LH, CLOSE, FACING) agree.

    python benchmarks/differential.py [--out differential.jsonl]

prints a summary table and writes one JSON line per program to ``--out``.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from homesim.knowledge.datasets import real_programs
from homesim.knowledge.fetch import dataset_dir, verify
from homesim.sim import execute
from homesim.sim.compare import ASPECTS, aspect
from reference import run_reference

SOURCES = ("homesim", "reference", "stored")
PAIRS = (("homesim", "stored"), ("reference", "stored"), ("homesim", "reference"))


def reference_outcomes(directory: Path, patched: bool) -> dict[str, dict]:
    """The reference runner's per-program dump: status, message, final states and edges."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "dump.jsonl"
        run_reference(directory, "dump", str(out), *(() if patched else ("--unpatched",)))
        return {r["id"]: r for r in map(json.loads, out.read_text().splitlines())}


def aspects_of_dump(record: dict) -> dict[str, set]:
    """The comparable aspects of a reference dump record."""
    found = {"states": {tuple(s) for s in record["states"]}}
    for name in ASPECTS[1:]:
        found[name] = {(a, b) for a, rel, b in record["edges"] if rel == name}
    return found


def compare(directory: Path) -> list[dict]:
    """One record per program: who executes it, and per-pair aspect agreement."""
    print("running the reference as shipped ...", flush=True)
    raw = reference_outcomes(directory, patched=False)
    print("running the reference with its bugs patched ...", flush=True)
    patched = reference_outcomes(directory, patched=True)
    print("running homesim ...", flush=True)
    records = []
    for rp in real_programs(directory):
        init, final = rp.graphs()
        result = execute(rp.program, init, reference=True)
        ref = patched[rp.id]
        seen: dict[str, dict[str, set] | None] = {
            "homesim": ({a: aspect(result.final_graph, a) for a in ASPECTS}
                        if result.executable else None),
            "reference": aspects_of_dump(ref) if ref["status"] == "ok" else None,
            "stored": {a: aspect(final, a) for a in ASPECTS},
        }
        record = {
            "id": rp.id,
            "homesim": "ok" if result.executable else result.message,
            "reference": ref["status"] if ref["status"] == "ok" else ref["message"],
            "reference_unpatched": raw[rp.id]["status"],
        }
        for x, y in PAIRS:
            if seen[x] is not None and seen[y] is not None:
                record[f"{x}~{y}"] = [a for a in ASPECTS if seen[x][a] != seen[y][a]]
        records.append(record)
    return records


def summarize(records: list[dict]) -> None:
    n = len(records)
    unpatched = Counter(r["reference_unpatched"] for r in records)
    print(f"\nexecutable of {n}: homesim {sum(r['homesim'] == 'ok' for r in records)}, "
          f"reference patched {sum(r['reference'] == 'ok' for r in records)}, "
          f"reference as shipped {unpatched['ok']} (crashed {unpatched['crash']}, "
          f"failed {unpatched['fail']})")
    print(f"\n{'aspect':<10}" + "".join(f"{x + ' ~ ' + y:>22}" for x, y in PAIRS))
    for name in ASPECTS:
        cells = []
        for x, y in PAIRS:
            both = [r[f"{x}~{y}"] for r in records if f"{x}~{y}" in r]
            cells.append(f"{sum(name not in d for d in both)}/{len(both)}")
        print(f"{name:<10}" + "".join(f"{c:>22}" for c in cells))
    for r in records:
        if r["homesim"] != "ok" or r["reference"] != "ok":
            print(f"  {r['id']}: homesim: {r['homesim']} | reference: {r['reference']}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("differential.jsonl"))
    args = parser.parse_args()
    directory = dataset_dir()
    verify(directory)
    records = compare(directory)
    args.out.write_text("".join(json.dumps(r) + "\n" for r in records))
    summarize(records)
    print(f"\nper-program records: {args.out}")


if __name__ == "__main__":
    main()
