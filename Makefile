# Set-up and entry points. `make run` and `make test` bootstrap .venv from PyPI on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: run test lint bench learn clean

$(STAMP): setup.py setup.cfg pyproject.toml package.xml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/vehicle-sim run $(ARGS)

lint: $(STAMP)
	$(BIN)/ruff check .

test: lint
	$(BIN)/python -m pytest $(PYTEST_ARGS)

bench: $(STAMP)
	$(BIN)/python benchmarks/run_all.py $(ARGS)

# The `learn` extra (stable-baselines3 and PyTorch, CPU build: a plain `pip install torch` pulls
# the CUDA build, several GB), then the highway training (docs/learning.md; ARGS: --minutes,
# --seed, --out). TORCH_INDEX: PyTorch's CPU wheels; TORCH_INDEX= leaves pip's own configuration.
TORCH_INDEX ?= https://download.pytorch.org/whl/cpu
LEARN_STAMP := $(VENV)/.installed-learn

$(LEARN_STAMP): $(STAMP)
	$(BIN)/python -m pip install -q $(if $(TORCH_INDEX),--extra-index-url $(TORCH_INDEX)) \
		-e '.[learn]'
	touch $(LEARN_STAMP)

learn: $(LEARN_STAMP)
	$(BIN)/python examples/train_highway.py $(ARGS)

clean:
	rm -rf $(VENV) build *.egg-info
