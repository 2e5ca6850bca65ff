# Rendering module (src/render/): sphlab render and view, PNG frames (written by
# the I/O layer, src/io/). Included by the top Makefile; adds objects, libraries and packages.
# It stands on the GL platform layer (src/gl/: contexts, GL table, program
# builder) and draws the overlay lists of src/overlay/. The renderer library
# includes nothing of src/gpu/: the GL backend's buffers reach it through
# src/gl/gl_fields.h. Only the commands (cmd_render.c, cmd_view.c) include
# src/gpu/gpu.h, to create simulations that share their context. The window
# (view) is cmd_view.c (its loop) and view_keys.c (its keys and their actions).

RENDER_PKGS   := sdl2 stb
RENDER_PKG_CFLAGS := $(shell pkg-config --cflags $(RENDER_PKGS) 2>/dev/null || echo -I/usr/include/stb -I/usr/include/SDL2)
# expanded when used: src/gl/module.mk (GL_CFLAGS) may be read after this one
RENDER_CFLAGS = $(GL_CFLAGS) $(RENDER_PKG_CFLAGS)
RENDER_LIBS   := $(shell pkg-config --libs $(RENDER_PKGS) 2>/dev/null || echo -lSDL2 -lstb) -lm

# SDL2, stb, the font (the GL packages come with src/gl/module.mk). xauth and
# xvfb are not needed: the window test uses SDL's offscreen video driver.
DEB_PKGS += libstb-dev libsdl2-dev fonts-dejavu-core

RENDER_LIB_OBJ := $(patsubst %,$(BUILD)/render/%.o,camera font renderer canvas hud layout view_ladder)
RENDER_CMD_OBJ := $(patsubst %,$(BUILD)/render/%.o,cmd_common cmd_render cmd_view view_keys view_record)

MOD_OBJ       += $(RENDER_LIB_OBJ) $(RENDER_CMD_OBJ)
MOD_LIBS      += $(RENDER_LIBS)
# A module library: linked before the layers it stands on (libsphgl.a,
# libsphoverlay.a) and the core.
MOD_TEST_LIBS += $(BUILD)/render/librender.a
MOD_TEST_SYS_LIBS += $(RENDER_LIBS)

$(BUILD)/sphlab-tests: $(BUILD)/render/librender.a

$(BUILD)/render/librender.a: $(RENDER_LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

# GLSL sources become C strings in the binary: no shader files at run time.
SHADERS := $(wildcard shaders/*.vert shaders/*.frag)
$(BUILD)/render/shaders.h: $(SHADERS) src/gl/embed-shaders.sh | $(BUILD)/render
	sh src/gl/embed-shaders.sh $(SHADERS) > $@.tmp && mv $@.tmp $@

RENDER_INC := -Isrc/render -Isrc/gl -Isrc/overlay -Isrc/io
$(BUILD)/render/%.o: src/render/%.c src/render/*.h src/gl/*.h src/overlay/*.h src/core/*.h src/app/*.h | $(BUILD)/render
	$(CC) $(CFLAGS) $(CORE_CFLAGS) $(RENDER_CFLAGS) $(RENDER_INC) -Isrc/app -I$(BUILD)/render -c -o $@ $<
# The commands create simulations on the GL backend (src/gpu/gpu.h).
$(BUILD)/render/cmd_render.o $(BUILD)/render/cmd_view.o: src/gpu/gpu.h
$(BUILD)/render/cmd_render.o $(BUILD)/render/cmd_view.o: CORE_CFLAGS += -Isrc/gpu
$(BUILD)/render/renderer.o: $(BUILD)/render/shaders.h

$(BUILD)/render:
	mkdir -p $@

# The render tests include src/render/ headers (tests/test_render.c and tests/test_render_*.c).
$(BUILD)/tests/test_render.o: CORE_CFLAGS += $(RENDER_INC) $(RENDER_CFLAGS)
$(BUILD)/tests/test_render_%.o: CORE_CFLAGS += $(RENDER_INC) -Isrc/gpu $(RENDER_CFLAGS)
# and are rebuilt when those headers change (sph_view's layout, for one)
$(patsubst tests/%.c,$(BUILD)/tests/%.o,$(wildcard tests/test_render*.c)): src/render/*.h

# `make asan`: Mesa (LLVM's JIT, the drivers) keeps allocations until exit
# by design; tests/lsan.supp (set by the Makefile) tells LeakSanitizer so.

# Warnings are errors under clang too: `make check-clang` also compiles this module.
.PHONY: check-clang-render
check-clang: check-clang-render
check-clang-render:
	$(MAKE) CC=clang BUILD=build-clang $(patsubst $(BUILD)/%,build-clang/%,$(RENDER_LIB_OBJ) $(RENDER_CMD_OBJ))
