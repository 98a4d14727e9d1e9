"""The README's example and docs/grounding.md's first snippet run in any home.

The README's watch-TV program, ungrounded, through `homesim.run_program` (prepare, ground,
repair, execute) and the two halves (`prepare_and_ground`, `execute`) on the program that
ran, in every built-in home and a sample of generated ones; `benchmarks/examples.py`
runs them in all of gen-0..gen-99.
"""

from __future__ import annotations

import pytest

import homesim
from homesim.world.homes import home_names

WATCH_TV = "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Walk] <sofa> (1)\n[Sit] <sofa> (1)\n" \
           "[Watch] <tv> (1)\n"


def test_the_readme_program_is_the_readme_s():
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    assert WATCH_TV.strip() in readme


@pytest.mark.parametrize("home", [*home_names(), "gen-0", "gen-3", "gen-7"])
def test_the_watch_tv_example_runs(home):
    p = homesim.parse_program(WATCH_TV)
    run = homesim.run_program(p, home, seed=0, trace=True)
    assert run.executable, run.message
    # Repair only inserts: the program's own steps ran, in order.
    inserted = {ins.index for ins in run.insertions}
    own = [s for i, s in enumerate(run.result.program.steps) if i not in inserted]
    assert [s.action.key for s in own] == [s.action.key for s in p.steps]
    # The halves, as the README shows them, on the program that ran.
    g = homesim.load_home(home)
    prepared, grounding = homesim.prepare_and_ground(run.repaired or p, g, seed=0)
    assert homesim.execute(grounding.program, prepared.graph).executable


def test_the_demo_runs_in_another_home(capsys):
    from homesim.cli.main import main

    assert main(["run", "--home", "scene3"]) == 0
    out = capsys.readouterr().out
    assert "inserted step 5 [TurnTo] <tv> (1)" in out and "executable: all 6 steps ran" in out
