# src/validate: `sphlab validate`, reference problems with published data or
# exact solutions, each one command that writes a CSV, a chart against the
# reference and a PASS/FAIL line (docs/accuracy.md, "Validation").
# Included by the Makefile (-include src/*/module.mk).
#
# The reference data and exact solutions (no simulation, no PLplot) form
# build/validate/libvalidate.a, which the tests link; the problems and the
# command (PLplot, through src/plot's output staging) go into the binary only.
VALIDATE_LIB_SRC := validate_ref
VALIDATE_CMD_SRC := cmd_validate validate_run val_dam_break val_hydrostatic val_taylor_green val_poiseuille val_couette val_channel val_obstacle val_drop
VALIDATE_PLOT_CFLAGS := $(shell pkg-config --cflags plplot 2>/dev/null || echo -I/usr/include/plplot)

# PLplot and its cairo driver come with src/plot's packages.
MOD_OBJ       += $(VALIDATE_LIB_SRC:%=$(BUILD)/validate/%.o) $(VALIDATE_CMD_SRC:%=$(BUILD)/validate/%.o)
# A module library: linked before the core (the Makefile's link line).
MOD_TEST_LIBS += $(BUILD)/validate/libvalidate.a
MOD_TEST_SYS_LIBS += -lm

$(BUILD)/sphlab-tests: $(BUILD)/validate/libvalidate.a

$(BUILD)/validate/libvalidate.a: $(VALIDATE_LIB_SRC:%=$(BUILD)/validate/%.o)
	ar rcs $@ $^

$(BUILD)/validate/%.o: src/validate/%.c src/validate/*.h src/app/*.h src/core/*.h src/plot/*.h | $(BUILD)/validate
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/app -Isrc/plot $(VALIDATE_PLOT_CFLAGS) -c -o $@ $<

$(BUILD)/validate:
	mkdir -p $@

# tests/test_validate.c includes src/validate/validate.h.
$(BUILD)/tests/test_validate.o: CORE_CFLAGS += -Isrc/validate

# `make test` compiles everything with clang as well: this module's objects too.
.PHONY: check-clang-validate
check-clang: check-clang-validate
check-clang-validate:
	$(MAKE) CC=clang BUILD=build-clang $(VALIDATE_LIB_SRC:%=build-clang/validate/%.o) $(VALIDATE_CMD_SRC:%=build-clang/validate/%.o)
