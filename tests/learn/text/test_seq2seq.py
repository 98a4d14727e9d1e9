import torch

from homesim.learn.text.seq2seq import Seq2Seq, Seq2SeqConfig


def _model() -> Seq2Seq:
    torch.manual_seed(0)
    # action, object, object, instance, instance (instance index 1: the second instance)
    table = torch.tensor([[0, 0, 0, 0, 0], [1, 1, 0, 0, 0], [2, 1, 2, 0, 0], [1, 2, 0, 0, 0],
                          [1, 1, 0, 1, 0]])
    return Seq2Seq(Seq2SeqConfig(n_words=10, n_actions=3, n_objects=3, word_dim=8), table)


def test_step_embedding_is_the_mean_of_its_parts():
    m = _model()
    e = m.step_embeddings()
    a, o = m.actions.weight, m.objects.weight
    assert torch.allclose(e[1], (a[1] + o[1]) / 2)
    assert torch.allclose(e[2], (a[2] + o[1] + o[2]) / 3)
    assert torch.allclose(e[0], a[0])
    assert torch.allclose(e[4], (a[1] + o[1] + m.instances.weight[1]) / 2)
    assert not torch.allclose(e[4], e[1])  # chair 2 is not chair 1


def test_scores_cover_every_step_and_padding_is_ignored():
    m = _model().eval()
    words = torch.tensor([[3, 4, 5], [6, 0, 0]])
    state = m.encode(words, words != 0)
    logits, _ = m.decode_step(state, None, m.step_embeddings())
    assert logits.shape == (2, 5)
    padded = torch.tensor([[6, 0, 0, 0, 0]])
    s1, _ = m.decode_step(m.encode(padded, padded != 0), None, m.step_embeddings())
    assert torch.allclose(s1[0], logits[1], atol=1e-5)


def test_teacher_forced_loss_falls_on_a_fixed_batch():
    m = _model()
    words = torch.tensor([[3, 4, 5], [6, 7, 0]])
    targets = torch.tensor([[1, 2, 0], [3, 0, -100]])
    opt = torch.optim.Adam(m.parameters(), lr=1e-2)
    losses = []
    for _ in range(30):
        loss = m(words, words != 0, targets)
        opt.zero_grad()
        loss.backward()
        opt.step()
        losses.append(loss.item())
    assert losses[-1] < 0.5 * losses[0]
