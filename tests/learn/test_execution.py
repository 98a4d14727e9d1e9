from dataclasses import replace

from homesim.learn.execution import StepRunner, executable


def test_truth_programs_execute_in_their_home(tiny_splits):
    assert all(executable(e.program, e) for e in tiny_splits.train)


def test_step_out_of_order_does_not_execute(tiny_splits):
    e = next(x for x in tiny_splits.train if len(x.program) >= 2)
    swapped = e.program.with_steps(tuple(reversed(e.program.steps)))
    assert not executable(swapped, e) or swapped == e.program


def test_can_run_leaves_the_state_and_try_step_binds(tiny_splits):
    e = tiny_splits.train[0]
    first = e.program.steps[0]
    key = (first.action.key, tuple(r.name for r in first.args))
    runner = StepRunner(e)
    mark = runner.state.mark()
    assert runner.can_run(key)
    assert runner.state.mark() == mark and not runner.bound
    assert runner.try_step(key) and runner.bound


def test_missing_class_cannot_run(tiny_splits):
    e = replace(tiny_splits.train[0], bindings={})
    assert not StepRunner(e).try_step(("WALK", ("no_such_thing",)))


def test_greedy_runner_and_grounding_agree_on_truth(tiny_splits):
    from homesim.learn.execution import runs_greedily

    for e in tiny_splits.test:
        assert runs_greedily(e.program, e) and executable(e.program, e)
