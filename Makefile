# rt_bushing -- top-level driver (GNU make). Everything is built with CMake:
#   make          configure + build Release into build/
#   make test     Release tests + symbol check, then an ASan/UBSan tree in build-asan/
#                 (the long tier excluded: ctest -LE long)
#   make test-long  the long tier: end-to-end diagnoses of more than ~25 s
#                 each (tests/CMakeLists.txt), Release, ~17 min on 2 cores
#   make demo     build, then run `build/rtb demo`
#   make bench    build, then run the Google Benchmark suite (JSON in build/bench.json)
#   make report   build, then run `build/rtb report`
#   make embedded cross-compile for a Cortex-M4F, print size and stack, run a
#                 test firmware in QEMU (installs its own Debian packages;
#                 not needed by make test)
#   make fuzz     libFuzzer targets (clang-14) for FUZZ_SECONDS each, in build-fuzz/
#   make fmu      build/fmu/rt_bushing.fmu, FMI 2.0 co-simulation (PARAMS=FILE: a specific bushing)
#   make acceptance  build, then `rtb diagnose` on records of the independent
#                 generator tests/refgen (table in build/acceptance/table.txt)
#   make blind    build, then `rtb diagnose` on records of the blind generator
#                 tests/blindgen (Python with numpy and scipy, in deps)
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
                nlohmann-json3-dev gnuplot-nox zip unzip libxml2-dev \
                python3 python3-numpy python3-scipy
# Only `make fuzz` needs clang and libFuzzer; `make test` replays the seed
# corpus with the gcc build instead (fuzz/CMakeLists.txt).
FUZZ_PACKAGES := cmake make clang-14 libfuzzer-14-dev nlohmann-json3-dev

# make embedded only (issue #11): cross toolchain, newlib, the QEMU board.
EMBEDDED_PACKAGES := gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm python3

.PHONY: all deps fuzz-deps deps-embedded configure build test test-release test-long check-symbols \
        check-host-builds test-asan demo bench report embedded fuzz fmu acceptance blind clean

all: build

# ------------------------------------------------------------------ deps
# Only Debian packages are ever installed; nothing else is downloaded.
# $(call ensure_packages,LIST): install what is missing (root) or say how.
define ensure_packages
	@missing=""; \
	for p in $(1); do \
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
endef

deps:
	$(call ensure_packages,$(DEB_PACKAGES))

fuzz-deps:
	$(call ensure_packages,$(FUZZ_PACKAGES))

deps-embedded:
	$(call ensure_packages,$(EMBEDDED_PACKAGES))

# ------------------------------------------------------------------ build
# The bushing compiled into the FMU: empty = the paper's section 3.4 set on
# every axis; else a six-axis JSON, a single-axis JSON (all six axes) or a
# header written by `rtb header` (its constant named after the file). Passed
# on every configure, so a plain `make test` goes back to the default.
PARAMS ?=
configure: deps
	$(CMAKE) -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release \
	  -DRTB_FMU_PARAMS="$(if $(PARAMS),$(abspath $(PARAMS)))"

build: configure
	$(SUBMAKE_ENV) $(CMAKE) --build $(BUILD) --parallel $(JOBS)

# ------------------------------------------------------------------ tests
test: test-release check-symbols check-host-builds test-asan
	@echo "make test: all passed"

test-release: build
	cd $(BUILD) && $(CTEST) --output-on-failure --timeout 600 -j $(JOBS) -LE long

test-long: build
	cd $(BUILD) && $(CTEST) --output-on-failure --timeout 900 -j $(JOBS) -L long

check-symbols: build
	bash tests/check_symbols.sh $(BUILD)/librt_bushing.a

# The library (double and float) under a host's flags and compilers: GCC at
# -O3 -march=x86-64-v4, Clang at -O3 if installed (~30 s; the script says why).
check-host-builds: deps
	JOBS=$(JOBS) CMAKE=$(CMAKE) bash tests/check_host_builds.sh

