# contact -- penalty contact kernels, driver, benchmarks and tests.
#
#   make            build libcontact, the driver, the tests
#   make run        run the showcase scene (SCENE=path for another)
#   make test       build and run the tests (Criterion)
#   make bench      build and run the benchmarks (Google Benchmark)
#   make bench-parts the narrow phase's parts timed each alone in L1
#   make check      tests under ASan+UBSan, then under ThreadSanitizer
#   make validation the validation cases with their plots (docs/VALIDATION.md)
#   make install    libcontact, its headers and contact.pc under PREFIX
#   make deps       install missing Debian packages (as root)
#
# Variables: CC=gcc|clang, PRECISION=double|single, ARCH=-march=native
# (ARCH= for portable binaries), BUILD=dir.

ifeq ($(origin CC),default)
CC = gcc
endif
PRECISION ?= double
ARCH ?= -march=native
CCNAME := $(notdir $(firstword $(CC)))
BUILD ?= build/$(CCNAME)-$(PRECISION)$(if $(strip $(ARCH)),,-portable)$(SAN_SUFFIX)

ifeq ($(PRECISION),single)
PREC_FLAGS = -DCT_SINGLE
else ifeq ($(PRECISION),double)
PREC_FLAGS =
else
$(error PRECISION must be double or single, not '$(PRECISION)')
endif

ifneq ($(findstring clang,$(CCNAME)),)
CXX_FOR_CC = clang++
else
CXX_FOR_CC = g++
endif
CXX := $(CXX_FOR_CC)

OPT ?= -O3
WARN = -Wall -Wextra -Werror
# -ffp-contract=off: no fused multiply-add unless written. gcc in ISO C mode
# already defaults to it; clang fuses by default, which (a) breaks the
# bit-for-bit agreement of the vector and one-pair predicates, whose loops
# it may fuse differently, and (b) moved three physics tests past their
# limits (TYPE7 squeeze, truss net energy, the stiffness trade).
CFLAGS_BASE = -std=c11 $(OPT) $(ARCH) -fno-math-errno -fno-trapping-math -ffp-contract=off -fopenmp $(WARN) -D_POSIX_C_SOURCE=200809L $(PREC_FLAGS)
CFLAGS_ALL = $(CFLAGS_BASE) $(SAN_FLAGS) $(EXTRA_CFLAGS)
# gcc only: the narrow phase's pair loops without partial redundancy
# elimination. Before if-conversion their selects are branches, and PRE
# copies the arithmetic that follows a select into its arms (a clamped
# weight times a coordinate becomes 0*a, 1*a and w*a, then a select), which,
# vectorised, costs extra products and blends and more live values than
# AVX2's 16 registers hold. The results are the same bit for bit; in
# alternating runs the 4-triangle kernel took 0.81-0.85 of the time and
# edge-edge 0.83-0.89; the contact cycle's change was within the host's
# noise (docs/DESIGN-CHANGES.md §6).
ifeq ($(findstring clang,$(CCNAME)),)
NARROW_CFLAGS = -fno-tree-pre
endif
NARROW_SRC := kernels/project.c kernels/project_tri.c kernels/project_quad.c \
              kernels/project_newton.c kernels/edge.c kernels/edge_block.c
# The flags of source file $(1) beyond CFLAGS_ALL.
src_cflags = $(if $(filter $(1),$(NARROW_SRC)),$(NARROW_CFLAGS))
# The narrow phase's block kernels: its vector loops, in files that use no
# OpenMP construct but simd. When CC is gcc they are compiled by clang
# (NARROW_CC) with -fopenmp-simd, which needs no OpenMP runtime: gcc 12's
# code for these loops ran 1.1-1.4x slower than clang 14's on this
# project's Zen 5 class host (BENCHMARKS.md). The loops use only +, -, *,
# /, sqrt and selects, without contraction (-ffp-contract=off) or libm
# calls, so both compilers' code gives the same bits. NARROW_CC=gcc (or
# NARROW_CC=$(CC)) compiles them with CC; so do sanitizer builds (one
# sanitizer runtime) and a machine without clang.
NARROW_VEC_SRC := kernels/project_tri.c kernels/project_quad.c kernels/project_newton.c \
                  kernels/edge_block.c
