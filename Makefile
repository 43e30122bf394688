# Spiral bevel gear contact analysis toolkit.
# `make validate` and `make test` each work on a fresh machine: both call `make setup` first.

SCENE   ?= reference/scenes/default.toml
OUT     ?= out
CARGO   ?= cargo
RELEASE := --release
BIN     := target/release

.PHONY: setup build test bench preprocess solve validate clean

setup:
	@bash scripts/setup.sh

build: setup
	$(CARGO) build $(RELEASE) --workspace --bins

test: setup
	$(CARGO) test $(RELEASE) --workspace
	bash scripts/check_env.sh

bench: setup build
	$(CARGO) bench -p preprocess --bench flanks
	$(CARGO) bench -p preprocess --bench mesh
	$(CARGO) bench -p preprocess --bench stiffness

preprocess: build
	$(BIN)/preprocess flanks $(SCENE) --out $(OUT)/$(notdir $(basename $(SCENE)))/flanks
	$(BIN)/preprocess mesh $(SCENE) --level reduced --out meshes
	$(BIN)/preprocess stiffness $(SCENE) --meshes meshes

solve: build
	$(BIN)/solver plan $(SCENE) --out $(OUT)/$(notdir $(basename $(SCENE)))/plan.json

validate: preprocess
	$(BIN)/validate utca $(SCENE) --flanks $(OUT)/$(notdir $(basename $(SCENE)))/flanks --reports reports

clean:
	$(CARGO) clean
	rm -rf $(OUT) reports
