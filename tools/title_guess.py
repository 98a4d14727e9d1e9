"""How often the program writer names a description's activity right when no title is given
(`homesim.learn.rerank.program_writer.ProgramWriter.guess_title`), leave-one-out over the
real programs.

    .venv/bin/python tools/title_guess.py

Each real description votes among the others (their own program's copies hidden, as when
the writer was fitted), with weights softmax(MiniLM cosine / tau); the nearest description
alone is tau -> 0. Prints the share of descriptions whose title wins the vote.
"""

from __future__ import annotations

import numpy as np

from homesim.learn.rerank.program_writer import real_writer, vote_titles

TAUS = (0.01, 0.02, 0.05, 0.1, 0.2)


def main() -> None:
    writer = real_writer()
    bank = writer.reranker.bank
    titles = np.array([e.title for e in bank.train])
    sims = bank.desc @ bank.desc.T
    same = np.array([[t == u for u in bank.tokens] for t in bank.tokens])
    sims = np.where(same, -np.inf, sims)  # itself and copies of its program
    nearest = titles[sims.argmax(axis=1)]
    print(f"{len(titles)} descriptions, {len(set(titles))} activities")
    print(f"nearest description's title: {np.mean(nearest == titles):.1%}")
    for tau in TAUS:
        voted = np.array(vote_titles(sims, list(titles), tau))
        mark = "  (the writer's)" if tau == writer.title_tau else ""
        print(f"vote, tau {tau}: {np.mean(voted == titles):.1%}{mark}")


if __name__ == "__main__":
    main()
