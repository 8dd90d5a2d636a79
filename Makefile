# libggx: the two commands of the README, and helpers. Everything real is in CMake.
BUILD ?= build
PYTHON ?= $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)
PREFIX ?= /usr/local
JOBS ?= 2
MAKEFLAGS += --no-print-directory

.PHONY: all deps deps-run deps-dev configure configure-run build run example bench bench-python test test-full test-long test-clang sanitize tsan tables \
        valgrind fuzz fuzz-ci install clean format format-check

all: build

# Debian packages: what `make run` needs (compiler, CMake, cairo and a font for the figures; libpng, libzip, libxml2 (and libcrypto, for x3p's MD5 checksums) and OpenEXR for the surfaces `ggx fit` reads, stb_image for the .hdr environments of `ggx render`, KISS FFT and Embree for the microsurfaces of `ggx microsurface` and their tracer), and what the test suite adds (cmocka, g++ for the
# header's C++ test, make for the install test, xmllint and poppler (pdfinfo) for the figures, groff for the man page,
# universal-ctags for the header index,
# Python with numpy, pytest and matplotlib for the Python package's tests and its example).
RUN_PKGS = cmake make gcc libc6-dev pkg-config libcairo2-dev fonts-dejavu-core libpng-dev libzip-dev libxml2-dev libssl-dev \
           libopenexr-dev libstb-dev libkissfft-dev libembree-dev
TEST_PKGS = $(RUN_PKGS) g++ clang libcmocka-dev libxml2-utils poppler-utils groff-base universal-ctags python3 \
            python3-numpy python3-pytest python3-matplotlib

deps:
	@sh cmake/install-deps.sh $(TEST_PKGS)

deps-run:
	@sh cmake/install-deps.sh $(RUN_PKGS)

# Tools for the robustness targets: clang with libFuzzer, valgrind.
deps-dev: deps
	@sh cmake/install-deps.sh clang libclang-rt-14-dev valgrind

CMAKE_CONFIG = -DCMAKE_BUILD_TYPE=Release -DGGX_WERROR=ON

configure: deps
	@cmake -S . -B $(BUILD) $(CMAKE_CONFIG) -DGGX_BUILD_TESTS=ON >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# Regenerates the shipped albedo tables (src/tables/albedo_iso.inc, src/tables/bsdf_iso.inc and
# src/tables/albedo_aniso.inc); a file is replaced only when the generator
# succeeds. tests/unit/tables_test.sh checks that a share of each file's lines regenerates bit for bit.
tables: deps-dev configure
	@cmake --build $(BUILD) -j $(JOBS) --target ggx_gen_tables
	@$(BUILD)/ggx_gen_tables > src/tables/albedo_iso.inc.tmp && mv src/tables/albedo_iso.inc.tmp src/tables/albedo_iso.inc
	@$(BUILD)/ggx_gen_tables --bsdf > src/tables/bsdf_iso.inc.tmp && mv src/tables/bsdf_iso.inc.tmp src/tables/bsdf_iso.inc
	@$(BUILD)/ggx_gen_tables --aniso > src/tables/albedo_aniso.inc.tmp && mv src/tables/albedo_aniso.inc.tmp src/tables/albedo_aniso.inc

# The main job on built-in defaults: the seeds' figures into out/ and a check of every sampler. It needs only the
# command: a first configure leaves the tests out (no cmocka needed); a build that has them keeps them.
configure-run: deps-run
	@cmake -S . -B $(BUILD) $(CMAKE_CONFIG) -DGGX_BUILD_TOOL=ON $(if $(wildcard $(BUILD)/CMakeCache.txt),,-DGGX_BUILD_TESTS=OFF) >/dev/null

run: configure-run
	@cmake --build $(BUILD) -j $(JOBS) --target ggx_tool
	@$(BUILD)/ggx demo

