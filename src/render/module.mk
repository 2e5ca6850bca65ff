# Rendering module (src/render/): sphlab render and view, PNG frames (written
# by the I/O layer, src/io/). Included by the top Makefile; adds objects,
# libraries and packages. GL code lives only in src/render/. The GL-free part
# (the overlay builder src/core/sph_overlay.c, the camera, the font) is also
# what the tests link without a window.

RENDER_PKGS   := epoxy egl osmesa sdl2 stb
RENDER_CFLAGS := $(shell pkg-config --cflags $(RENDER_PKGS) 2>/dev/null || echo -I/usr/include/stb -I/usr/include/SDL2)
RENDER_LIBS   := $(shell pkg-config --libs $(RENDER_PKGS) 2>/dev/null || echo -lepoxy -lEGL -lOSMesa -lSDL2 -lstb) -lm

# Mesa's EGL and drivers (llvmpipe), OSMesa, libepoxy, SDL2, stb, the font;
# libgl-dev has GL/glcorearb.h. xauth and xvfb are not needed: the window
# test uses SDL's offscreen video driver.
DEB_PKGS += libepoxy-dev libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri libosmesa6-dev libstb-dev \
            libsdl2-dev fonts-dejavu-core

RENDER_LIB_OBJ := $(BUILD)/core/sph_overlay.o \
    $(patsubst %,$(BUILD)/render/%.o,camera font gl_epoxy gl_program ctx_egl ctx_osmesa renderer)
RENDER_CMD_OBJ := $(patsubst %,$(BUILD)/render/%.o,cmd_common cmd_render cmd_view)

MOD_OBJ       += $(RENDER_LIB_OBJ) $(RENDER_CMD_OBJ)
MOD_LIBS      += $(RENDER_LIBS)
# The tests link the renderer from a library placed after the core library,
# so the core comes again after it.
MOD_TEST_LIBS += $(BUILD)/render/librender.a $(BUILD)/libsphcore.a $(RENDER_LIBS)

$(BUILD)/sphlab-tests: $(BUILD)/render/librender.a

# Made afresh: an object moved out of the module (vtk.o, now in src/io) must not stay in it.
$(BUILD)/render/librender.a: $(RENDER_LIB_OBJ) src/render/module.mk
	rm -f $@ && ar rcs $@ $(filter %.o,$^)

# GLSL sources become C strings in the binary: no shader files at run time.
SHADERS := $(wildcard shaders/*.vert shaders/*.frag)
$(BUILD)/render/shaders.h: $(SHADERS) src/render/embed-shaders.sh | $(BUILD)/render
	sh src/render/embed-shaders.sh $(SHADERS) > $@.tmp && mv $@.tmp $@

$(BUILD)/render/%.o: src/render/%.c src/render/*.h src/io/*.h src/gpu/gpu.h src/core/*.h src/app/*.h | $(BUILD)/render
	$(CC) $(CFLAGS) $(CORE_CFLAGS) $(RENDER_CFLAGS) -Isrc/render -Isrc/gpu -Isrc/app -Isrc/io -I$(BUILD)/render -c -o $@ $<
$(BUILD)/render/renderer.o: $(BUILD)/render/shaders.h

$(BUILD)/render:
	mkdir -p $@

# The render tests include src/render/ headers (tests/test_render.c and tests/test_render_*.c).
$(BUILD)/tests/test_render.o: CORE_CFLAGS += -Isrc/render $(RENDER_CFLAGS)
$(BUILD)/tests/test_render_%.o: CORE_CFLAGS += -Isrc/render -Isrc/gpu $(RENDER_CFLAGS)

# `make asan`: Mesa (LLVM's JIT, the drivers) keeps allocations until exit
# by design; tests/lsan.supp (set by the Makefile) tells LeakSanitizer so.

# Warnings are errors under clang too: `make check-clang` also compiles this module.
.PHONY: check-clang-render
check-clang: check-clang-render
check-clang-render:
	$(MAKE) CC=clang BUILD=build-clang $(patsubst $(BUILD)/%,build-clang/%,$(RENDER_LIB_OBJ) $(RENDER_CMD_OBJ))
