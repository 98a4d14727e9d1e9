"""Table 3 as markdown, from the results `table.evaluate_dataset` returns."""

from __future__ import annotations


def markdown_table(results: list[dict], eval_seconds: float | None = None) -> str:
    """One markdown table per data set, with sizes and training times under it."""
    lines: list[str] = []
    for result in results:
        lines += [f"### {result['dataset'].capitalize()} data "
                  f"(test n={result['n_test']}, train n={result['n_train']})", "",
                  "| Method | Action | Objects | Steps | Mean | Simulator % |",
                  "|---|---:|---:|---:|---:|---:|"]
        for row, s in result["rows"].items():
            lines.append(f"| {row} | {s['action']:.3f} | {s['objects']:.3f} | "
                         f"{s['steps']:.3f} | {s['mean']:.3f} | {s['simulator']:.1f} |")
        times = ", ".join(f"{name} {sec:.0f} s" for name, sec in result["train_seconds"].items()
                          if sec is not None)
        lines += ["", f"Training wall time: {times}.", ""]
    if eval_seconds is not None:
        lines += [f"Evaluation wall time (all rows, both data sets): {eval_seconds:.0f} s.", ""]
    return "\n".join(lines)
