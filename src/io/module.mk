# The I/O layer (src/io/): how every command writes a file. One atomic writer
# (a unique temporary, checked writes, rename on commit), mkdir -p, the
# signal handler that removes temporaries, PNG (stb_image_write), VTK, JSON
# (cJSON), scene files. GL-free; stands on libc, stb and cJSON, and (vtk.c, io_scene.c) on the
# core's sph_sim.h; io_scene.c on sph_scene.h. Included by the top Makefile, which links build/io/libio.a
# (IO_LIB, then the
# core; IO_SYS_LIBS with the system libraries): every module above may call it.

IO_SRC    := io_out io_dir io_png io_json vtk io_scene
IO_CFLAGS := $(shell pkg-config --cflags stb 2>/dev/null || echo -I/usr/include/stb)
IO_LIB      := $(BUILD)/io/libio.a
IO_SYS_LIBS := $(shell pkg-config --libs libcjson 2>/dev/null || echo -lcjson) \
               $(shell pkg-config --libs stb 2>/dev/null || echo -lstb)

DEB_PKGS += libcjson-dev libstb-dev

$(BUILD)/io/libio.a: $(IO_SRC:%=$(BUILD)/io/%.o)
	rm -f $@ && ar rcs $@ $^

$(BIN) sphlab-asan $(BUILD)/sphlab-tests: $(BUILD)/io/libio.a

$(BUILD)/io/%.o: src/io/%.c src/io/*.h src/core/*.h | $(BUILD)/io
	$(CC) $(CFLAGS) $(CORE_CFLAGS) $(IO_CFLAGS) -c -o $@ $<

$(BUILD)/io:
	mkdir -p $@

# The commands include src/io/ headers by relative path; the tests by name.
$(BUILD)/tests/test_io.o $(BUILD)/tests/test_render_overlay.o: CORE_CFLAGS += -Isrc/io

# `make test` compiles everything with clang as well: this module too.
.PHONY: check-clang-io
check-clang: check-clang-io
check-clang-io:
	$(MAKE) CC=clang BUILD=build-clang $(IO_SRC:%=build-clang/io/%.o)

# The commands in src/app include io.h (through app.h) and vtk.h.
$(APP:%=$(BUILD)/app/%.o): $(wildcard src/io/*.h)
$(BUILD)/plot/plot_out.o $(BUILD)/lesson/lesson_export.o $(BUILD)/lesson/lesson_steps.o $(BUILD)/bench/bench_machine.o $(BUILD)/bench/bench_levels.o: $(wildcard src/io/*.h)
