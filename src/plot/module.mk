# src/plot: `sphlab plot`, charts for a report through PLplot's cairo driver
# (PNG and PDF). Included by the Makefile (-include src/*/module.mk).
PLOT_SRC    := cmd_plot plot_csv plot_out plot_draw plot_page
PLOT_CFLAGS := $(shell pkg-config --cflags plplot 2>/dev/null || echo -I/usr/include/plplot)
PLOT_LIBS   := $(shell pkg-config --libs plplot 2>/dev/null || echo -lplplot)
STB_CFLAGS  := $(shell pkg-config --cflags stb 2>/dev/null || echo -I/usr/include/stb)
STB_LIBS    := $(shell pkg-config --libs stb 2>/dev/null || echo -lstb)

# plplot-driver-cairo holds pngcairo and pdfcairo; fonts-dejavu-core the text;
# libstb-dev the PNG decoder the tests use.
DEB_PKGS      += libplplot-dev plplot-driver-cairo fonts-dejavu-core libstb-dev
MOD_OBJ       += $(PLOT_SRC:%=$(BUILD)/plot/%.o)
MOD_LIBS      += $(PLOT_LIBS)
MOD_TEST_SYS_LIBS += $(STB_LIBS)

$(BUILD)/plot/%.o: src/plot/%.c src/plot/*.h src/app/*.h src/core/*.h | $(BUILD)/plot
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/app $(PLOT_CFLAGS) -c -o $@ $<

$(BUILD)/plot:
	mkdir -p $@

# The plot tests (tests/test_plot*.c) decode PNGs with stb_image. A pattern's
# % matches at least one character, hence test_plot.o named on its own.
$(BUILD)/tests/test_plot.o $(BUILD)/tests/test_plot%.o: CFLAGS += $(STB_CFLAGS)
# tests/test_plot.c calls plot.h's axis rule (inline) in-process.
$(BUILD)/tests/test_plot.o: CORE_CFLAGS += -Isrc/plot
$(BUILD)/tests/test_plot.o: src/plot/plot.h

# `make test` compiles the library, app and tests with clang as well; the
# module's objects too.
check-clang: check-clang-plot
.PHONY: check-clang-plot
check-clang-plot:
	$(MAKE) CC=clang BUILD=build-clang $(PLOT_SRC:%=build-clang/plot/%.o)
