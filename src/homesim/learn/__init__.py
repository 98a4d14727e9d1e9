"""Learning to write programs from descriptions (needs the ``learn`` extra: PyTorch).

Glossary:
    example: a description, its ungrounded program and the home it belongs to (`data`).
    step vocabulary: every (action, object classes) step seen in training; the decoder
        scores all of them at each position (`vocab`, `seq2seq`).
    MLE / PG: teacher-forced training, then self-critical policy gradient with an LCS and
        simulator reward (`train`).
    constrained decoding: greedy decoding that emits only steps whose preconditions hold
        in the simulated home (`decode`).
"""
