from homesim.learn.eval.baselines import nn_retrieval, random_retrieval, random_sampling


def test_random_baselines_are_seeded(tiny_splits):
    train, test = tiny_splits.train, tiny_splits.test
    a = [str(p) for p in random_sampling(train, test, seed=1)]
    assert a == [str(p) for p in random_sampling(train, test, seed=1)]
    assert a != [str(p) for p in random_sampling(train, test, seed=2)]
    pool = {e.program.steps for e in train}
    assert all(p.steps in pool for p in random_retrieval(train, test, seed=1))


def test_nn_retrieval_finds_the_same_description(tiny_splits):
    train = tiny_splits.train
    preds = nn_retrieval(train, train[:5])
    assert [p.steps for p in preds] == [e.program.steps for e in train[:5]]


def test_title_medoid_is_the_activitys_most_central_program():
    from homesim.learn.eval.baselines import medoids, title_medoid
    from homesim.program.metrics import lcs_steps

    train = _with_activity_copies()
    centres = medoids(train)
    for activity, centre in centres.items():
        group = [e for e in train if e.activity == activity]
        total = sum(lcs_steps(centre.program, e.program) for e in group)
        assert all(total >= sum(lcs_steps(o.program, e.program) for e in group) for o in group)
    preds = title_medoid(train, train[:3])
    assert [p.steps for p in preds] == [centres[e.activity].program.steps for e in train[:3]]


def test_title_median_is_more_central_than_the_medoid_where_it_can_be():
    from homesim.learn.data import Example
    from homesim.learn.eval.baselines import medoids, title_median
    from homesim.program.metrics import lcs_steps
    from homesim.program.model import Program
    from tests.learn.rerank.test_median import program

    dishes = [Example(f"d{i}", Program(program(s).steps, "Wash dishes", s))
              for i, s in enumerate(("fae", "ebe", "ecda"))]
    train = [*dishes, *_with_activity_copies()]
    centres = medoids(train)
    for pred, e in zip(title_median(train, train), train, strict=True):
        group = [x.program for x in train if x.activity == e.activity]
        median = sum(lcs_steps(pred, q) for q in group)
        medoid = sum(lcs_steps(centres[e.activity].program, q) for q in group)
        assert median > medoid + 0.1 if e in dishes else median >= medoid


def test_an_unseen_activity_gets_the_medoid_of_the_nearest_title():
    from dataclasses import replace

    from homesim.learn.eval.baselines import medoids, title_medoid
    from homesim.program.model import Program

    train = _with_activity_copies()
    tv = next(e for e in train if e.activity == "watch tv")
    unseen = replace(tv, program=Program(tv.program.steps, "Watch television", "relax"))
    (pred,) = title_medoid([e for e in train if e.activity != unseen.activity], [unseen])
    assert pred.steps == medoids(train)["watch tv"].program.steps


def test_nn_on_title_and_on_description(tiny_splits):
    from homesim.learn.eval.baselines import nn_description, nn_title

    train = tiny_splits.train
    assert [p.steps for p in nn_description(train, train[:4])] == [
        e.program.steps for e in train[:4]]
    for pred, e in zip(nn_title(train, train[:6]), train[:6], strict=True):
        same_title = {x.program.steps for x in train if x.title == e.title}
        assert pred.steps in same_title


def _with_activity_copies():
    from homesim.learn.data import synthetic_examples

    return synthetic_examples(30, seed=5)


def test_oracle_retrieval_returns_the_closest_training_program(tiny_splits):
    from homesim.learn.eval.baselines import oracle_retrieval
    from homesim.program.metrics import lcs_steps

    train, test = tiny_splits.train, tiny_splits.test
    preds = oracle_retrieval(train, test)
    for p, e in zip(preds, test, strict=True):
        best = max(lcs_steps(t.program, e.program) for t in train)
        assert lcs_steps(p, e.program) == best
    assert [p.steps for p in oracle_retrieval(train, train[:3])] == [
        e.program.steps for e in train[:3]]
