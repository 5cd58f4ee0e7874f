# The README's commands. Each installs missing dependencies first (scripts/install-deps.sh), so a
# fresh Debian 12 machine needs nothing else.
#   make demo    build, then run the whole pipeline on the bundled sample into demo-out/
#   make test    build, then run every test (unit, golden, interop) with CTest
#   make bench   build, then run the benchmarks (figures go to bench/RESULTS.md by hand)
BUILD_DIR ?= build
JOBS ?= 2
CMAKE_FLAGS ?=
# ccache: key entries by paths relative to the checkout, so every clone (CI's included) shares them.
export CCACHE_BASEDIR := $(CURDIR)
export CCACHE_NOHASHDIR := true

.PHONY: all deps configure build test demo bench clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_FLAGS) > $(BUILD_DIR).configure.log 2>&1 \
	  || (cat $(BUILD_DIR).configure.log; exit 1)

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

demo: build
	@scripts/demo.sh $(BUILD_DIR)/cli/cinepath demo-out

bench: build
	@scripts/bench.sh $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR) $(BUILD_DIR).configure.log demo-out
