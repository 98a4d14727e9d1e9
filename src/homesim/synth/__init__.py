"""Synthetic programs: a probabilistic grammar of executable programs with descriptions."""

from homesim.synth.grammar import DEFAULT_HOMES, Grammar, generate
from homesim.synth.io import read_jsonl, write_jsonl

__all__ = ["DEFAULT_HOMES", "Grammar", "generate", "read_jsonl", "write_jsonl"]
