# Two commands: `make run` opens the editor, `make test` runs every test. Both set everything up.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: run test bench deps build clean sanitize fuzz tsan
FUZZ_SECONDS ?= 60

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/app/sylva $(PRESET)

# The fuzz part: 20 s per harness when clang is installed, skipped with a message otherwise.
test: build
	@bash scripts/run-tests.sh $(BUILD)
	@bash tests/fuzz/run-fuzz.sh build-fuzz 20 --if-clang

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

# libFuzzer harnesses (tests/fuzz/) with clang, ASan and UBSan, FUZZ_SECONDS each.
fuzz: deps
	@bash scripts/install-deps.sh --fuzz
	@bash tests/fuzz/run-fuzz.sh build-fuzz $(FUZZ_SECONDS)

# ThreadSanitizer over the core, the mesher and the growth worker: the worker tests and a stress test.
tsan: deps
	@cmake -S . -B build-tsan -DSYLVA_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	@cmake --build build-tsan -j $(JOBS) --target sylva_worker_tests
	TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 ./build-tsan/tests/sylva_worker_tests

clean:
	rm -rf $(BUILD)
