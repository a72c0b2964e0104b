# Thin wrapper: the real build is CMake + Ninja. Every target installs missing dependencies first.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
DEMO_OUT ?= demo-out

FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
SANITIZE_DIR ?= build-sanitize

.PHONY: all deps deps-demo configure build demo test bench format clean fuzz sanitize python

all: build

CMAKE_CONFIGURE = cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
  -DPython_EXECUTABLE=/usr/bin/python3

deps:
	@./scripts/install-deps.sh

# Only what the floorgrid program needs: a fresh machine's first report waits for no test tool.
deps-demo:
	@./scripts/install-deps.sh --demo

# Everything configured: tests, benchmarks and the Python module. A build folder that `make demo`
# configured for the program alone gets them switched on here.
configure: deps
	@if [ ! -f $(BUILD_DIR)/build.ninja ] || \
	    grep -q '^FLOORGRID_BUILD_TESTS:BOOL=OFF' $(BUILD_DIR)/CMakeCache.txt; then \
	  $(CMAKE_CONFIGURE) -DFLOORGRID_BUILD_TESTS=ON -DFLOORGRID_BUILD_BENCH=ON \
	    -DFLOORGRID_PYTHON=ON; \
	fi

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

DATA ?= ../shared/data

# The main job on the built-in default: simulate an office, align it (pairs, every model,
# metrics, overlays), then show what real files look like to `info`. Only the floorgrid
# program is built, with only its own dependencies installed (not the test tools, tests and
# benchmarks the demo never runs); a new build folder is configured without them.
demo: deps-demo
	@if [ ! -f $(BUILD_DIR)/build.ninja ]; then \
	  $(CMAKE_CONFIGURE) -DFLOORGRID_BUILD_TESTS=OFF -DFLOORGRID_BUILD_BENCH=OFF \
	    -DFLOORGRID_PYTHON=OFF; \
	fi
	cmake --build $(BUILD_DIR) -j $(JOBS) --target floorgrid
	./$(BUILD_DIR)/floorgrid demo --out $(DEMO_OUT)
	@if [ -d "$(DATA)" ]; then \
	  ./$(BUILD_DIR)/floorgrid info $(DATA)/bonn/GMap/GMap.yaml; \
	else echo "demo: $(DATA) is missing: no real files to show"; fi
	@echo "demo: results in $(DEMO_OUT)/align (report.html, metrics.json, model.json, overlays/)"
	@echo "demo: browse them: ./$(BUILD_DIR)/floorgrid serve $(DEMO_OUT)/align --replay, then open http://127.0.0.1:8080/"

# The Python module `floorgrid` for Debian's /usr/bin/python3: built, then installed into
# /usr/local/lib/python3.X/dist-packages (on its path; `pip` is not needed).
PYTHON_PREFIX ?= /usr/local
python: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target floorgrid_python
	cmake --install $(BUILD_DIR) --component python --prefix $(PYTHON_PREFIX)
	cd / && /usr/bin/python3 -c "import floorgrid; print('import floorgrid:', floorgrid.__file__)"

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

bench: build
	./scripts/run-benchmarks.sh $(BUILD_DIR)

# Every parser fuzzed (libFuzzer, clang-16, ASan + UBSan) for FUZZ_SECONDS each on its seed corpus.
fuzz: deps
	cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-16 \
	  -DFLOORGRID_FUZZ=ON -DFLOORGRID_BUILD_TESTS=OFF -DFLOORGRID_BUILD_BENCH=OFF
	cmake --build $(FUZZ_DIR) -j $(JOBS)
	./scripts/run-fuzz.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (GCC).
# alloc_dealloc_mismatch=0: libdime (not ours, not instrumented) allocates an unknown DXF table's
# name with new[] and frees it with delete.
sanitize: deps
	cmake -S . -B $(SANITIZE_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DFLOORGRID_SANITIZE=ON -DFLOORGRID_BUILD_BENCH=OFF
	cmake --build $(SANITIZE_DIR) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:alloc_dealloc_mismatch=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --test-dir $(SANITIZE_DIR) --output-on-failure -j $(JOBS) $(SANITIZE_CTEST_ARGS)

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
