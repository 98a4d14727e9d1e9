"""Which built-in home each real program comes from (its stored initial graph names none).

For every real program, the nodes of its initial graph that the original pipeline did not
add (ids < 1000) are matched by id against each built-in home: a node matches when the
home has that id with the same class or an equivalent name (``television`` / ``tv``).
Prints, per home, how many programs match it best and the mean share of matching nodes.

    python tools/source_home.py
"""

from __future__ import annotations

from collections import Counter, defaultdict

from homesim.knowledge import load_kb, real_programs
from homesim.knowledge.kbtypes import class_names_for
from homesim.world import home_names, load_home


def main() -> None:
    kb = load_kb()
    homes = {name: load_home(name) for name in home_names()}
    best: Counter[str] = Counter()
    shares: dict[str, list[float]] = defaultdict(list)
    for rp in real_programs():
        init, _ = rp.graphs()
        base = [n for n in init if n.id < 1000]
        scores = {}
        for name, home in homes.items():
            same = sum(1 for n in base if (h := home.get(n.id)) is not None
                       and h.class_name in class_names_for(n.class_name, kb))
            scores[name] = same / len(base)
            shares[name].append(scores[name])
        best[max(scores, key=scores.get)] += 1
    print(f"{'home':<16} {'best match':>10} {'mean share of nodes matching':>30}")
    for name in homes:
        mean = sum(shares[name]) / len(shares[name])
        print(f"{name:<16} {best[name]:>10} {mean:>30.1%}")


if __name__ == "__main__":
    main()
