# Thin wrapper: install what is missing, configure, build, then run the main job or the tests.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
# lavapipe warns about a missing runtime dir without this; the validation layer is found by the loader.
export XDG_RUNTIME_DIR ?= /tmp

.PHONY: all deps configure build run test bench clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	@$(BUILD_DIR)/hmblur demo --out-dir out

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The benchmark suites at a reduced size (about a minute on 2 cores); full runs and their
# commands: bench/README.md and bench/results/.
BENCH_OUT ?= out/bench
PYTHON ?= /usr/bin/python3
bench: build
	@mkdir -p $(BENCH_OUT)/passes $(BENCH_OUT)/error-vs-time $(BENCH_OUT)/error-explanation
	@$(BUILD_DIR)/hmblur-bench passes --sizes 160x90,320x180 --out $(BENCH_OUT)/passes/passes.json > /dev/null
	@$(BUILD_DIR)/hmblur-bench error-vs-time --size 160x90 --judge-spp 256 --reference-spp 1,2,4,8,16,32 \
	    --out $(BENCH_OUT)/error-vs-time/error-vs-time.json > /dev/null
	@$(PYTHON) bench/scripts/plot_error_vs_time.py $(BENCH_OUT)/error-vs-time/error-vs-time.json
	@$(BUILD_DIR)/hmblur-bench explain --size 160x90 --reference-spp 64 \
	    --out $(BENCH_OUT)/error-explanation/explanation.json > /dev/null
	@echo "bench: results in $(BENCH_OUT)/passes, $(BENCH_OUT)/error-vs-time and $(BENCH_OUT)/error-explanation"

clean:
	rm -rf $(BUILD_DIR) out
