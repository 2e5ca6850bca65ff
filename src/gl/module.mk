# GL platform layer (src/gl/): the headless GL contexts (EGL surfaceless or on
# a device, OSMesa, or a caller's such as SDL's), the table of GL functions,
# the program builder and the script that embeds GLSL as C strings. Both the
# renderer (src/render/) and the GL compute backend (src/gpu/) stand on it;
# it includes neither. Included by the top Makefile.
#
# libepoxy cannot resolve GL under an OSMesa context (it knows GLX and EGL
# only, and aborts), so OSMesa is linked directly and its context fills the
# GL table from OSMesaGetProcAddress (gl_table.h).

GL_PKGS   := epoxy egl osmesa
GL_CFLAGS := $(shell pkg-config --cflags $(GL_PKGS) 2>/dev/null)
GL_LIBS   := $(shell pkg-config --libs $(GL_PKGS) 2>/dev/null || echo -lepoxy -lEGL -lOSMesa)
# Turns GLSL files into C strings (the render and gpu modules use it).
GL_EMBED  := src/gl/embed-shaders.sh

# Mesa's EGL and drivers (llvmpipe), OSMesa, libepoxy; libgl-dev has GL/glcorearb.h.
DEB_PKGS += libepoxy-dev libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri libosmesa6-dev

GL_SRC := gl_context ctx_egl ctx_osmesa gl_epoxy gl_program
GL_OBJ := $(GL_SRC:%=$(BUILD)/gl/%.o)

MOD_OBJ       += $(GL_OBJ)
MOD_LIBS      += $(GL_LIBS)
# A base layer: linked after the module libraries that use it, before the core.
BASE_TEST_LIBS += $(BUILD)/gl/libsphgl.a
MOD_TEST_SYS_LIBS += $(GL_LIBS)

$(BUILD)/sphlab-tests: $(BUILD)/gl/libsphgl.a

$(BUILD)/gl/libsphgl.a: $(GL_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/gl/%.o: src/gl/%.c src/gl/*.h | $(BUILD)/gl
	$(CC) $(CFLAGS) $(WARN) $(GL_CFLAGS) -Isrc/gl -c -o $@ $<

$(BUILD)/gl:
	mkdir -p $@

# Warnings are errors under clang too.
.PHONY: check-clang-gl
check-clang: check-clang-gl
check-clang-gl:
	$(MAKE) CC=clang BUILD=build-clang $(patsubst $(BUILD)/%,build-clang/%,$(GL_OBJ))