ifeq ($(origin NARROW_CC),undefined)
ifeq ($(findstring clang,$(CCNAME))$(SAN_SUFFIX),)
NARROW_CC := $(if $(shell command -v clang 2>/dev/null),clang)
endif
endif
NARROW_MIXED := $(if $(filter-out $(CC),$(or $(NARROW_CC),$(CC))),1)
NARROW_VEC_CFLAGS = $(filter-out -fopenmp,$(CFLAGS_ALL)) -fopenmp-simd
NARROW_CC_ID := $(if $(NARROW_MIXED),$(NARROW_CC) $(shell $(NARROW_CC) -dumpversion 2>/dev/null))
# The OpenMP runtime the programs link: OMPRT=llvm (LLVM's libomp, the
# default) or OMPRT=gnu (gcc's libgomp). gcc compiles OpenMP against
# libgomp's interface, which libomp implements as well (Debian's libomp5-14,
# from libomp-dev, which `make deps` installs for clang anyway); clang links
# libomp whatever OMPRT says. Why libomp: libgomp ends every barrier with a
# futex system call, waiters or not, and system calls are slow on this
# project's virtual machines. Measured with the two builds alternating
# (BENCHMARKS.md, floor/sync rows): a parallel region 1.24 us on one thread
# and 2.9 on two with libgomp, 0.12 and 1.6 with libomp; a barrier 1.20 and
# 1.48 against 0.01 and 0.88. A driver cycle runs about fifty of them, so
# the small and middle sizes gain: the showcase scene 1.13-1.16x, the
# searches on the Radioss decks 1.1-1.3x, kernels at 10^4 pairs up to
# 1.3x; at 10^5-10^6 nodes the two are within the host's noise. The
# results are the same bits: no kernel depends on the runtime's schedule
# (the tests check 1 against 2 threads; the clang builds always used
# libomp).
ifneq ($(findstring clang,$(CCNAME)),)
override OMPRT := llvm
endif
OMPRT ?= llvm
ifeq ($(OMPRT),llvm)
OMP_LIBS = $(if $(findstring clang,$(CCNAME)),,-l:libomp.so.5)
else ifneq ($(OMPRT),gnu)
$(error OMPRT must be llvm or gnu, not '$(OMPRT)')
endif
# A link: the compile flags, without -fopenmp (with which gcc links libgomp)
# when OMP_LIBS names the runtime; OMP_LIBS goes after the libraries.
OMP_LDFLAGS = $(if $(OMP_LIBS),,-fopenmp)
LINK_CFLAGS = $(filter-out -fopenmp,$(CFLAGS_ALL)) $(OMP_LDFLAGS)

GIT_COMMIT := $(shell git rev-parse --short=12 HEAD 2>/dev/null || echo none)$(shell git diff --quiet HEAD 2>/dev/null || echo -dirty)
PROV_FLAGS = $(strip $(CFLAGS_ALL))$(if $(NARROW_CFLAGS), (narrow phase: $(NARROW_CFLAGS)))$(if \
             $(NARROW_MIXED), (narrow-phase block kernels: $(NARROW_CC_ID) -fopenmp-simd)) (OpenMP \
             runtime: $(if $(filter llvm,$(OMPRT)),libomp,libgomp))
PROV = -DCT_BUILD_CFLAGS='"$(PROV_FLAGS)"' -DCT_BUILD_COMMIT='"$(GIT_COMMIT)"'
INC = -Ikernels -Idriver -Ibench

