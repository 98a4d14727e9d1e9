"""How people-like synthetic descriptions are: vocabulary and distinct-n, three sources.

- ``templates``: the fixed task phrases (`homesim.synth.templates`), what the learning
  figures were made with;
- ``people``: the paraphrase grammar (`homesim.synth.describe`), `homesim synth`'s default;
  the same programs as ``templates`` (same seed);
- ``real``: the 518 real descriptions (`homesim.knowledge.datasets`; needs
  ``homesim data fetch``).

The synthetic sets have as many descriptions as the real one (distinct-n falls as a set
grows), from --seed. Prints each set's size, words per description, vocabulary,
distinct-1 and distinct-2 (`homesim.synth.textstats`), and the ratio of the paraphrase
grammar to the templates.

    python benchmarks/descriptions.py [--seed 0] [--samples 5]
"""

from __future__ import annotations

import argparse

from homesim.errors import HomesimError
from homesim.synth import generate
from homesim.synth.textstats import TextStats, text_stats

REAL_COUNT = 518


def real_descriptions() -> list[str]:
    """The real programs' descriptions, or [] without the data set."""
    try:
        from homesim.knowledge.datasets import real_programs
        from homesim.knowledge.fetch import dataset_dir

        return [rp.description for rp in real_programs(dataset_dir())]
    except HomesimError:
        return []


def row(label: str, s: TextStats) -> str:
    return (f"{label:<10} {s.texts:>6} {s.mean_words:>11.1f} {s.vocabulary:>11} "
            f"{s.distinct_1:>11.3f} {s.distinct_2:>11.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--samples", type=int, default=0, help="print this many examples")
    args = parser.parse_args()
    real = real_descriptions()
    n = len(real) or REAL_COUNT
    sets = {style: [sp.program.description for sp in generate(n, args.seed, style=style)]
            for style in ("templates", "people")}
    if real:
        sets["real"] = real
    stats = {label: text_stats(texts) for label, texts in sets.items()}
    print(f"{'':<10} {'texts':>6} {'words/text':>11} {'vocabulary':>11} "
          f"{'distinct-1':>11} {'distinct-2':>11}")
    for label, s in stats.items():
        print(row(label, s))
    new, old = stats["people"], stats["templates"]
    print(f"\npeople / templates: vocabulary {new.vocabulary / old.vocabulary:.2f}x, "
          f"distinct-1 {new.distinct_1 / old.distinct_1:.2f}x, "
          f"distinct-2 {new.distinct_2 / old.distinct_2:.2f}x")
    if not real:
        print("(no real descriptions: run 'homesim data fetch')")
    for i in range(min(args.samples, n)):
        print(f"\n[{i}] templates: {sets['templates'][i]}\n    people:    {sets['people'][i]}")


if __name__ == "__main__":
    main()