# Sanitizer tree: AddressSanitizer (+LeakSanitizer) and UndefinedBehaviorSanitizer.
# RelWithDebInfo, but with -O1 -g1 instead of CMake's -O2 -g: the sanitized
# Eigen code of the offline tool compiles about twice as fast, and line tables
# are all the sanitizer stack traces need. Override with ASAN_OPT_FLAGS=.
ASAN_OPT_FLAGS ?= -O1 -g1 -DNDEBUG
test-asan: deps
	$(CMAKE) -S . -B $(ASAN) -DRTB_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DRTB_BUILD_BENCH=OFF -DRTB_FMU_PARAMS= \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(ASAN_OPT_FLAGS)" \
	  -DCMAKE_C_FLAGS_RELWITHDEBINFO="$(ASAN_OPT_FLAGS)"
	$(SUBMAKE_ENV) $(CMAKE) --build $(ASAN) --parallel $(JOBS)
	cd $(ASAN) && ASAN_OPTIONS=detect_leaks=1 \
	  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	  $(CTEST) --output-on-failure --timeout 900 -j $(JOBS) -LE long

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

# The blind generator (tests/blindgen; issue #10): written from the paper and
# the CLI's help only, with its own effect definitions and rig conventions.
# 10-60 s per case (generation included); the default, 24 cases on each of
# two seeds, takes 20-40 min. Table in build/blind/ (score_blind.py).
BLIND_ARGS ?= --set all --seeds "1 2"
blind: build
	bash tests/blindgen/run_blind.sh --build $(BUILD) --out $(BUILD)/blind $(BLIND_ARGS)

bench: build
	@if [ ! -x $(BUILD)/bench/rtb_bench ]; then echo "$(BUILD)/bench/rtb_bench was not built (no bench/*_bench.cpp?)"; exit 1; fi
	./$(BUILD)/bench/rtb_bench --benchmark_out=$(BUILD)/bench.json --benchmark_out_format=json

# ------------------------------------------------------------------ embedded
# Cortex-M4F single-precision build, size, stack depth, QEMU test firmware
# (embedded/Makefile says what each step does). Output in build-embedded/.
embedded: deps-embedded
	$(SUBMAKE_ENV) $(MAKE) -C embedded OUT=$(CURDIR)/build-embedded

# ------------------------------------------------------------------ fuzzing
# Each target runs FUZZ_SECONDS from the seed corpus fuzz/corpus/<target>/
# (read only); new inputs go to $(FUZZ)/corpus/<target>/, crashes to
# $(FUZZ)/artifacts/. A crash stops make with the reproducer's path:
# turn it into a regression test (tests/*_test.cpp) and add it to the corpus.
FUZZ         ?= build-fuzz
FUZZ_SECONDS ?= 30
FUZZ_TARGETS := csv_reader params_json stepper
fuzz: fuzz-deps
	$(CMAKE) -S . -B $(FUZZ) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DRTB_FUZZ=ON \
	  -DRTB_BUILD_TESTS=OFF -DRTB_BUILD_BENCH=OFF -DRTB_BUILD_OFFLINE=OFF
	$(SUBMAKE_ENV) $(CMAKE) --build $(FUZZ) --parallel $(JOBS)
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ)/corpus/$$t $(FUZZ)/artifacts; \
	  echo "== fuzz $$t for $(FUZZ_SECONDS) s"; \
	  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	  ./$(FUZZ)/fuzz/$${t}_fuzz -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ)/artifacts/$$t- $(FUZZ)/corpus/$$t fuzz/corpus/$$t \
	    2> $(FUZZ)/$$t.log || { tail -n 40 $(FUZZ)/$$t.log; exit 1; }; \
	  grep -E '^stat::(number_of_executed_units|new_units_added)' $(FUZZ)/$$t.log | tr '\n' ' '; echo; \
	done
	@echo "make fuzz: $(words $(FUZZ_TARGETS)) targets, $(FUZZ_SECONDS) s each, no crash"
# FMI 2.0 co-simulation FMU (zip from Debian; see README "Importing the FMU").
fmu: configure
	$(SUBMAKE_ENV) $(CMAKE) --build $(BUILD) --parallel $(JOBS) --target fmu
	@echo "built $(BUILD)/fmu/rt_bushing.fmu$(if $(PARAMS), with $(PARAMS))"

clean:
	rm -rf $(BUILD) $(ASAN) $(FUZZ) build-embedded