# Provenance is compiled into kernels/common.o: rebuild it whenever the commit
# or the flags change (a stamp file that is rewritten only when they differ).
PROV_STAMP := $(BUILD)/provenance.stamp
PROV_LINE := $(GIT_COMMIT) $(PROV_FLAGS)
$(shell mkdir -p $(BUILD) && (test -f $(PROV_STAMP) && [ "$$(cat $(PROV_STAMP))" = '$(PROV_LINE)' ] || echo '$(PROV_LINE)' > $(PROV_STAMP)))
# The narrow-phase objects are rebuilt when their own flags change.
NARROW_STAMP := $(BUILD)/narrow-flags.stamp
$(shell test -f $(NARROW_STAMP) && [ "$$(cat $(NARROW_STAMP))" = 'x$(NARROW_CFLAGS) $(NARROW_CC_ID)' ] || echo 'x$(NARROW_CFLAGS) $(NARROW_CC_ID)' > $(NARROW_STAMP))
$(NARROW_SRC:%.c=$(BUILD)/%.o): $(NARROW_STAMP)

PKGS_CFLAGS = $(shell pkg-config --cflags hwloc libcyaml criterion 2>/dev/null)
LIBS_HWLOC = $(shell pkg-config --libs hwloc 2>/dev/null || echo -lhwloc)
LIBS_CYAML = $(shell pkg-config --libs libcyaml 2>/dev/null || echo -lcyaml)
LIBS_CRIT = $(shell pkg-config --libs criterion 2>/dev/null || echo -lcriterion)
LIBS_BENCH = -lbenchmark -lpthread
# Peers (bench only): nanoflann and CGAL are header-only; Bullet's collision
# library (its headers as system headers, so their warnings are not ours).
PEER_CXXFLAGS = -isystem /usr/include/bullet
LIBS_PEERS = -lBulletCollision -lLinearMath

