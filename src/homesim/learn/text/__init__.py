"""The paper's description -> program model: an LSTM encoder and an attentive step decoder
(`seq2seq`, with its `Seq2SeqConfig`), one checkpoint file with its vocabularies
(`text2prog`), MLE then self-critical policy gradient (`train`), greedy, sampled and
simulator-constrained decoding (`decode`), and a minimum-Bayes-risk consensus of its
samples with retrieved programs (`consensus`)."""
