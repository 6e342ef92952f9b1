# filigree — header-only C toolkit. GNU make.
#
#   make demo            render the gallery into out/ (installs Debian packages as root)
#   make test            header matrix + every test, normal and under ASan+UBSan,
#                        the interval and rounded-edge tests (and four of frep
#                        and grooves) again built by clang;
#                        also builds the examples, and the benchmarks and
#                        fingerprint programs at -O0 into build/check (not run)
#   make check-headers   the header compile matrix only
#   make bench           error-against-time tables, CSV in out/bench, plots in docs/img
#   make fuzz            long libFuzzer runs (FUZZ_SECONDS=600)
#   make fuzz-fast       the same without ASan/UBSan at -O2: about 9x the runs a
#                        second for the targets that check answers
#   make coverage        the header lines no test runs (gcc --coverage; MODULES=rounded ...)
#   make fingerprint     every header's answers hashed bit for bit: diff before/after a refactor
#   make install PREFIX=/usr/local    headers + filigree.pc
#   make clean
#
# Tests, benchmarks and examples are found by name (docs/conventions.md):
#   tests/test_*.c|cpp, bench/bench_*.c|cpp, examples/<name>/*.c|cpp.

CC      ?= gcc
CXX     ?= g++
PREFIX  ?= /usr/local
B       := build
NPROC   := $(shell nproc 2>/dev/null || echo 2)
OPT     ?= -O2 -march=native
# line tables only: enough for sanitizer and perf backtraces, and a quarter
# of the compile time of -g (make DBG=-g for a debugger's variables)
DBG     ?= -g1
WARN    := -Wall -Wextra -Werror -Wno-unused-function
# -ffp-contract=fast is gcc's default in GNU mode; we state it so the tests
# prove the headers survive contraction of a*b+c into fma (clang's test
# build turns it off again: CLANG_UNFUSED).
CFLAGS_ALL   := $(OPT) $(DBG) -ffp-contract=fast -Iinclude -Itests -Iexamples/common $(WARN)
TEST_CFLAGS  := -std=gnu11 $(CFLAGS_ALL)
TEST_CXXFLAGS:= -std=gnu++17 $(CFLAGS_ALL)
SAN_FLAGS    := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# the sanitizer build's optimisation: -Og compiles in half -O1's time (the
# san tree was a third of make test's compile time) and runs about as fast
SAN_OPT      := -Og
LDLIBS_ALL   := -Wl,--as-needed -lembree3 -lquadmath -lpthread -lm
EX_LDLIBS    := -Wl,--as-needed -lOpenImageIO -lOpenImageIO_Util -lembree3 -lpthread -lm
BENCH_LDLIBS := -Wl,--as-needed -lOpenImageIO -lOpenImageIO_Util -lembree3 -lgsl -lgslcblas -lquadmath -lpthread -lm

