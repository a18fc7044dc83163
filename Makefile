# The two commands of the README: `make demo` and `make test`. Both install what is missing first.
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
CMAKE_GEN  := -G Ninja
DEMO_OUT   ?= demo-output

.PHONY: all deps configure build demo test test-release test-asan bench bench-dynamic fuzz clean

all: build

deps:
	@bash scripts/install-deps.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release

configure: $(BUILD)/build.ninja

build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	bash scripts/demo.sh $(BUILD)/tool/shoremesh $(DEMO_OUT)

# Release tests (ctest, every test), then the library suites again under AddressSanitizer + UBSan, with
# smaller sizes (SHOREMESH_SANITIZER_BUILD). SHOREMESH_SKIP_ASAN=1 skips that second stage.
ASAN_TESTS := shoremesh_engine_tests shoremesh_io_tests shoremesh_mesh_tests

test: test-release test-asan

test-release: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-asan: deps
	@if [ -n "$$SHOREMESH_SKIP_ASAN" ]; then echo "sanitizer run skipped (SHOREMESH_SKIP_ASAN set)"; else \
	  set -e; \
	  cmake -S . -B $(ASAN_BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHOREMESH_SANITIZE=ON -DSHOREMESH_BUILD_BENCH=OFF; \
	  cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(ASAN_TESTS); \
	  for t in $(ASAN_TESTS); do echo "== $$t (ASan + UBSan)"; \
	    SHOREMESH_SANITIZER_BUILD=1 ./$(ASAN_BUILD)/tests/$$t --gtest_brief=1 || exit 1; done; fi

bench: build
	bash bench/run.sh $(BUILD)

# The dynamic benchmark and its plot (bench/dynamic_speedup.png) need Debian's python3-matplotlib.
bench-dynamic: build
	@/usr/bin/python3 -c 'import matplotlib' 2>/dev/null || { apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-matplotlib; }
	/usr/bin/python3 bench/run_dynamic.py $(BUILD)

fuzz: deps
	bash scripts/fuzz.sh

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(DEMO_OUT)