KERNEL_SRC := $(wildcard kernels/*.c)
DRIVER_SRC := $(filter-out driver/main.c,$(wildcard driver/*.c driver/*/*.c))
TEST_SRC := $(wildcard tests/*.c)
BENCH_C_SRC := $(wildcard bench/*.c)
BENCH_CXX_SRC := $(wildcard bench/*.cc)
BENCH_PEER_SRC := $(wildcard bench/peers/*.cc)

KERNEL_OBJ := $(KERNEL_SRC:%.c=$(BUILD)/%.o)
DRIVER_OBJ := $(DRIVER_SRC:%.c=$(BUILD)/%.o)
TEST_OBJ := $(TEST_SRC:%.c=$(BUILD)/%.o)
BENCH_OBJ := $(BENCH_C_SRC:%.c=$(BUILD)/%.o) $(BENCH_CXX_SRC:%.cc=$(BUILD)/%.o) \
             $(BENCH_PEER_SRC:%.cc=$(BUILD)/%.o)

EXAMPLE_SRC := $(wildcard examples/*.c)
EXAMPLES := $(EXAMPLE_SRC:examples/%.c=$(BUILD)/bin/example_%)

LIBCONTACT := $(BUILD)/libcontact.a
LIBDRIVER := $(BUILD)/libdriver.a
CONTACT := $(BUILD)/bin/contact
TESTS := $(BUILD)/bin/tests
BENCHBIN := $(BUILD)/bin/bench

# Debian packages the project needs (checked by `make deps`).
DEB_PKGS = pkg-config libhwloc-dev libbenchmark-dev libcriterion-dev libcyaml-dev libyaml-dev \
           libomp-dev clang libclang-rt-14-dev gnuplot-nox python3
ifneq ($(filter bench bench-full bench-test,$(MAKECMDGOALS)),)
DEB_PKGS += libnanoflann-dev libcgal-dev libbullet-dev
endif

.PHONY: all deps run test bench bench-full bench-test check check-asan check-tsan clean vecreport lib \
        validation install install-check examples

all: deps
	@$(MAKE) --no-print-directory build-all

.PHONY: build-all
build-all: $(LIBCONTACT) $(CONTACT) $(TESTS) $(EXAMPLES)

lib: $(LIBCONTACT)

deps:
	@missing=""; for p in $(DEB_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "deps: installing$$missing"; \
	    export DEBIAN_FRONTEND=noninteractive; \
	    apt-get update -qq && apt-get install -y -qq --no-install-recommends $$missing >/dev/null || \
	      { echo "deps: apt-get install$$missing failed"; exit 1; }; \
	  else \
	    echo "deps: missing Debian packages:$$missing"; \
	    echo "deps: run:  sudo apt-get install -y$$missing"; exit 1; \
	  fi; \
	fi

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(call src_cflags,$<) $(PROV) $(INC) $(PKGS_CFLAGS) -MMD -MP -c $< -o $@

# The block kernels with NARROW_CC (see NARROW_VEC_SRC). -fopenmp-simd
# ignores every other OpenMP construct, silently: a file that has one stops
# the build.
ifneq ($(NARROW_MIXED),)
$(NARROW_VEC_SRC:%.c=$(BUILD)/%.o): $(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	@! grep -nE 'omp +(parallel|for|task|taskloop|single|master|critical|atomic|barrier|sections)|CTI_PAR_FOR|omp_[a-z_]+ *\(' $< || \
	  { echo "$<: compiled by $(NARROW_CC) -fopenmp-simd, which would ignore the OpenMP above"; exit 1; }
	$(NARROW_CC) $(NARROW_VEC_CFLAGS) $(PROV) $(INC) -MMD -MP -c $< -o $@
endif

# The Bullet peer compiles to a stub that refuses to run when Bullet's
# headers are missing (bench/peers/bullet_peer.cc). A stub built before the
# package was installed must be rebuilt (the headers keep the package's own,
# older dates, so they cannot be the prerequisite): the object depends on a
# stamp whose name says whether the headers are there, created when that
# changes.
BULLET_STAMP := $(BUILD)/bench/peers/bullet-headers-$(if $(wildcard /usr/include/bullet/btBulletCollisionCommon.h),yes,no)
$(BULLET_STAMP):
	@mkdir -p $(dir $@) && rm -f $(BUILD)/bench/peers/bullet-headers-* && touch $@
$(BUILD)/bench/peers/bullet_peer.o: $(BULLET_STAMP)

$(BUILD)/%.o: %.cc
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 $(OPT) $(ARCH) -fopenmp -Wall -Wextra -Werror $(PREC_FLAGS) $(SAN_FLAGS) $(PROV) $(INC) $(PKGS_CFLAGS) $(PEER_CXXFLAGS) -MMD -MP -c $< -o $@

$(BUILD)/kernels/common.o: $(PROV_STAMP)

$(LIBCONTACT): $(KERNEL_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(LIBDRIVER): $(DRIVER_OBJ)
	@rm -f $@
	ar rcs $@ $^

LDLIBS_ALL = $(LIBS_CYAML) $(LIBS_HWLOC) -lm $(OMP_LIBS)

$(CONTACT): $(BUILD)/driver/main.o $(LIBDRIVER) $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CC) $(LINK_CFLAGS) $^ -o $@ $(LDLIBS_ALL)

# The test program sees the project's allocations (tests/alloc_fail.h):
# the linker sends the project's calls of these functions to wrappers that
# can make them fail.
WRAP_ALLOC = -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=aligned_alloc \
  -Wl,--wrap=strdup,--wrap=strndup,--wrap=free
$(TESTS): $(TEST_OBJ) $(LIBDRIVER) $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CC) $(LINK_CFLAGS) $(WRAP_ALLOC) $^ -o $@ $(LIBS_CRIT) $(LDLIBS_ALL)

# The examples use the public header alone (kernels/contact.h and the
# ct_*.h it includes); tests/test_examples.c runs them.
$(BUILD)/examples/%.o: examples/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -Ikernels -MMD -MP -c $< -o $@

$(BUILD)/bin/example_%: $(BUILD)/examples/%.o $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CC) $(LINK_CFLAGS) $^ -o $@ -lm $(OMP_LIBS)

examples: $(EXAMPLES)

$(BENCHBIN): $(BENCH_OBJ) $(LIBDRIVER) $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CXX) $(OPT) $(ARCH) $(OMP_LDFLAGS) $(SAN_FLAGS) $^ -o $@ $(LIBS_BENCH) $(LIBS_PEERS) $(LDLIBS_ALL)

# ---- User commands ----------------------------------------------------------

# SCENE=path runs another scene; `contact demo` shows the search comparison.
# The driver creates the output directory with its missing parents (out/ in
# a fresh checkout) and prints where it wrote.
SCENE ?= data/scenes/showcase.yaml
run: deps
	@$(MAKE) --no-print-directory $(CONTACT)
	$(CONTACT) run $(SCENE) --out out/$(basename $(notdir $(SCENE)))

# Criterion forks one process per test; tests set their own thread counts.
# Build, then run: two make calls, so that `make -j test` never starts the
# tests while their program is still being linked.
TEST_ARGS ?= --jobs 1
test: deps
	@$(MAKE) --no-print-directory build-tests
	@$(MAKE) --no-print-directory run-tests

# MESH=path adds a Radioss deck of yours to the real-mesh benchmarks.
# `make bench` runs the double-precision benchmarks, then the precision-
# sensitive ones (kernels, the precision trade row) in single precision,
# times the kernel rows of both builds in alternating rounds (the single
# build's speed-up, bench/interleave.py), compares the narrow phase of both
# builds on one case, and writes the
# Markdown tables (build/bench.md) and the plots (docs/*.png).
BENCH_ARGS ?=
BENCH_ENV = CT_SHARED=$(abspath ../shared) $(if $(MESH),CT_BENCH_MESH=$(abspath $(MESH)))
SINGLE_BUILD = build/$(CCNAME)-single$(if $(strip $(ARCH)),,-portable)
BENCH_SINGLE = $(SINGLE_BUILD)/bin/bench
BENCH_OUT = build/bench
bench: deps
	@$(MAKE) --no-print-directory $(BENCHBIN)
	@$(MAKE) --no-print-directory PRECISION=single $(BENCH_SINGLE)
	$(BENCH_ENV) $(BENCHBIN) --benchmark_out=$(BENCH_OUT).json $(BENCH_ARGS)
	$(BENCH_ENV) $(BENCH_SINGLE) --benchmark_filter='^(kernels/(narrow|force)|trade/precision)' \
	  --benchmark_out=$(BENCH_OUT)-single.json --benchmark_repetitions=3
	$(BENCH_ENV) python3 bench/interleave.py $(BENCHBIN) $(BENCH_SINGLE) --rounds 5 \
	  --filter '^kernels/(narrow/[a-z0-9]+|force/penalty\+coulomb-fused)/t1/(10000|1000000)/' \
	  --json $(BENCH_OUT)-interleaved.json
	$(BENCHBIN) --dump-narrow $(BENCH_OUT)-narrow-double.txt
	$(BENCH_SINGLE) --dump-narrow $(BENCH_OUT)-narrow-single.txt
	python3 bench/trade_precision.py $(BENCH_OUT)-narrow-double.txt $(BENCH_OUT)-narrow-single.txt \
	  --json $(BENCH_OUT)-precision.json
	python3 bench/report.py $(BENCH_OUT).json $(BENCH_OUT)-single.json $(BENCH_OUT)-precision.json \
	  $(BENCH_OUT)-interleaved.json > $(BENCH_OUT).md
	python3 bench/plots.py $(BENCH_OUT).json $(BENCH_OUT)-single.json --out docs/
	@awk '/^## Speed targets/ { p = 1 } p && /^# / { exit } p' $(BENCH_OUT).md
	@echo "bench: tables in $(BENCH_OUT).md, plots in docs/, raw results in $(BENCH_OUT)*.json"

bench-full: deps
	@$(MAKE) --no-print-directory $(BENCHBIN)
	$(BENCH_ENV) CT_BENCH_FULL=1 $(BENCHBIN) --benchmark_repetitions=3 --benchmark_out=$(BENCH_OUT)-full.json $(BENCH_ARGS)
	python3 bench/report.py $(BENCH_OUT)-full.json > $(BENCH_OUT)-full.md

# PNG plots in docs/ from the last bench run(s).
.PHONY: plots
plots:
	python3 bench/plots.py $(BENCH_OUT).json $(wildcard $(BENCH_OUT)-single.json) --out docs/

# The narrow phase taken apart: each part of a block's work (the block
# kernel, the copy of the coordinates, the gaps) alone on one block in L1
# (bench/parts/narrow_parts.c; docs/TARGETS.md quotes it). It reads the library's
# internal header, so it links the library of the same build (and the
# driver's for the benchmark's meshes); run it again with PRECISION=single
# for single precision.
PARTS_BIN = $(BUILD)/bin/narrow_parts
$(BUILD)/bench/parts/narrow_parts.o: bench/parts/narrow_parts.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(INC) -MMD -MP -c $< -o $@
$(PARTS_BIN): $(BUILD)/bench/parts/narrow_parts.o $(LIBDRIVER) $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CC) $(LINK_CFLAGS) $^ -o $@ -lm $(OMP_LIBS)
.PHONY: bench-parts
bench-parts: deps
	@$(MAKE) --no-print-directory $(PARTS_BIN)
	$(BENCH_ENV) $(PARTS_BIN)

# The harness's own correctness: every peer's pair set against the direct
# search on small meshes (no timing).
bench-test: deps
	@$(MAKE) --no-print-directory $(BENCHBIN)
	$(BENCHBIN) --verify-peers

# The validation cases of issue 6 (suites validation_*) again, recording
# their curves and figures, then the plots (docs/validation/*.png) and the
# results table of docs/VALIDATION.md. The assertions are the same as in
# `make test`, which runs these cases too.
VALID_OUT = build/validation
validation: deps
	@$(MAKE) --no-print-directory build-tests
	@rm -rf $(VALID_OUT) && mkdir -p $(VALID_OUT)
	CT_VALIDATION_OUT=$(abspath $(VALID_OUT)) CT_SHARED=$(abspath ../shared) \
	  $(TESTS) --jobs 1 --filter 'validation_*/*'
	python3 tests/validation_plots.py $(VALID_OUT) --out docs/validation --page docs/VALIDATION.md

# ---- Sanitizers -------------------------------------------------------------
# ASan+UBSan with gcc. The race check uses clang's ThreadSanitizer with LLVM's
# OpenMP runtime (libomp) and its Archer tool, which tells TSan about OpenMP's
# barriers, tasks and reductions, so there are no false reports from the
# runtime and no suppressions file.

ARCHER := $(firstword $(wildcard /usr/lib/llvm-14/lib/libarcher.so /usr/lib/llvm-*/lib/libarcher.so))

check: deps
	@$(MAKE) --no-print-directory check-asan
	@$(MAKE) --no-print-directory check-tsan
	@$(MAKE) --no-print-directory check-narrow-cc
	@$(MAKE) --no-print-directory install-check

# The narrow-phase block kernels compiled by NARROW_CC give the same bits as
# compiled by CC: tests/bits/narrow_bits.c hashes every output of every
# narrow kernel over 200000 random pairs (degenerate and NaN ones included),
# built both ways, in double and single precision; the outputs must match.
NARROW_BITS = bin/narrow_bits
$(BUILD)/$(NARROW_BITS): $(BUILD)/tests/bits/narrow_bits.o $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CC) $(LINK_CFLAGS) $^ -o $@ -lm $(OMP_LIBS)

