from dataclasses import replace

from homesim.ground import run_program
from homesim.learn.execution import StepRunner, executable
from homesim.program import ACTIONS, ObjectRef, Program, Step


def test_truth_programs_execute_in_their_home(tiny_splits):
    assert all(executable(e.program, e) for e in tiny_splits.train)


def test_step_out_of_order_does_not_execute(tiny_splits):
    e = next(x for x in tiny_splits.train if len(x.program) >= 2)
    swapped = e.program.with_steps(tuple(reversed(e.program.steps)))
    assert not executable(swapped, e) or swapped == e.program


def test_can_run_leaves_the_state_and_try_step_binds(tiny_splits):
    e = tiny_splits.train[0]
    first = e.program.steps[0]
    key = (first.action.key, tuple(r.key for r in first.args))
    runner = StepRunner(e)
    assert runner.can_run(key)
    assert runner.steps == () and not runner.bound
    assert runner.try_step(key) and runner.bound and len(runner.steps) == 1


def test_missing_class_cannot_run(tiny_splits):
    e = replace(tiny_splits.train[0], bindings={})
    assert not StepRunner(e).try_step(("WALK", (("no_such_thing", 1),)))


def test_the_runner_accepts_exactly_what_run_program_runs(tiny_splits):
    # television is tv in the homes, wine_glass is added by preparation: as in run_program
    e = tiny_splits.train[0]
    runner = StepRunner(e)
    verdicts = []
    for action, name in [("WALK", "television"), ("SWITCHON", "television"),
                         ("GRAB", "television"), ("WALK", "wine_glass"), ("GRAB", "wine_glass")]:
        key = (action, ((name, 1),))
        step = Step(ACTIONS[action], (ObjectRef(name, 1),))
        expected = run_program(Program((*runner.steps, step)), e.graph()).executable
        verdicts.append(runner.try_step(key))
        assert verdicts[-1] == expected
    assert verdicts == [True, True, False, True, True]
    assert executable(Program(runner.steps), e)


def test_greedy_runner_and_grounding_agree_on_truth(tiny_splits):
    from homesim.learn.execution import runs_greedily

    for e in tiny_splits.test:
        assert runs_greedily(e.program, e) and executable(e.program, e)