HEADERS  := $(wildcard include/*.h)
TEST_C   := $(wildcard tests/test_*.c)
TEST_CPP := $(wildcard tests/test_*.cpp)
TESTS    := $(patsubst tests/%.c,$(B)/tests/%,$(TEST_C)) $(patsubst tests/%.cpp,$(B)/tests/%,$(TEST_CPP))
SAN_TESTS:= $(patsubst $(B)/tests/%,$(B)/san/%,$(TESTS))
FUZZERS  := $(patsubst tests/%.c,$(B)/fuzz/%,$(wildcard tests/fuzz_*.c))
# the interval and rounded-edge tests again, built by clang, and the frep and
# grooves tests that hold answers to bounds against independent references
# (the rest of theirs passed under clang at full scale on 2026-12-05, and
# unfused on 2026-12-07, by hand): the bounds must hold under its code
# generation, unfused (below)
CLANG_TESTS := $(patsubst tests/%.c,$(B)/clang/%,$(wildcard tests/test_interval*.c tests/test_rounded*.c) \
               tests/test_frep_interval.c tests/test_frep_solve.c tests/test_frep_trace.c tests/test_grooves_oracle.c)
# clang builds the headers and its tests unfused: gcc's two builds fuse
# a*b+c (as -march=native hosts do), clang's rounds every product (as
# baseline x86-64 hosts and the fuzzers do), so every bound of the clang
# tests is checked both ways at no extra build
CLANG_UNFUSED := -ffp-contract=off
# GCC's own headers (quadmath.h for the __float128 references), searched
# after clang's
GCC_INCLUDE := $(shell gcc -print-file-name=include)
TEST_DEPS:= $(HEADERS) $(wildcard tests/*.h)
# Each header's implementation is compiled once per test build (normal,
# ASan+UBSan, clang) into build/impl/<build>/libfiligree.a, one member per
# header (tests/impl/*.c). A test that does not define XX_IMPLEMENTATION
# links it from there; one that needs its own copy (XX_NO_* switches,
# allocator hooks, the xx__ internals) defines it and takes nothing from
# that member. Compiling every implementation into every test was two
# thirds of make test's compile time.
IMPL_NAMES := $(basename $(notdir $(wildcard tests/impl/*.c)))
IMPL_OBJS  := $(foreach f,tests san clang,$(foreach n,$(IMPL_NAMES),$(B)/impl/$(f)/$(n).o) $(B)/impl/$(f)/libfiligree.a)

BENCH_C  := $(wildcard bench/bench_*.c)
BENCH_CPP:= $(wildcard bench/bench_*.cpp)
BENCHES  := $(patsubst bench/%.c,$(B)/bench/%,$(BENCH_C)) $(patsubst bench/%.cpp,$(B)/bench/%,$(BENCH_CPP))

# an example is a folder under examples/ with C or C++ sources (models/ holds data)
EX_NAMES := $(filter-out common,$(notdir $(patsubst %/,%,$(dir $(wildcard examples/*/*.c examples/*/*.cpp)))))
EX_NAMES := $(sort $(EX_NAMES))
EXAMPLES := $(addprefix $(B)/examples/,$(EX_NAMES))
EX_COMMON:= $(wildcard examples/common/*.c examples/common/*.cpp)
EX_COMMON_OBJ := $(patsubst examples/common/%,$(B)/examples/common/%.o,$(EX_COMMON))

.PHONY: all test tests benches compile-checks fingerprints fingerprint check-headers demo bench fuzz fuzz-fast fuzz-fused coverage install clean deps-test deps-demo deps-bench examples
.DELETE_ON_ERROR:
# the examples/common objects are shared by every example and bench: keep them
.SECONDARY: $(EX_COMMON_OBJ) $(IMPL_OBJS)

all: tests examples

# ---------------------------------------------------------------- tests
deps-test:
	@scripts/deps.sh test
tests: $(TESTS) $(SAN_TESTS) $(FUZZERS) $(CLANG_TESTS)
# built by make test so that a bench that no longer compiles fails CI
benches: $(BENCHES)
# make test's build of the benches and fingerprint programs: a compile and
# link check only, at -O0 in a tree of its own (a fifth of the -O2 build's
# time: about 40 s of make test's 15 minutes; make bench and make
# fingerprint build their own at -O2; check-headers compiles the headers'
# code optimised)
compile-checks:
	@$(MAKE) --no-print-directory B=$(B)/check OPT=-O0 benches fingerprints
# the same for the fingerprint programs (scripts/fingerprint, make fingerprint)
FP_NAMES := interval rounded grooves frep
FINGERPRINTS := $(addprefix $(B)/fingerprint/fp_,$(FP_NAMES))
fingerprints: $(FINGERPRINTS)

test: deps-test
	@$(MAKE) --no-print-directory -j$(NPROC) tests examples compile-checks
	@tests/run_all.sh $(B)/tests $(B)/san $(T)

# libFuzzer targets (clang): a short run inside make test, a long one in make fuzz.
# fuzz_interval_ops: the pair path (-march=native, as the tests) and the
# __float128 references (GCC's quadmath.h, after clang's own headers).
FUZZ_FLAGS_fuzz_interval_ops := -march=native -idirafter $(GCC_INCLUDE)
FUZZ_LIBS_fuzz_interval_ops  := -lquadmath
$(B)/fuzz/%: tests/%.c $(TEST_DEPS)
	@mkdir -p $(dir $@)
	clang -std=gnu11 -O1 $(DBG) -Iinclude -Itests $(FUZZ_FLAGS_$*) -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all $< -o $@ $(FUZZ_LIBS_$*) -lm
$(B)/fuzz_fast/%: tests/%.c $(TEST_DEPS)
	@mkdir -p $(dir $@)
	clang -std=gnu11 -O2 $(DBG) -Iinclude -Itests $(FUZZ_FLAGS_$*) -fsanitize=fuzzer $< -o $@ $(FUZZ_LIBS_$*) -lm
# the same with fused multiply-adds (-march=native -ffp-contract=fast), the
# arithmetic of gcc's test builds and of hosts built for FMA machines; the
# unfused and fused builds round differently and find different inputs
$(B)/fuzz_fused/%: tests/%.c $(TEST_DEPS)
	@mkdir -p $(dir $@)
	clang -std=gnu11 -O2 $(DBG) -march=native -ffp-contract=fast -Iinclude -Itests $(FUZZ_FLAGS_$*) -fsanitize=fuzzer $< -o $@ $(FUZZ_LIBS_$*) -lm

check-headers:
	@tests/check_headers.sh

$(B)/impl/tests/%.o: tests/impl/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CFLAGS) -c $< -o $@
$(B)/impl/san/%.o: tests/impl/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CFLAGS) $(SAN_OPT) $(SAN_FLAGS) -c $< -o $@
$(B)/impl/clang/%.o: tests/impl/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	clang $(TEST_CFLAGS) $(CLANG_UNFUSED) -c $< -o $@
$(B)/impl/%/libfiligree.a: $(foreach n,$(IMPL_NAMES),$(B)/impl/%/$(n).o)
	rm -f $@ && ar rcs $@ $^

# tests that include example sources rebuild when those change
EX_TESTS := $(basename $(notdir $(shell grep -l '"\.\./examples/' tests/*.c)))
$(foreach d,tests clang san fuzz,$(addprefix $(B)/$(d)/,$(EX_TESTS))): $(wildcard examples/*/*.h examples/common/*.c)

$(B)/tests/%: tests/%.c $(TEST_DEPS) $(B)/impl/tests/libfiligree.a
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CFLAGS) $< $(B)/impl/tests/libfiligree.a -o $@ $(LDLIBS_ALL)
$(B)/tests/%: tests/%.cpp $(TEST_DEPS) $(B)/impl/tests/libfiligree.a
	@mkdir -p $(dir $@)
	$(CXX) $(TEST_CXXFLAGS) $< $(B)/impl/tests/libfiligree.a -o $@ $(LDLIBS_ALL)
$(B)/clang/%: tests/%.c $(TEST_DEPS) $(B)/impl/clang/libfiligree.a
	@mkdir -p $(dir $@)
	clang $(TEST_CFLAGS) $(CLANG_UNFUSED) -idirafter $(GCC_INCLUDE) $< $(B)/impl/clang/libfiligree.a -o $@ $(LDLIBS_ALL)
$(B)/san/%: tests/%.c $(TEST_DEPS) $(B)/impl/san/libfiligree.a
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CFLAGS) $(SAN_OPT) $(SAN_FLAGS) $< $(B)/impl/san/libfiligree.a -o $@ $(LDLIBS_ALL)
$(B)/san/%: tests/%.cpp $(TEST_DEPS) $(B)/impl/san/libfiligree.a
	@mkdir -p $(dir $@)
	$(CXX) $(TEST_CXXFLAGS) $(SAN_OPT) $(SAN_FLAGS) $< $(B)/impl/san/libfiligree.a -o $@ $(LDLIBS_ALL)

# ---------------------------------------------------------------- examples
deps-demo:
	@scripts/deps.sh demo
examples: $(EXAMPLES)

$(B)/examples/common/%.c.o: examples/common/%.c $(HEADERS) $(wildcard examples/common/*.h)
	@mkdir -p $(dir $@)
	$(CC) -std=gnu11 $(CFLAGS_ALL) -pthread -c $< -o $@
$(B)/examples/common/%.cpp.o: examples/common/%.cpp $(HEADERS) $(wildcard examples/common/*.h)
	@mkdir -p $(dir $@)
	$(CXX) -std=gnu++17 $(CFLAGS_ALL) -Wno-deprecated-declarations -pthread -c $< -o $@

# examples and benchmarks may include tests/*.h (the grooves oracle is the
# examples' geometry baseline): they depend on them, so edits rebuild them
.SECONDEXPANSION:
$(B)/examples/%: $$(wildcard examples/$$*/*.c examples/$$*/*.cpp examples/$$*/*.h) $(EX_COMMON_OBJ) $(TEST_DEPS)
	@mkdir -p $(dir $@)
	$(foreach s,$(filter %.c,$^),$(CC) -std=gnu11 $(CFLAGS_ALL) -pthread -c $(s) -o $@.$(notdir $(s)).o &&) true
	$(CXX) -std=gnu++17 $(CFLAGS_ALL) -pthread -o $@ \
	  $(foreach s,$(filter %.c,$^),$@.$(notdir $(s)).o) \
	  $(filter %.cpp %.o,$^) $(EX_LDLIBS)

