# rt_bushing -- top-level driver (GNU make). Everything is built with CMake:
#   make          configure + build Release into build/
#   make test     Release tests + symbol check, then an ASan/UBSan tree in build-asan/
#   make demo     build, then run `build/rtb demo`
#   make bench    build, then run the Google Benchmark suite (JSON in build/bench.json)
#   make report   build, then run `build/rtb report`
#   make acceptance  build, then `rtb diagnose` on records of the independent
#                 generator tests/refgen (table in build/acceptance/table.txt)
#   make clean    remove the build trees
# Every target except clean first checks the Debian packages it needs (deps).

SHELL       := bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := all
# The steps of one goal depend on each other's trees; keep them sequential.
.NOTPARALLEL:

JOBS      ?= 2
BUILD     ?= build
ASAN      ?= build-asan
CMAKE     ?= cmake
CTEST     ?= ctest
# cmake --build runs its own make; do not hand it our jobserver/flags.
SUBMAKE_ENV := env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL

DEB_PACKAGES := cmake g++ make libgtest-dev libbenchmark-dev libeigen3-dev \
                nlohmann-json3-dev gnuplot-nox

.PHONY: all deps configure build test test-release check-symbols test-asan \
        demo bench report acceptance clean

all: build

# ------------------------------------------------------------------ deps
# Only Debian packages are ever installed; nothing else is downloaded.
deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
	  if ! dpkg-query -W -f='$${Status}\n' "$$p" 2>/dev/null | grep -q '^install ok installed$$'; then \
	    missing="$$missing $$p"; \
	  fi; \
	done; \
	missing="$${missing# }"; \
	if [ -z "$$missing" ]; then exit 0; fi; \
	echo "missing Debian packages: $$missing"; \
	if [ "$$(id -u)" -eq 0 ]; then \
	  apt-get update; \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y $$missing; \
	else \
	  echo "sudo apt-get install -y $$missing"; \
	  exit 1; \
	fi

# ------------------------------------------------------------------ build
configure: deps
	$(CMAKE) -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: configure
	$(SUBMAKE_ENV) $(CMAKE) --build $(BUILD) --parallel $(JOBS)

# ------------------------------------------------------------------ tests
test: test-release check-symbols test-asan
	@echo "make test: all passed"

test-release: build
	cd $(BUILD) && $(CTEST) --output-on-failure --timeout 600 -j $(JOBS)

check-symbols: build
	bash tests/check_symbols.sh $(BUILD)/librt_bushing.a

# Sanitizer tree: AddressSanitizer (+LeakSanitizer) and UndefinedBehaviorSanitizer.
# RelWithDebInfo, but with -O1 -g1 instead of CMake's -O2 -g: the sanitized
# Eigen code of the offline tool compiles about twice as fast, and line tables
# are all the sanitizer stack traces need. Override with ASAN_OPT_FLAGS=.
ASAN_OPT_FLAGS ?= -O1 -g1 -DNDEBUG
test-asan: deps
	$(CMAKE) -S . -B $(ASAN) -DRTB_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DRTB_BUILD_BENCH=OFF \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(ASAN_OPT_FLAGS)" \
	  -DCMAKE_C_FLAGS_RELWITHDEBINFO="$(ASAN_OPT_FLAGS)"
	$(SUBMAKE_ENV) $(CMAKE) --build $(ASAN) --parallel $(JOBS)
	cd $(ASAN) && ASAN_OPTIONS=detect_leaks=1 \
	  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	  $(CTEST) --output-on-failure --timeout 900 -j $(JOBS)

# ------------------------------------------------------------------ tools
demo: build
	@if [ ! -x $(BUILD)/rtb ]; then echo "$(BUILD)/rtb was not built (offline/main.cpp missing?)"; exit 1; fi
	./$(BUILD)/rtb demo

# The real-data studies need the measured data next to the repository.
DATA_DIR ?= ../shared/data
report: build
	@if [ ! -x $(BUILD)/rtb ]; then echo "$(BUILD)/rtb was not built (offline/main.cpp missing?)"; exit 1; fi
	@if [ ! -d "$(DATA_DIR)" ]; then \
	  echo "make report: the measured data folder $(DATA_DIR) is missing."; \
	  echo "  It holds the friction-damper and VHB 4910 records (see docs/results/ for what they give)."; \
	  echo "  Put it there or run: make report DATA_DIR=/path/to/data"; exit 1; fi
	./$(BUILD)/rtb report --data-dir "$(DATA_DIR)" --out-dir docs/results

# `rtb diagnose` scored on records from the independent reference generator
# (tests/refgen/acceptance.sh; issue #10). 10-60 s per case: the quick set
# takes 10-20 min; ACCEPT_ARGS="--set all" runs every word on two seeds.
ACCEPT_ARGS ?= --set quick
acceptance: build
	bash tests/refgen/acceptance.sh --build $(BUILD) $(ACCEPT_ARGS)

bench: build
	@if [ ! -x $(BUILD)/bench/rtb_bench ]; then echo "$(BUILD)/bench/rtb_bench was not built (no bench/*_bench.cpp?)"; exit 1; fi
	./$(BUILD)/bench/rtb_bench --benchmark_out=$(BUILD)/bench.json --benchmark_out_format=json

clean:
	rm -rf $(BUILD) $(ASAN)
