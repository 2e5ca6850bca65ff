# sphlab: make (build), make demo, make test, make asan, make clean.
# `make demo` and `make test` first install any missing Debian packages.

CC      ?= cc
OPT     ?= -O2 -march=native
CFLAGS  ?= $(OPT) -g
WARN    := -std=c11 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wvla -D_POSIX_C_SOURCE=200809L
OMP     := -fopenmp
PKGS_CORE := inih
PKGS_TEST := criterion
# No fused multiply-adds (clang forms them by default, gcc -std=c11 does not): every
# compiler and -O level rounds alike, so tests/test_golden.c's stored hash holds for all.
FP      := -ffp-contract=off
CORE_CFLAGS := $(WARN) $(FP) $(OMP) -Isrc/core $(shell pkg-config --cflags $(PKGS_CORE) 2>/dev/null)
CORE_LIBS   := $(shell pkg-config --libs $(PKGS_CORE) 2>/dev/null || echo -linih) -lm

BUILD   := build
# The binary's path: `make BUILD=build-gl BIN=build-gl/sphlab` builds beside its objects.
BIN     ?= sphlab
# Every file of src/core and src/passes is built: a new pass is a new file, no list to edit.
CORE    := $(filter-out sph_overlay,$(sort $(basename $(notdir $(wildcard src/core/sph_*.c)))))
PASSES  := $(sort $(basename $(notdir $(wildcard src/passes/*.c))))
APP     := main app_options app_threads cmd_run cmd_check cmd_hardcases
TESTS   := $(filter-out test_util,$(basename $(notdir $(wildcard tests/test_*.c))))

# Modules above the core (rendering, plotting) add objects, flags and libraries
# to these from their own fragment, src/MODULE/module.mk. The I/O layer's
# library (IO_LIB, src/io/module.mk) goes just before the core on the link
# lines: every module may use it, and it uses the core.
# Debian packages the build and tests need; modules append theirs.
DEB_PKGS := build-essential clang pkg-config libinih-dev libcriterion-dev libomp-dev libclang-rt-14-dev
MOD_OBJ  :=
MOD_LIBS :=
# The tests link the modules' libraries in layers, each before what it
# stands on, and name every library once: the modules' own (render, gpu,
# study: MOD_TEST_LIBS, none using another), then the layers below them (gl,
# overlay: BASE_TEST_LIBS, which use only the core), then the core, then the
# system's libraries (MOD_TEST_SYS_LIBS, repeats dropped).
MOD_TEST_LIBS :=
BASE_TEST_LIBS :=
MOD_TEST_SYS_LIBS :=
-include $(wildcard src/*/module.mk)
.DEFAULT_GOAL := all

# A list without its repeats, each kept where it first appears (-lm from the
# core and from a module is named once on a link line).
uniq = $(if $1,$(firstword $1) $(call uniq,$(filter-out $(firstword $1),$1)))

CORE_OBJ := $(CORE:%=$(BUILD)/core/%.o) $(PASSES:%=$(BUILD)/passes/%.o)
APP_OBJ  := $(APP:%=$(BUILD)/app/%.o) $(MOD_OBJ)
TEST_OBJ := $(TESTS:%=$(BUILD)/tests/%.o) $(BUILD)/tests/test_util.o
# The option table is tested in-process (tests/test_options.c).
TEST_APP_OBJ := $(BUILD)/app/app_options.o $(BUILD)/app/app_threads.o
$(BUILD)/tests/test_options.o: CORE_CFLAGS += -Isrc/app
$(BUILD)/tests/test_threads.o: CORE_CFLAGS += -Isrc/app
$(BUILD)/tests/test_options.o: src/app/app_options.h src/app/commands.h

.PHONY: all demo test check-tests check-clang asan asan-run fuzz deps clean

all: $(BIN)

$(BIN): $(BUILD)/libsphcore.a $(APP_OBJ)
	$(CC) $(CFLAGS) $(OMP) -o $@ $(APP_OBJ) $(IO_LIB) $(BUILD)/libsphcore.a $(call uniq,$(CORE_LIBS) $(MOD_LIBS) $(IO_SYS_LIBS))

$(BUILD)/libsphcore.a: $(CORE_OBJ)
	ar rcs $@ $^

$(BUILD)/core/%.o: src/core/%.c src/core/*.h | $(BUILD)/core
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -c -o $@ $<
$(BUILD)/passes/%.o: src/passes/%.c src/passes/*.h src/core/*.h | $(BUILD)/passes
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -c -o $@ $<
$(BUILD)/app/%.o: src/app/%.c src/app/*.h src/core/*.h | $(BUILD)/app
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/app -c -o $@ $<
$(BUILD)/tests/%.o: tests/%.c tests/*.h src/core/*.h | $(BUILD)/tests
	$(CC) $(CFLAGS) $(CORE_CFLAGS) $(shell pkg-config --cflags $(PKGS_TEST) 2>/dev/null) -Itests -c -o $@ $<

$(BUILD)/core $(BUILD)/passes $(BUILD)/app $(BUILD)/tests:
	mkdir -p $@

$(BUILD)/sphlab-tests: $(TEST_OBJ) $(TEST_APP_OBJ) $(BUILD)/libsphcore.a
	$(CC) $(CFLAGS) $(OMP) -o $@ $(TEST_OBJ) $(TEST_APP_OBJ) $(MOD_TEST_LIBS) $(BASE_TEST_LIBS) $(IO_LIB) $(BUILD)/libsphcore.a \
	    $(call uniq,$(CORE_LIBS) $(MOD_TEST_SYS_LIBS) $(IO_SYS_LIBS) $(shell pkg-config --libs $(PKGS_TEST) 2>/dev/null || echo -lcriterion))

# Installs what is missing (Debian packages); does nothing when all are there.
deps:
	@sh tests/install-deps.sh $(DEB_PKGS)

# The main job: the 2D dam break headless, then the full-simulation lesson's export. Prints the timing table; writes to
# out/demo/ the per-step stats, the final particles, charts (PNG + PDF) of the
# time per pass and of energy and density, and rendered frames.
DEMO_SCENE ?= lessons/scenes/dam-break-2d.ini
demo: deps
	$(MAKE) sphlab
	mkdir -p out/demo
	./sphlab run $(DEMO_SCENE) --stats out/demo/stats.csv --dump out/demo/particles.csv
	./sphlab plot passes out/demo/stats.csv --out out/demo
	./sphlab plot series out/demo/stats.csv --y ekin,rho_max,max_speed --dim 2 --out out/demo
	./sphlab render $(DEMO_SCENE) --out out/demo/frames --every 400 --steps 2400 --overlay grid --quiet
	./sphlab lesson 7 --export out/demo/lesson-7
	@echo "demo: figures and tables in out/demo/, the full-simulation lesson's report in out/demo/lesson-7/report.md"

# The whole suite, the clang build, then the whole suite again under
# AddressSanitizer and UndefinedBehaviorSanitizer (what CI runs).
test: deps
	$(MAKE) $(BIN) $(BUILD)/sphlab-tests
	$(MAKE) check-tests
	$(MAKE) check-clang
	$(MAKE) asan-run

# Warnings are errors under both compilers: compile everything with clang too.
check-clang:
	$(MAKE) CC=clang BUILD=build-clang build-clang/libsphcore.a $(APP:%=build-clang/app/%.o) $(TEST_OBJ:$(BUILD)/%=build-clang/%)
	@echo "clang: library, app and tests compile with -Wall -Wextra -Werror"

# Runs the suite against the binaries already built (also used by `make asan`).
# The test binary's own threads wait passively too (sphlab sets this itself;
# docs/performance.md, "Threads on a busy machine"); tests/test_threads.c unsets it.
check-tests:
	OMP_WAIT_POLICY=passive SPHLAB=./$(BIN) $(BUILD)/sphlab-tests --jobs 2
	sh tests/cli.sh ./$(BIN)
	sh tests/cli_io.sh ./$(BIN)

asan: deps
	$(MAKE) asan-run

# -O2 without -march=native: the scalar loops (no AVX), as a CPU without AVX2 runs them; -O2 rather than -O1 runs
# the suite about 1.2 times faster under the sanitizers, with the same sums (no contraction, no reassociation).
asan-run:
	$(MAKE) BUILD=build-asan OPT="-O2 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all" \
	    sphlab-asan build-asan/sphlab-tests
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
	    $(MAKE) BUILD=build-asan SPHLAB_BIN=./sphlab-asan check-tests-asan

sphlab-asan: $(BUILD)/libsphcore.a $(APP_OBJ)
	$(CC) $(CFLAGS) $(OMP) -o $@ $(APP_OBJ) $(IO_LIB) $(BUILD)/libsphcore.a $(call uniq,$(CORE_LIBS) $(MOD_LIBS) $(IO_SYS_LIBS))

check-tests-asan:
	OMP_WAIT_POLICY=passive SPHLAB=./sphlab-asan $(BUILD)/sphlab-tests --jobs 2
	sh tests/cli.sh ./sphlab-asan
	sh tests/cli_io.sh ./sphlab-asan

# Fuzzing the scene parser with libFuzzer (clang, ASan, UBSan). FUZZ_SECONDS
# bounds the run; the corpus starts from the shipped scenes and grows in build-fuzz/corpus.
FUZZ_SECONDS ?= 60
fuzz: deps
	mkdir -p build-fuzz/corpus
	cp lessons/scenes/*.ini build-fuzz/corpus/ 2>/dev/null || true
	clang -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -fopenmp \
	    -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Werror -Isrc/core $(shell pkg-config --cflags inih) \
	    -o build-fuzz/fuzz_scene tests/fuzz_scene.c $(CORE:%=src/core/%.c) $(PASSES:%=src/passes/%.c) $(CORE_LIBS)
	build-fuzz/fuzz_scene -max_total_time=$(FUZZ_SECONDS) -max_len=4096 -timeout=10 \
	    -artifact_prefix=build-fuzz/ build-fuzz/corpus

clean:
	rm -rf build build-asan build-clang build-fuzz sphlab sphlab-asan
