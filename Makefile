# Thin wrapper: the real build is CMake + Ninja. Every target installs missing dependencies first.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
DEMO_OUT ?= demo-out

.PHONY: all deps configure build demo test bench format clean

all: build

deps:
	@./scripts/install-deps.sh

$(BUILD_DIR)/build.ninja: | deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)

configure: deps $(BUILD_DIR)/build.ninja

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

DATA ?= ../shared/data

# The main job on the built-in default: simulate an office, align it (pairs, every model,
# metrics, overlays), then show what real files look like to `info`.
demo: build
	./$(BUILD_DIR)/floorgrid demo --out $(DEMO_OUT)
	@if [ -d "$(DATA)" ]; then \
	  ./$(BUILD_DIR)/floorgrid info $(DATA)/bonn/GMap/GMap.yaml; \
	else echo "demo: $(DATA) is missing: no real files to show"; fi
	@echo "demo: results in $(DEMO_OUT)/align (metrics.json, model.json, overlays/)"

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

bench: build
	./scripts/run-benchmarks.sh $(BUILD_DIR)

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
