from homesim.learn.eval.scores import lcs_scores
from homesim.learn.text.text2prog import Text2Prog
from homesim.learn.text.train import TrainConfig, reward, train_mle, train_pg

SIM_WEIGHT = TrainConfig().sim_weight


def test_mle_loss_falls_then_pg_runs(tiny_splits):
    train = tiny_splits.train[:12]
    t2p = Text2Prog.create(train, seed=0, embeddings="none")
    history = train_mle(t2p, train, TrainConfig(epochs=4, batch_size=4, lr=1e-2))
    assert len(history) == 4 and history[-1] < history[0]
    calls = []
    rewards = train_pg(t2p, train, TrainConfig(epochs=1, batch_size=6, lr=1e-3), use_sim=True,
                       progress=lambda d, t, v: calls.append((d, t)))
    assert len(rewards) == 1 and 0.0 <= rewards[0] <= 1.0 + SIM_WEIGHT
    assert calls[-1] == (2, 2)


def test_reward_is_lcs_plus_simulator_bonus(tiny_splits):
    e = tiny_splits.train[0]
    assert reward(e.program, e, use_sim=False) == 1.0
    assert reward(e.program, e, use_sim=True) == 1.0 + SIM_WEIGHT
    assert reward(e.program, e, use_sim=True, sim_weight=0.5) == 1.5
    wrong = e.program.with_steps(e.program.steps[1:])
    assert reward(wrong, e, use_sim=False) == lcs_scores(wrong, e.program)[2]


def test_best_on_dev_restores_the_best_epoch(tiny_splits):
    from homesim.learn.text.train import BestOnDev

    train = tiny_splits.train[:12]
    t2p = Text2Prog.create(train, seed=0, embeddings="none")
    best = BestOnDev(t2p, train[:4])
    train_mle(t2p, train, TrainConfig(epochs=3, batch_size=4, lr=1e-2), after_epoch=best)
    assert len(best.scores) == 3 and best.best == max(best.scores)
    best.restore()
    restored = BestOnDev(t2p, train[:4])
    restored(0)
    assert restored.scores[0] == best.best
