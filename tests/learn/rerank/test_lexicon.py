"""Which classes and actions a text names: knowledge-base names and learned links."""

from homesim.learn.rerank.lexicon import LexiconConfig, ObjectLexicon
from tests.learn.rerank.test_reranker import TV, _example


def test_lexicon_finds_knowledge_base_names_and_learned_words():
    train = [_example("Watch TV", f"go to the living room and turn on the tv {i}", TV)
             for i in range(3)]
    lexicon = ObjectLexicon.fit(train)
    named = lexicon.mentions("Turn on the TV in the living room")
    assert "television" in named  # "tv" is a knowledge-base name of television
    assert "home_office" in named  # "living" learned from the three pairs
    assert "home_office" not in ObjectLexicon.fit(train[:1]).mentions("the living room")
    assert lexicon.implicit_rate("television") < 0.5 == lexicon.implicit_rate("unheard_of")
    strict = ObjectLexicon.fit(train, LexiconConfig(min_pairs=4))  # three pairs are too few
    assert "home_office" not in strict.mentions("Turn on the TV in the living room")
