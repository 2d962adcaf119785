# Two commands: `make run` opens the editor, `make test` runs every test. Both set everything up.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: run test bench deps build clean sanitize

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/sylva $(PRESET)

test: build
	@bash scripts/run-tests.sh $(BUILD)

bench: build
	./$(BUILD)/sylva bench presets/*.json

sanitize:
	$(MAKE) test BUILD=build-asan CMAKE_FLAGS="-DSYLVA_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo"

clean:
	rm -rf $(BUILD)