# Benchmarks: ns per call of every scalar function and batch kernel, ratios, and the machine's floors.
bench: build
	@$(BUILD)/ggx_bench
	@$(BUILD)/ggx_bench_fit
	@$(BUILD)/ggx_bench_filter
	@$(BUILD)/ggx_bench_microsurface
	@if [ -x $(BUILD)/ggx_bench_kirchhoff ]; then $(BUILD)/ggx_bench_kirchhoff; fi
	@$(BUILD)/ggx_bench_predict
	@if [ -x $(BUILD)/ggx ]; then for m in bumps checker scratches sawtooth; do \
	  $(BUILD)/ggx render --normal-map tests/data/normal_maps/$$m.png --alpha 0.1 --out $(BUILD)/normal-map-$$m.png; \
	  echo; done; fi
	@if [ -x $(BUILD)/ggx_bench_render ]; then $(BUILD)/ggx_bench_render; fi

# The Python package's overhead: ns per element and microseconds per call against its bare native loops.
bench-python: build
	@PYTHONPATH=$(BUILD)/python $(PYTHON) lab/bench/bench_python.py

# The small C example of the library (D, G1 and the BRDF for a skewed shape).
example: build
	@$(BUILD)/ggx_example

# The two tiers of the suite (docs/testing.md). make test: every function, sampler and variant, chi-square with its
# negative controls, on the quick tier's smaller sweeps (GGX_TEST_SCALE 0.2; the command's test without its
# chi-square minutes; the packaging test, a minute of CMake builds, runs in the full tier). make test-full: the full
# sweeps (scale 1), the command's audit and check runs and the packaging test included.
TEST_QUICK_SCALE = 0.2
test: build
	@cd $(BUILD) && GGX_TEST_SCALE=$(TEST_QUICK_SCALE) GGX_CLI_QUICK=1 ctest --output-on-failure -j $(JOBS) -E '^(consumer|install|header_matrix|cuda_compile)$$'

test-full: build
	@cd $(BUILD) && GGX_TEST_SCALE=1 ctest --output-on-failure -j $(JOBS)

# The property tests at ten times their size.
test-long: build
	@cd $(BUILD) && GGX_TEST_SCALE=10 ctest --output-on-failure -R robust

# The whole unit and property suite under AddressSanitizer + UndefinedBehaviorSanitizer (gcc), at a tenth of the
# sample counts (the install and consumer tests are left out: their programs are not built with the sanitizer runtime; so is
# the Python test: python3 would have to load the sanitizer runtime first).
SAN_FLAGS = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g
sanitize: deps
	@cmake -S . -B build-san -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGGX_WERROR=ON -DCMAKE_C_FLAGS="$(SAN_FLAGS)" \
	  -DCMAKE_CXX_FLAGS="$(SAN_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(SAN_FLAGS)" -DCMAKE_SHARED_LINKER_FLAGS="$(SAN_FLAGS)" >/dev/null
	@cmake --build build-san -j $(JOBS)
	@cd build-san && GGX_TEST_SCALE=0.1 GGX_CLI_QUICK=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/support/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) -E 'install|consumer|python'

# The batch tests under ThreadSanitizer (gcc; TSAN_CC=clang works too where its runtime is installed): batch calls
# from many threads, the first calls of a process included (tests/unit/test_batch_threads.c), must be free of data races.
TSAN_CC ?= gcc
TSAN_FLAGS = -fsanitize=thread -fno-omit-frame-pointer -g
# (no ifunc clones: their resolvers run during relocation, before the ThreadSanitizer runtime is up, and crash)
TSAN_CFLAGS = $(TSAN_FLAGS) -DGGX_NO_CLONES
tsan: deps
	@CC=$(TSAN_CC) cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGGX_WERROR=ON -DGGX_BUILD_TOOL=OFF \
	  -DGGX_BUILD_EXAMPLES=OFF -DCMAKE_C_FLAGS="$(TSAN_CFLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(TSAN_FLAGS)" \
	  -DCMAKE_SHARED_LINKER_FLAGS="$(TSAN_FLAGS)" >/dev/null
	@cmake --build build-tsan -j $(JOBS) --target test_batch test_batch_threads test_fit_threads test_parallel
	@cd build-tsan && GGX_TEST_SCALE=0.1 TSAN_OPTIONS=halt_on_error=1 ctest --output-on-failure -R '^(batch|fit_threads|parallel)'

