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
	./$(BUILD)/app/sylva $(PRESET)

test: build
	@bash scripts/run-tests.sh $(BUILD)

bench: build
	./$(BUILD)/app/sylva bench --repeat 5
	@if [ -x $(BUILD)/tests/sylva_microbench ]; then ./$(BUILD)/tests/sylva_microbench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; fi

sanitize:
	$(MAKE) test BUILD=build-asan CMAKE_FLAGS="-DSYLVA_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo"

clean:
	rm -rf $(BUILD)
