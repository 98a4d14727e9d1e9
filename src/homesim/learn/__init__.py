"""Learning to write programs from descriptions and videos (needs the ``learn`` extra).

Packages, one idea each:
    text: the paper's description -> program seq2seq (`text.seq2seq`), its checkpoint
        (`text.text2prog`), MLE and policy-gradient training (`text.train`), greedy,
        sampled and simulator-constrained decoding (`text.decode`), and its consensus with
        retrieval (`text.consensus`).
    rerank: the learned reranker of retrieved and edited training programs
        (`rerank.reranker`) with its editors (`rerank.insertion`, `rerank.deletion`),
        retrieve-and-edit (`rerank.retrieve`), and the program writer built on it
        (`rerank.program_writer`, ``homesim learn write``).
    video: the paper's Table 2: episodes reduced and cached (`video.cache`, `video.data`),
        the split (`video.splits`), clip models (`video.clips`, `video.framecnn`), the
        video -> program model (`video.video2prog`), training, scoring and the report.
    eval: the evaluation: splits, scores, baselines, seeds and bootstrap intervals, the
        tables and their markdown, the title -> program benchmark.

Shared by them: `data` (examples and the 70/10/20 split), `vocabularies` (words and steps
as ids), `embeddings` (MiniLM and word2vec vectors), `execution` (the simulator as reward,
decoding constraint and Simulator % column).

Glossary:
    example: a description, its ungrounded program and the home it belongs to (`data`).
    step vocabulary: every (action, object classes) step seen in training; the decoder
        scores all of them at each position (`vocabularies`, `text.seq2seq`).
    MLE / PG: teacher-forced training, then self-critical policy gradient with an LCS and
        simulator reward (`text.train`).
    constrained decoding: greedy decoding that emits only steps whose preconditions hold
        in the simulated home (`text.decode`).
    candidate: a training program, or one edited from it, that the reranker scores
        (`rerank.base`).
"""