# The whole build (library, command, tests, Python module) with clang and clang++, and the suite at a tenth of its
# sample counts: clang is a first-class compiler (the default build is gcc's).
test-clang: deps
	@CC=clang CXX=clang++ cmake -S . -B build-clang $(CMAKE_CONFIG) -DGGX_BUILD_TESTS=ON >/dev/null
	@cmake --build build-clang -j $(JOBS)
	@cd build-clang && GGX_REQUIRE_CLANG=1 GGX_TEST_SCALE=0.1 GGX_CLI_QUICK=1 ctest --output-on-failure -j $(JOBS) -E install

# The CLI tests with every ggx run under valgrind (memcheck, leak check); any error fails the test.
valgrind: deps-dev build
	@cd $(BUILD)/tests && GGX_CLI_QUICK=1 \
	  GGX_WRAP="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --suppressions=$(CURDIR)/tests/support/valgrind.supp" \
	  sh ../../tests/cli/cli_test.sh $(CURDIR)/$(BUILD)/ggx $(CURDIR)/$(BUILD)/tests/png_info
	@cd $(BUILD)/tests && \
	  GGX_WRAP="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --suppressions=$(CURDIR)/tests/support/valgrind.supp" \
	  sh ../../tests/cli/fit_cli_test.sh $(CURDIR)/$(BUILD)/ggx
	@cd $(BUILD)/tests && \
	  GGX_WRAP="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --suppressions=$(CURDIR)/tests/support/valgrind.supp" \
	  sh ../../tests/cli/mipmap_cli_test.sh $(CURDIR)/$(BUILD)/ggx
	@cd $(BUILD)/tests && \
	  GGX_WRAP="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --suppressions=$(CURDIR)/tests/support/valgrind.supp" \
	  sh ../../tests/cli/render_mip_test.sh $(CURDIR)/$(BUILD)/ggx
	@cd $(BUILD)/tests && \
	  GGX_WRAP="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --suppressions=$(CURDIR)/tests/support/valgrind.supp" \
	  sh ../../tests/cli/microsurface_cli_test.sh $(CURDIR)/$(BUILD)/ggx
	@cd $(BUILD)/tests && \
	  GGX_WRAP="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --suppressions=$(CURDIR)/tests/support/valgrind.supp" \
	  sh ../../tests/cli/predict_cli_test.sh $(CURDIR)/$(BUILD)/ggx

# The C style: .clang-format (120 columns). make format rewrites the sources, make format-check (in CI) fails on
# any that differ.
format:
	@sh cmake/install-deps.sh clang-format
	@sh cmake/format.sh fix

format-check:
	@sh cmake/install-deps.sh clang-format
	@sh cmake/format.sh check

# libFuzzer: each target for FUZZ_SECONDS (default 60) from the committed corpus; new inputs go to build-fuzz/.
FUZZ_SECONDS ?= 60
fuzz: deps-dev
	@CC=clang cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGGX_FUZZ=ON -DGGX_BUILD_TESTS=OFF \
	  -DGGX_BUILD_TOOL=OFF -DGGX_BUILD_EXAMPLES=OFF >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target fuzz_api fuzz_cli fuzz_surface
	@sh tests/fuzz/run.sh build-fuzz $(FUZZ_SECONDS)

# CI: each target briefly.
fuzz-ci:
	@$(MAKE) fuzz FUZZ_SECONDS=10

# Installs the ggx command and its man page, the library (shared and static), headers, pkg-config and CMake files
# under PREFIX; runs ldconfig where the loader searches the libdir (as root), or gives ggx.pc an rpath where it does
# not (cmake/install_loader.cmake). A configured build is only brought up to date (its options kept).
install:
	@if [ -f $(BUILD)/CMakeCache.txt ]; then cmake --build $(BUILD) -j $(JOBS); else $(MAKE) build; fi
	@cmake --install "$(BUILD)" --prefix "$(PREFIX)"

clean:
	rm -rf $(BUILD)
