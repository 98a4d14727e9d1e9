"""The one way to run a program in a home: prepare, ground, execute, and repair.

Every entry point runs programs through `run_program`: ``homesim run`` and ``homesim
render``, the web API and editor (``/api/execute``, ``/api/render``), goal checks, the
dataset, the learning reward and constrained decoding (step by step, see
`homesim.learn.execution.StepRunner`), so they all give the same verdict and message.

`run_program` first runs the program as written (`homesim.ground.strict.run_strict`):
an ungrounded program (``<cup> (1)``) is prepared for the home (objects it lacks added,
presupposed states set) and grounded; a grounded one (``<cup> (1.417)``) is checked and
executed as is. When a step cannot run (or grounding fails), it **repairs** the program
(`homesim.ground.repair`): it inserts the commonsense steps people leave out (walk to an
object before grabbing it, turn to the TV before watching it, open the fridge before
taking the milk out), and runs the repaired program. The `Run` then lists every inserted
step with its reason (`Run.insertions`) beside the verdict as written (`Run.strict`).
The program's own steps are never changed, dropped or reordered. When no insertion
helps, the answer is the strict one: where and why the program as written fails.

``repair=False`` gives the strict answer (what plan scoring and the learning figures
use); ``reference=True`` runs the program as the reference simulator does: no
preparation, grounding or repair, ``(N)`` read as node N.

Contract: a program that cannot run in the home is an answer, not an error. Grounding
failures and refused bindings give a `Run` with ``executable`` False, ``stage``
``"grounding"`` and the grounding's one-line message; a step whose preconditions fail
gives ``stage`` ``"execution"``. `run_program` raises only on a broken home (e.g. one
without a character: `ExecutionError`).

>>> from homesim.program import parse_program
>>> from homesim.world import load_home
>>> p = parse_program("[Walk] <dining_room> (1)\\n[Find] <wine_glass> (1)\\n"
...                   "[Grab] <wine_glass> (1)")
>>> run = run_program(p, load_home("scene1_trimmed"))
>>> run.executable, run.message, [a.class_name for a in run.prepared.added]
(True, 'executable: all 3 steps ran', ['wine_glass'])
>>> run = run_program("[Grab] <wine_glass> (1)", "scene1_trimmed")
>>> run.executable, run.message
(True, 'executable: all 2 steps ran, 1 of them inserted by repair')
>>> run.insertions[0].reason
'walk to <wine_glass> (1) before [Grab]: it needs the character close to it'
>>> run.strict.kind.value, run.strict.stage
('unreachable', 'grounding')
>>> run_program("[Grab] <wine_glass> (1)", "scene1_trimmed", repair=False).executable
False
"""

from __future__ import annotations

from dataclasses import replace

from homesim.ground.repair import repair_steps
from homesim.ground.strict import Insertion, Run, as_inputs, insert_steps, run_strict, runs
from homesim.knowledge.kbtypes import ObjectKnowledge, default_kb
from homesim.program.model import Program
from homesim.world.graph import EnvironmentGraph

__all__ = ["Insertion", "Run", "run_program", "runs"]


def run_program(program: Program | str, home: EnvironmentGraph | str, *,
                prepare: bool = True, repair: bool = True, seed: int = 0,
                trace: bool = False, kb: ObjectKnowledge | None = None,
                reference: bool = False) -> Run:
    """Run `program` in `home`: prepare and ground it when it is not grounded, execute it,
    and repair it when a step cannot run.

    Args:
        program: a `Program` or program text.
        home: an environment graph or the name of a built-in home.
        prepare: add the objects the program needs and the home lacks, and set the states
            it presupposes, before grounding (and retry with extra instances where
            grounding fails, see `prepare_and_ground`). Without it, only ground.
        repair: when the program as written cannot run, insert the steps it misses
            (`homesim.ground.repair`) and run that; False gives the strict answer.
        seed: seed of preparation, grounding and repair (same seed, same run).
        trace: record each step's outcome and changes in ``result.trace``.
        kb: the object knowledge base (default: `homesim.knowledge.load_kb()`).
        reference: run as the reference simulator does, ``(N)`` read as node N (nothing
            prepared, grounded or repaired).

    Returns:
        A `Run`; see the module docstring for what fails how.
    """
    program, home = as_inputs(program, home)
    strict = run_strict(program, home, prepare=prepare, seed=seed, trace=trace, kb=kb,
                        reference=reference)
    if strict.executable or not repair or reference or not program.steps:
        return strict
    kb = kb or default_kb()
    insertions = repair_steps(program, home, strict, seed=seed, kb=kb, prepare=prepare)
    if not insertions:
        return strict
    run = run_strict(insert_steps(program, insertions), home, prepare=prepare, seed=seed,
                     trace=trace, kb=kb)
    if not run.executable:  # as repair's search found it; a guard all the same
        return strict
    message = f"{run.message}, {len(insertions)} of them inserted by repair"
    return replace(run, program=program, message=message, insertions=insertions,
                   strict=strict)
