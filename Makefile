# Two commands do everything on a machine with Python 3.11 and make:
#   make reproduce   create .venv if missing, install, regenerate tables/ and figures/
#   make test        create .venv if missing, install with the test extra, run lint and pytest
# Tested versions of every dependency are pinned in constraints.txt.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip install --quiet -c constraints.txt

.PHONY: reproduce test lint bench clean-venv

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(VENV)/.installed: pyproject.toml constraints.txt | $(BIN)/python
	$(PIP) -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml constraints.txt | $(BIN)/python
	$(PIP) -e '.[test]'
	touch $@ $(VENV)/.installed

reproduce: $(VENV)/.installed
	MPLBACKEND=Agg $(BIN)/gearlever reproduce --tables tables --figures figures

lint: $(VENV)/.installed-test
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/ruff format --check src tests benchmarks

test: lint
	MPLBACKEND=Agg $(BIN)/python -m pytest src tests

bench: $(VENV)/.installed
	for f in benchmarks/*.py; do $(BIN)/python $$f || exit 1; done

clean-venv:
	rm -rf $(VENV)
