# Two commands on a fresh machine with Python 3.11:
#   make reproduce   install into .venv and rebuild every figure and table
#   make test        install into .venv (with test extras) and run the tests
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
CORES ?= 2

.PHONY: reproduce test check install clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e ".[test]"
	touch $@

install: $(VENV)/.installed

reproduce: install
	$(BIN)/snakemake -c$(CORES)

check: install
	$(BIN)/snakemake -c$(CORES) all reproduce_check --forcerun reproduce_check

test: install
	$(BIN)/python -m pytest

clean:
	rm -rf results .snakemake
