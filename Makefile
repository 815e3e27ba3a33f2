# needlekit: the two set-up commands of the README.
#   make demo   install dependencies, build, run the main job (`needlekit reproduce`, the full run) on the built-in
#               examples: out/report.html and the data and figures under out/ (`make demo-quick`: the quick run)
#   make test   install dependencies, build, run the whole test suite through ctest
BUILD_DIR ?= build
JOBS ?= 2
CLI = $(BUILD_DIR)/bin/needlekit

.PHONY: all deps configure build demo demo-quick test bench clean

all: build

deps:
	@./scripts/install-deps

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	@./scripts/demo $(CLI) out

demo-quick: build
	@./scripts/demo $(CLI) out --quick

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

bench: build
	@$(BUILD_DIR)/bin/needlekit_bench

clean:
	@rm -rf $(BUILD_DIR) out
