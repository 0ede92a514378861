# Two commands do everything on a machine with Python 3.11 and make:
#   make reproduce   create .venv if missing, install, regenerate tables/ and figures/
#   make test        create .venv if missing, install with the test extra, run pytest
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin

.PHONY: reproduce test bench clean-venv

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $@ $(VENV)/.installed

reproduce: $(VENV)/.installed
	MPLBACKEND=Agg $(BIN)/gearlever reproduce --tables tables --figures figures

test: $(VENV)/.installed-test
	MPLBACKEND=Agg $(BIN)/python -m pytest src tests

bench: $(VENV)/.installed
	for f in benchmarks/*.py; do $(BIN)/python $$f || exit 1; done

clean-venv:
	rm -rf $(VENV)
