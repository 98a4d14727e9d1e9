"""Entry points agree: the 518 real programs in the 10 built-in homes, through each door.

Each real program is turned into ungrounded form (`homesim.ground.unground`, as in
benchmarks/grounding.py) and run in each built-in home (five apartments, trimmed and
full) through:

- library: ``homesim.run_program(program, home)`` (what ``homesim run`` calls);
- API: ``POST /api/execute`` through FastAPI's TestClient;
- CLI: ``homesim run FILE --home H --json`` through typer's CliRunner, on the first
  --cli-sample programs of each home (a process-free CLI call is slow-ish);
- and, for comparison, what the API did before issue 11: ground only, without
  preparation (``run_program(..., prepare=False)``).

Printed per home: executable rate of each, and how many programs get the same verdict
AND message through the library and the API (and the CLI sample). Goal: 100% agreement.

    python benchmarks/entry_points.py [--homes scene1_trimmed,...] [--limit N]
                                      [--workers 2] [--cli-sample 20]
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import tempfile
import time
from pathlib import Path

from _real_programs import ungrounded_texts

HOMES = [f"scene{i}{t}" for t in ("_trimmed", "") for i in range(1, 6)]


def _run_home(job: tuple[str, list[str], int]) -> tuple[str, dict]:
    """Every program in one home through every entry point (in a worker process)."""
    home, texts, cli_sample = job
    from fastapi.testclient import TestClient
    from typer.testing import CliRunner

    from homesim.cli.main import app as cli_app
    from homesim.ground import run_program
    from homesim.program import parse_program
    from homesim.serve import create_app
    from homesim.world import load_home

    graph = load_home(home)
    client = TestClient(create_app(), base_url="http://127.0.0.1")  # a loopback Host
    runner = CliRunner()
    counts = {"n": len(texts), "library": 0, "api": 0, "ground_only": 0, "same": 0,
              "cli_n": 0, "cli": 0, "cli_same": 0, "mismatches": []}
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        for i, text in enumerate(texts):
            lib = run_program(parse_program(text), graph)
            api = client.post("/api/execute", json={"program": text, "home": home}).json()
            old = run_program(parse_program(text), graph, prepare=False, repair=False)
            counts["library"] += lib.executable
            counts["api"] += api["executable"]
            counts["ground_only"] += old.executable
            verdict = (lib.executable, lib.message)
            if verdict == (api["executable"], api["message"]):
                counts["same"] += 1
            elif len(counts["mismatches"]) < 3:
                counts["mismatches"].append((i, verdict, api["message"]))
            if i < cli_sample:
                path = Path(tmp) / f"p{i}.txt"
                path.write_text(text, encoding="utf-8")
                out = runner.invoke(cli_app, ["run", str(path), "--home", home, "--json"])
                cli = json.loads(out.stdout)
                counts["cli_n"] += 1
                counts["cli"] += cli["executable"]
                counts["cli_same"] += verdict == (cli["executable"], cli["message"])
    counts["seconds"] = time.perf_counter() - t0
    return home, counts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--homes", default=",".join(HOMES))
    parser.add_argument("--limit", type=int, default=0, help="first N programs only")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--cli-sample", type=int, default=20)
    args = parser.parse_args()

    texts = ungrounded_texts(args.limit)
    homes = args.homes.split(",")
    with mp.get_context("spawn").Pool(args.workers) as pool:
        results = dict(pool.map(_run_home, [(h, texts, args.cli_sample) for h in homes],
                                chunksize=1))
    print(f"{len(texts)} real programs, ungrounded; executable % per entry point "
          "(same: verdict and message identical to the library's)")
    print(f"{'home':16} {'library':>8} {'API':>8} {'same':>8} {'CLI':>12} {'CLI same':>9} "
          f"{'API before (ground only)':>25} {'s':>6}")
    total_same = total = 0
    for home in homes:
        c = results[home]
        n = c["n"]
        total += n
        total_same += c["same"]
        cli = f"{100 * c['cli'] / max(c['cli_n'], 1):.1f} of {c['cli_n']}"
        print(f"{home:16} {100 * c['library'] / n:8.1f} {100 * c['api'] / n:8.1f} "
              f"{100 * c['same'] / n:8.1f} {cli:>12} {c['cli_same']:>4}/{c['cli_n']:<4} "
              f"{100 * c['ground_only'] / n:25.1f} {c['seconds']:6.0f}")
        for m in c["mismatches"]:
            print(f"    mismatch: program {m[0]}: library {m[1]} / API {m[2]!r}")
    print(f"agreement library vs API: {total_same}/{total} "
          f"({100 * total_same / max(total, 1):.1f}%; goal 100%)")


if __name__ == "__main__":
    main()