.PHONY: check-narrow-cc
check-narrow-cc:
ifeq ($(NARROW_MIXED),)
	@echo "check-narrow-cc: the block kernels are compiled by $(CC) like the rest: nothing to compare"
else
	@set -e; for p in double single; do \
	  a=build/$(CCNAME)-$$p$(if $(strip $(ARCH)),,-portable); b=$$a-narrow-cc; \
	  $(MAKE) --no-print-directory PRECISION=$$p BUILD=$$a $$a/$(NARROW_BITS); \
	  $(MAKE) --no-print-directory PRECISION=$$p BUILD=$$b NARROW_CC=$(CC) $$b/$(NARROW_BITS); \
	  $$a/$(NARROW_BITS) 2>/dev/null > $$a/narrow_bits.txt; \
	  $$b/$(NARROW_BITS) 2>/dev/null > $$b/narrow_bits.txt; \
	  if cmp -s $$a/narrow_bits.txt $$b/narrow_bits.txt; then \
	    echo "check-narrow-cc: $$p: $(NARROW_CC) and $(CC) give the same bits ($$(wc -l < $$a/narrow_bits.txt) kernel runs)"; \
	  else \
	    echo "check-narrow-cc: $$p: the block kernels differ between $(NARROW_CC) and $(CC):"; \
	    diff $$a/narrow_bits.txt $$b/narrow_bits.txt; exit 1; \
	  fi; \
	done
