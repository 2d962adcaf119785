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

# ASan + UBSan. alloc_dealloc_mismatch is off because the allocation-counting test replaces the
# global operator new/delete, which makes Mesa's LLVM (llvmpipe) pair allocators ASan cannot match.
# The tests that open a GL context run without leak checking: Mesa's unloaded driver modules leave
# allocations LeakSanitizer reports against "<unknown module>"; every other test checks leaks.
GL_TESTS = HeadlessRender|EditorSmoke|EditorSession|EditorBench|RenderBench
sanitize: deps
	@cmake -S . -B build-asan -DSYLVA_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	@cmake --build build-asan -j $(JOBS)
	ASAN_OPTIONS=alloc_dealloc_mismatch=0 bash scripts/run-tests.sh build-asan -E '$(GL_TESTS)'
	ASAN_OPTIONS=alloc_dealloc_mismatch=0:detect_leaks=0 bash scripts/run-tests.sh build-asan -R '$(GL_TESTS)'

clean:
	rm -rf $(BUILD)