demo: deps-demo
	@$(MAKE) --no-print-directory examples
	@mkdir -p out && [ -w out ] || { echo "filigree: cannot write to out/ (check its permissions)"; exit 1; }
	@set -e; for e in $(EX_NAMES); do $(B)/examples/$$e --demo out; done
	@echo "gallery written to out/"

# ---------------------------------------------------------------- benchmarks
deps-bench:
	@scripts/deps.sh bench
$(B)/bench/%: bench/%.c $(TEST_DEPS) $(wildcard bench/*.h examples/*/*.h) $(EX_COMMON_OBJ)
	@mkdir -p $(dir $@)
	$(CC) -std=gnu11 $(CFLAGS_ALL) -Ibench -c $< -o $@.o
	$(CXX) -o $@ $@.o $(EX_COMMON_OBJ) $(BENCH_LDLIBS)
$(B)/bench/%: bench/%.cpp $(TEST_DEPS) $(wildcard bench/*.h examples/*/*.h) $(EX_COMMON_OBJ)
	@mkdir -p $(dir $@)
	$(CXX) -std=gnu++17 $(CFLAGS_ALL) -Ibench -o $@ $< $(EX_COMMON_OBJ) $(BENCH_LDLIBS)

# BENCH=rounded runs only the benchmarks whose name contains "rounded".
# Each benchmark's stdout goes to out/bench/<name>.txt; stderr shows its wall
# time, and the load average and the CPU at its start. Plots are drawn into a temporary
# directory and moved to docs/img/ only when gnuplot succeeds, so with BENCH
# set a plot whose CSV this run did not write is skipped and its old SVG kept.
# The CPU the timings were taken on (its model name, family and model, as
# `lscpu` gives them): CPU times compare only on one kind of CPU.
BENCH_CPU = $(shell awk -F': *' '/^model name/ && !n {n=$$2} /^cpu family/ && !f {f=$$2} /^model[ \t]*:/ && !m {m=$$2} END {print n ", family " f " model " m}' /proc/cpuinfo 2>/dev/null)
BENCH_RUN = $(strip $(if $(BENCH),$(foreach b,$(BENCHES),$(if $(findstring $(BENCH),$(notdir $(b))),$(b))),$(BENCHES)))
bench: deps-bench
	@$(if $(BENCH_RUN),,echo "no benchmark matches BENCH=$(BENCH)" >&2; exit 1)
	@$(MAKE) --no-print-directory $(BENCH_RUN)
	@mkdir -p out/bench docs/img
	@set -e; for b in $(BENCH_RUN); do n=$$(basename $$b); \
	  echo "== $$n (load $$(cut -d' ' -f1 /proc/loadavg), $$(date -u '+%F %T') UTC, $(BENCH_CPU))" >&2; \
	  s=$$(date +%s); $$b out/bench > out/bench/$$n.txt; cat out/bench/$$n.txt; \
	  echo "== $$n took $$(( $$(date +%s) - s )) s" >&2; done
	@set -e; tmp=$$(mktemp -d); for g in $(wildcard bench/*.gp); do \
	  if gnuplot -e "dir='out/bench'; img='$$tmp'" $$g $(if $(BENCH),2>/dev/null); then mv $$tmp/* docs/img/ 2>/dev/null || true; \
	  else rm -f $$tmp/*; $(if $(BENCH),echo "skipped plot $$g" >&2,exit 1); fi; done; rmdir $$tmp
	@echo "tables in out/bench/*.csv, plots in docs/img/"

# ---------------------------------------------------------------- fuzzing
FUZZ_SECONDS ?= 600
# FUZZ=rounded runs only the fuzz targets whose name contains "rounded"
FUZZ_RUN = $(strip $(if $(FUZZ),$(foreach f,$(FUZZERS),$(if $(findstring $(FUZZ),$(notdir $(f))),$(f))),$(FUZZERS)))
# $(call fuzz_in,DIR): build the chosen targets into $(B)/DIR and run each
# for FUZZ_SECONDS on its grown corpus and its seeds
define fuzz_in
	@$(if $(FUZZ_RUN),,echo "no fuzz target matches FUZZ=$(FUZZ)" >&2; exit 1)
	@scripts/deps.sh fuzz
	@$(MAKE) --no-print-directory $(subst /fuzz/,/$(1)/,$(FUZZ_RUN))
	@set -e; for f in $(FUZZ_RUN); do n=$$(basename $$f); mkdir -p $$f.corpus; \
	  $(B)/$(1)/$$n -max_total_time=$(FUZZ_SECONDS) $$f.corpus $$(ls -d tests/corpus/$$n 2>/dev/null); done
endef
# under ASan and UBSan
fuzz:
	$(call fuzz_in,fuzz)
# answers only (no memory checks), sharing make fuzz's grown corpora
fuzz-fast:
	$(call fuzz_in,fuzz_fast)
# fuzz-fast's run on the fused build
fuzz-fused:
	$(call fuzz_in,fuzz_fused)

# ---------------------------------------------------------------- coverage
MODULES ?=
coverage:
	@scripts/deps.sh test
	@python3 scripts/coverage.py $(MODULES)

# ---------------------------------------------------------------- fingerprint
# each header's answers hashed (docs/conventions.md): run on the old tree and
# on the new one, the outputs must be equal for a change meant to keep them
fingerprint: deps-test
	@$(MAKE) --no-print-directory -j$(NPROC) fingerprints
	@set -e; for p in $(FP_NAMES); do $(B)/fingerprint/fp_$$p; done

$(B)/fingerprint/fp_%: scripts/fingerprint/fp_%.c scripts/fingerprint/fp.h $(TEST_DEPS) $(wildcard examples/*/*.h) $(EX_COMMON_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CFLAGS) -c $< -o $@.o
	$(CXX) -o $@ $@.o $(EX_COMMON_OBJ) $(BENCH_LDLIBS)

# ---------------------------------------------------------------- install
install:
	install -d $(DESTDIR)$(PREFIX)/include/filigree $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 $(HEADERS) $(DESTDIR)$(PREFIX)/include/filigree/
	printf 'prefix=%s\nincludedir=$${prefix}/include/filigree\n\nName: filigree\nDescription: header-only fine geometric detail for ray tracers\nVersion: 0.1.0\nCflags: -I$${includedir}\nLibs: -lm\n' \
	  "$(PREFIX)" > $(DESTDIR)$(PREFIX)/lib/pkgconfig/filigree.pc
	@echo "installed headers to $(DESTDIR)$(PREFIX)/include/filigree and filigree.pc"

clean:
	rm -rf $(B) out