endif

ASAN_MAKE = $(MAKE) --no-print-directory CC=gcc OPT=-O1 SAN_SUFFIX=-asan \
	  SAN_FLAGS="-g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer" \
	  TEST_ENV="ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 OMP_NUM_THREADS=2 CT_CHECK=1"
check-asan:
	@$(ASAN_MAKE) build-tests
	@$(ASAN_MAKE) run-tests

# Criterion cannot run under ThreadSanitizer (its boxfort arena fails to map:
# Snaipe/Criterion issue 274), so the race check is a program of its own,
# tests/race/race_check.c, that drives every parallel kernel with 2 threads
# and verifies the results against serial or direct references.
RACE_SRC := $(wildcard tests/race/*.c)
RACE_BIN := $(BUILD)/bin/race_check
$(RACE_BIN): $(RACE_SRC:%.c=$(BUILD)/%.o) $(LIBDRIVER) $(LIBCONTACT)
	@mkdir -p $(dir $@)
	$(CC) $(LINK_CFLAGS) $^ -o $@ $(LDLIBS_ALL)

check-tsan:
	@test -n "$(ARCHER)" || { echo "check-tsan: libarcher.so not found (package libomp-14-dev)"; exit 1; }
	@$(MAKE) --no-print-directory CC=clang OPT=-O1 SAN_SUFFIX=-tsan SAN_FLAGS="-g -fsanitize=thread" race-bin
	TSAN_OPTIONS="halt_on_error=1 ignore_noninstrumented_modules=1" OMP_NUM_THREADS=2 \
	  OMP_TOOL_LIBRARIES=$(ARCHER) CT_SHARED=$(abspath ../shared) \
	  build/clang-$(PRECISION)$(if $(strip $(ARCH)),,-portable)-tsan/bin/race_check

.PHONY: race-bin
race-bin: $(RACE_BIN)

.PHONY: build-tests run-tests
build-tests: $(TESTS) $(EXAMPLES) $(CONTACT)
# Criterion runs one test process per core, each with OpenMP threads: left
# to spin at barriers (the default policy), a process's waiting threads
# burn the cores the other needs. Passive waiting changes no result (every
# kernel is bit-identical for any schedule) and took the suite from 265 s
# to 52 s of wall time on 2 cores (2026-12-02).
TEST_OMP ?= OMP_WAIT_POLICY=passive
run-tests:
	$(TEST_ENV) $(TEST_OMP) CT_SHARED=$(abspath ../shared) $(TESTS) $(TEST_ARGS)

# Which loops the compiler vectorised, per kernel file: gcc's
# -fopt-info-vec-optimized, clang's loop-vectorize remarks (which name the
# line of the loop's pragma, or of the macro that holds the loop).
ifneq ($(findstring clang,$(CCNAME)),)
VEC_INFO = -Rpass=loop-vectorize
VEC_MATCH = [a-z_]*\.c:[0-9]*:[0-9]*: remark: vectorized loop[^[]*
else
VEC_INFO = -fopt-info-vec-optimized
VEC_MATCH = [a-z_]*\.c:[0-9]*:[0-9]*: optimized: loop vectorized.*
endif
# With NARROW_CC, its files are reported by clang.
CLANG_VEC_INFO = -Rpass=loop-vectorize
CLANG_VEC_MATCH = [a-z_]*\.c:[0-9]*:[0-9]*: remark: vectorized loop[^[]*
vec_by_narrow = $(and $(NARROW_MIXED),$(filter $(1),$(NARROW_VEC_SRC)))
vec_cmd = $(if $(call vec_by_narrow,$(1)),$(NARROW_CC) $(NARROW_VEC_CFLAGS) $(INC) $(CLANG_VEC_INFO),$(CC) \
          $(CFLAGS_ALL) $(call src_cflags,$(1)) $(INC) $(VEC_INFO))
vec_match = $(if $(call vec_by_narrow,$(1)),$(CLANG_VEC_MATCH),$(VEC_MATCH))
vecreport: deps
	@$(foreach f,$(KERNEL_SRC),echo "== $(f)$(if $(call vec_by_narrow,$(f)), ($(NARROW_CC)))"; \
	  $(call vec_cmd,$(f)) -c $(f) -o /dev/null > $(BUILD)/vecreport.log 2>&1 || \
	    { cat $(BUILD)/vecreport.log; exit 1; }; \
	  grep -o '$(call vec_match,$(f))' $(BUILD)/vecreport.log | sort -u;)

# ---- Installation -------------------------------------------------------------
# The static library, the public headers (in include/contact/) and a
# pkg-config file whose flags carry the precision the library was built
# with (a program compiled without -DCT_SINGLE against the single-precision
# library would read floats as doubles). The library is built for this
# machine's processor unless ARCH= (portable).
PREFIX ?= /usr/local
PUBLIC_HEADERS := kernels/contact.h kernels/ct_search.h kernels/ct_narrow.h kernels/ct_force.h \
                  kernels/ct_friction.h kernels/ct_assemble.h kernels/ct_timestep.h
install: deps
	@$(MAKE) --no-print-directory $(LIBCONTACT)
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/contact
	install -m 644 $(LIBCONTACT) $(DESTDIR)$(PREFIX)/lib/libcontact.a
	install -m 644 $(PUBLIC_HEADERS) $(DESTDIR)$(PREFIX)/include/contact/
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$${prefix}/lib' 'includedir=$${prefix}/include' '' \
	  'Name: contact' \
	  'Description: penalty contact kernels for explicit finite-element dynamics ($(PRECISION) precision)' \
	  'Version: $(GIT_COMMIT)' \
	  'Cflags: -I$${includedir}/contact -fopenmp $(PREC_FLAGS)' \
	  'Libs: -L$${libdir} -lcontact -fopenmp -lm' > $(DESTDIR)$(PREFIX)/lib/pkgconfig/contact.pc

# What a user of the installed library does: the example compiled against
# the installed headers and contact.pc alone, run, its verification passed.
INSTALL_CHECK = $(abspath $(BUILD)/install-check)
install-check:
	@rm -rf $(INSTALL_CHECK)
	@$(MAKE) --no-print-directory install PREFIX=$(INSTALL_CHECK) >/dev/null
	PKG_CONFIG_PATH=$(INSTALL_CHECK)/lib/pkgconfig $(CC) -std=c11 -O2 -Wall -Wextra -Werror \
	  examples/slide.c $$(PKG_CONFIG_PATH=$(INSTALL_CHECK)/lib/pkgconfig pkg-config --cflags --libs contact) \
	  -o $(INSTALL_CHECK)/slide
	$(INSTALL_CHECK)/slide
	@if $(CC) -std=c11 examples/slide.c -I$(INSTALL_CHECK)/include/contact -fopenmp \
	    $(if $(PREC_FLAGS),,-DCT_SINGLE) -L$(INSTALL_CHECK)/lib -lcontact -lm \
	    -o $(INSTALL_CHECK)/other-precision 2>$(INSTALL_CHECK)/other-precision.log; then \
	  echo "install-check: a program of the other precision linked against the library"; exit 1; \
	fi; grep -q "undefined reference to .ct_library_is_" $(INSTALL_CHECK)/other-precision.log || \
	  { cat $(INSTALL_CHECK)/other-precision.log; exit 1; }; \
	echo "install-check: a program of the other precision is refused at link time"

clean:
	rm -rf build

-include $(shell find build -name '*.d' 2>/dev/null)
