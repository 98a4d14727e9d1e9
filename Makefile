# Two commands: `make demo` (set up and run the main job) and `make test` (set up and test).
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
EXTRAS ?= dev,stats,learn

.PHONY: setup demo test lint bench clean

setup: $(VENV)/.installed

$(VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[$(EXTRAS)]"
	touch $@

demo: setup
	$(BIN)/homesim run

test: setup
	$(BIN)/homesim data fetch
	$(BIN)/ruff check src tests benchmarks tools
	HOMESIM_REQUIRE_DATA=1 $(BIN)/python -m pytest

bench: setup
	$(BIN)/homesim data fetch
	$(BIN)/python benchmarks/executor.py
	$(BIN)/python benchmarks/grounding.py

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .ruff_cache
