# The two commands of the README: `make run` and `make test`. Both install missing Debian
# packages, configure a Release build in build/ and build it: `make run` the libraries and the
# mote tool, all `cmake --install build` needs (scripts/install-deps run: no test, benchmark,
# Python or browser packages), `make test` everything. Plain CMake works too (README).

BUILD       ?= build
JOBS        ?= $(shell nproc)
CMAKE_FLAGS ?=
CTEST_ARGS  ?=
FUZZ_SECONDS ?= 30
# What `make test` builds besides the libraries and the tool (`make run` turns them off).
EVERYTHING  := -DMOTE_BUILD_TESTS=ON -DMOTE_BUILD_BENCH=ON -DMOTE_BUILD_EXAMPLES=ON

.PHONY: all deps deps-run configure build run test bench fuzz tsan clean

all: build

deps:
	@scripts/install-deps

deps-run:
	@scripts/install-deps run

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(EVERYTHING) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: deps-run
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DMOTE_BUILD_TESTS=OFF \
	  -DMOTE_BUILD_BENCH=OFF -DMOTE_BUILD_EXAMPLES=OFF $(CMAKE_FLAGS)
	cmake --build $(BUILD) -j $(JOBS)
	$(BUILD)/tool/mote run

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) $(CTEST_ARGS)

# `make bench`: the default (portable, run-time dispatched) Release build in build-bench/
# (CMAKE_FLAGS=-DMOTE_NATIVE=ON for -march=native), every benchmark suite with
# medians of 3 repetitions into bench/results/<suite>.json, then bench/plot.py writes the
# end-to-end table (e2e.md) and plot (e2e.png), and bench/python/bench_python.py (the Python
# package's overhead) into python.json. BENCH_FILTER (a regex) runs a subset.
BENCH_BUILD  ?= build-bench
BENCH_DATA   ?= ../shared/data
BENCH_SUITES ?= bench_e2e bench_engine bench_maps bench_raycast
BENCH_FILTER ?= .
BENCH_REPS   ?= 3
BENCH_OUT    := bench/results
# The Debian interpreter, which python3-matplotlib (scripts/install-deps) installs into.
BENCH_PYTHON ?= $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)

bench: deps
	cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)
	cmake --build $(BENCH_BUILD) -j $(JOBS) --target $(BENCH_SUITES)
	mkdir -p $(BENCH_OUT)
	uptime > $(BENCH_OUT)/uptime.txt
	git describe --always --dirty > $(BENCH_OUT)/version.txt 2>/dev/null || echo unknown > $(BENCH_OUT)/version.txt
	set -e; for suite in $(BENCH_SUITES); do \
	  rm -f $(BENCH_OUT)/$$suite.json; \
	  exe=$$(find $(BENCH_BUILD)/bench -name $$suite -type f -perm -u+x | head -n 1); \
	  $$exe --benchmark_filter='$(BENCH_FILTER)' \
	    --benchmark_repetitions=$(BENCH_REPS) --benchmark_report_aggregates_only=true \
	    --benchmark_out=$(BENCH_OUT)/$$suite.json --benchmark_out_format=json; \
	done
	uptime >> $(BENCH_OUT)/uptime.txt
	$(BENCH_PYTHON) bench/plot.py $(BENCH_OUT)
	@if grep -q '^MOTE_BUILD_PYTHON:BOOL=ON' $(BENCH_BUILD)/CMakeCache.txt; then \
	  cmake --build $(BENCH_BUILD) -j $(JOBS) --target mote_python && \
	  PYTHONPATH=$(BENCH_BUILD)/python $(BENCH_PYTHON) bench/python/bench_python.py \
	    $(BENCH_DATA) $(BENCH_OUT)/python.json; \
	else echo "bench: Python package not built (MOTE_BUILD_PYTHON off): bench_python.py skipped"; fi

# Every reader's libFuzzer target for FUZZ_SECONDS each, JOBS at a time, under ASan + UBSan, in
# build-fuzz (clang); fails on any finding. The corpus grows in build-fuzz/fuzz-corpus between runs.
fuzz: deps
	cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
	  -DMOTE_BUILD_FUZZERS=ON -DMOTE_BUILD_TESTS=OFF -DMOTE_BUILD_BENCH=OFF \
	  -DMOTE_BUILD_EXAMPLES=OFF -DMOTE_BUILD_TOOL=OFF -DMOTE_NATIVE=OFF $(CMAKE_FLAGS)
	cmake --build build-fuzz -j $(JOBS) --target fuzzers
	FUZZ_JOBS=$(JOBS) tests/fuzz/run-fuzzers build-fuzz $(FUZZ_SECONDS)

# The engine and Localizer tests under ThreadSanitizer (clang) in build-tsan; see .ci/tsan.
tsan: deps
	.ci/tsan

clean:
	rm -rf $(BUILD)
