# needlekit: the two set-up commands of the README.
#   make demo   install dependencies, build, run the main job on the built-in examples (results under out/)
#   make test   install dependencies, build, run the whole test suite through ctest
BUILD_DIR ?= build
JOBS ?= 2
CLI = $(BUILD_DIR)/bin/needlekit

.PHONY: all deps configure build demo test bench clean

all: build

deps:
	@./scripts/install-deps

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	@./scripts/demo $(CLI) out

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

bench: build
	@$(BUILD_DIR)/bin/needlekit_bench

clean:
	@rm -rf $(BUILD_DIR) out
