# src/study: `sphlab study` and `sphlab estimate`, the reference problems with
# known answers and what each accuracy choice costs (docs/accuracy.md).
# Included by the Makefile (-include src/*/module.mk).
#
# The reference problems and the study machinery (no PLplot, no GL) form
# build/study/libstudy.a, which the tests link; the commands and the charts
# (PLplot, through src/plot's output staging) go into the binary only.
STUDY_LIB_SRC := study_ref study_estimate study_vary study_live
STUDY_CMD_SRC := cmd_study cmd_estimate study_plot
STUDY_PLOT_CFLAGS := $(shell pkg-config --cflags plplot 2>/dev/null || echo -I/usr/include/plplot)

# PLplot and its cairo driver come with src/plot's packages.
DEB_PKGS      += libplplot-dev plplot-driver-cairo fonts-dejavu-core
MOD_OBJ       += $(STUDY_LIB_SRC:%=$(BUILD)/study/%.o) $(STUDY_CMD_SRC:%=$(BUILD)/study/%.o)
# A module library: linked before the core (the Makefile's link line).
MOD_TEST_LIBS += $(BUILD)/study/libstudy.a
MOD_TEST_SYS_LIBS += -lm

$(BUILD)/sphlab-tests: $(BUILD)/study/libstudy.a

$(BUILD)/study/libstudy.a: $(STUDY_LIB_SRC:%=$(BUILD)/study/%.o)
	ar rcs $@ $^

$(BUILD)/study/%.o: src/study/%.c src/study/*.h src/app/*.h src/core/*.h src/plot/*.h | $(BUILD)/study
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/app -Isrc/plot $(STUDY_PLOT_CFLAGS) -c -o $@ $<

$(BUILD)/study:
	mkdir -p $@

# The study tests (tests/test_study.c, tests/test_study_*.c) include src/study/study.h.
$(BUILD)/tests/test_study.o: CORE_CFLAGS += -Isrc/study
$(BUILD)/tests/test_study%.o: CORE_CFLAGS += -Isrc/study

# `make test` compiles everything with clang as well: this module's objects too.
.PHONY: check-clang-study
check-clang: check-clang-study
check-clang-study:
	$(MAKE) CC=clang BUILD=build-clang $(STUDY_LIB_SRC:%=build-clang/study/%.o) $(STUDY_CMD_SRC:%=build-clang/study/%.o)
# test_gl_study.c: a study on the GL backend (the study API and the GL tests' helpers)
$(BUILD)/tests/test_gl_study.o: CORE_CFLAGS += -Isrc/study -Isrc/gpu
