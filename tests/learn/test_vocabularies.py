from homesim.learn.vocabularies import END, UNK, StepVocab, WordVocab, step_key, tokenize
from homesim.program import parse_program


def test_tokenize_lowercases_and_drops_punctuation():
    assert tokenize("Turn ON the TV, then sit.") == ["turn", "on", "the", "tv", "then", "sit"]


def test_word_vocab_unknown_and_padding():
    v = WordVocab.build(["go to the sofa"])
    assert v.words[:2] == ["<pad>", "<unk>"]
    assert v.encode("go to the moon")[-1] == UNK
    assert v.encode("!!!") == [UNK]


def test_step_vocab_encode_decode_round_trip():
    p = parse_program("[Walk] <cup> (1)\n[Grab] <cup> (1)\n[PutBack] <cup> (1) <table> (1)")
    v = StepVocab.build([p])
    ids = v.encode(p)
    assert ids[-1] == END and len(ids) == 4
    assert str(v.decode(ids)) == str(p)
    assert v.table[v.index[step_key(p.steps[2])]][2] == v.objects.index("table")
    assert StepVocab.from_json(v.to_json()).steps == v.steps


def test_step_outside_vocabulary_is_reported():
    v = StepVocab.build([parse_program("[Walk] <cup> (1)")])
    assert v.encode(parse_program("[Walk] <sofa> (1)")) is None


def test_instance_numbers_survive_the_vocabulary():
    p = parse_program("[Walk] <chair> (1)\n[Sit] <chair> (1)\n[StandUp]\n[Walk] <chair> (2)")
    v = StepVocab.build([p])
    assert str(v.decode(v.encode(p))) == str(p)
    assert v.table[v.index[step_key(p.steps[3])]][3] == 1  # the second chair's instance
    assert StepVocab.from_json(v.to_json()).steps == v.steps


def test_unseen_share_counts_steps_outside_the_vocabulary():
    v = StepVocab.build([parse_program("[Walk] <cup> (1)\n[Grab] <cup> (1)")])
    other = parse_program("[Walk] <cup> (1)\n[Grab] <mug> (1)\n[Walk] <mug> (1)\n[Grab] <cup> (1)")
    assert v.unseen_share([other]) == 0.5
