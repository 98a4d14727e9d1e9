from homesim.learn.baselines import nn_retrieval, random_retrieval, random_sampling


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
