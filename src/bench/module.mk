# src/bench: `sphlab bench`, the optimisation ladder (largest N at 60 steps/s
# per level, ms per pass, checks against a reference level), time per step
# against N, and the machine's limits. Included by the Makefile
# (-include src/*/module.mk). Charts go through PLplot like src/plot's
# (PLOT_CFLAGS and the libraries come from src/plot/module.mk).

# This fragment is read before the others and before the Makefile's `all`:
# keep whatever default goal was set so far, so that `bench` never becomes it.
BENCH_SAVED_GOAL := $(.DEFAULT_GOAL)

BENCH_SRC := cmd_bench bench_common bench_ladder bench_report bench_scaling bench_solvers bench_levels bench_measure bench_machine bench_chart bench_flops bench_pair
MOD_OBJ   += $(BENCH_SRC:%=$(BUILD)/bench/%.o)

$(BUILD)/bench/%.o: src/bench/%.c src/bench/*.h src/plot/plot.h src/gpu/gpu.h src/app/*.h src/core/*.h | $(BUILD)/bench
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/app -Isrc/plot -Isrc/gpu $(PLOT_CFLAGS) -c -o $@ $<

$(BUILD)/bench:
	mkdir -p $@

# tests/test_bench.c calls bench.h's inline peak rule in-process.
$(BUILD)/tests/test_bench.o: CORE_CFLAGS += -Isrc/bench
$(BUILD)/tests/test_bench.o: src/bench/bench.h

# `make bench`: the ladder and the scaling in 3D (and the machine's limits),
# into build/bench/.
BENCH_OUT ?= build/bench
.PHONY: bench
bench: sphlab
	mkdir -p $(BENCH_OUT)
	./sphlab bench machine --out $(BENCH_OUT)
	./sphlab bench ladder --out $(BENCH_OUT)
	./sphlab bench scaling --out $(BENCH_OUT)

# `make test` compiles the library, app and tests with clang as well; this module's objects too.
check-clang: check-clang-bench
.PHONY: check-clang-bench
check-clang-bench:
	$(MAKE) CC=clang BUILD=build-clang $(BENCH_SRC:%=build-clang/bench/%.o)

.DEFAULT_GOAL := $(BENCH_SAVED_GOAL)
