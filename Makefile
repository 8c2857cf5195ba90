# Thin wrapper around CMake presets; see README.md.
BUILD_DIR ?= build
PRESET    ?= default
JOBS      ?= $(shell nproc)
ROTORD_ARGS ?= --sim g5500

.PHONY: all deps build run test bench embedded format format-check clean

all: build

deps:
	@./scripts/install-deps.sh --with-web

build: deps
	@cmake --preset $(PRESET) >/dev/null
	@cmake --build --preset $(PRESET) -j $(JOBS)

run: build
	./$(BUILD_DIR)/rotord $(ROTORD_ARGS)

test: build
	@./scripts/check-format.sh
	ctest --preset $(PRESET) -j $(JOBS)

bench: build
	@cmake --build --preset $(PRESET) --target benchmarks -j $(JOBS)
	./$(BUILD_DIR)/bench/rotord_bench

embedded: deps
	@cmake --preset embedded >/dev/null
	@cmake --build --preset embedded -j $(JOBS)
	ctest --preset embedded

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) build-embedded
