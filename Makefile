# Two commands do everything on a machine with Python 3.11 and make:
#   make reproduce   create .venv if missing, install, regenerate tables/ and figures/
#   make test        create .venv if missing, install with the test extra, run lint and pytest
#   make docs        the documentation site in docs/_build/html (Sphinx, the docs extra)
#   make wheel-check build a wheel and an sdist, install the wheel in a fresh venv, smoke-test it
# Tested versions of every dependency are pinned in constraints.txt.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip install --quiet -c constraints.txt

.PHONY: reproduce test lint bench docs wheel-check clean-venv

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(VENV)/.installed: pyproject.toml constraints.txt | $(BIN)/python
	$(PIP) -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml constraints.txt | $(BIN)/python
	$(PIP) -e '.[test]'
	touch $@ $(VENV)/.installed

$(VENV)/.installed-docs: pyproject.toml constraints.txt | $(BIN)/python
	$(PIP) -e '.[docs]'
	touch $@ $(VENV)/.installed

$(VENV)/.installed-build: pyproject.toml constraints.txt | $(BIN)/python
	$(PIP) -e '.[build]'
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

docs: $(VENV)/.installed-docs
	MPLBACKEND=Agg $(BIN)/sphinx-build -W --keep-going -b html docs docs/_build/html

wheel-check: $(VENV)/.installed-build
	PYTHON=$(BIN)/python .ci/wheel-check

clean-venv:
	rm -rf $(VENV)
