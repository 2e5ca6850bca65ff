# The window's parameter panel (src/panel/): Dear ImGui from Debian's
# libimgui-dev, whose static library also holds the SDL2 and OpenGL 3
# backends (their headers under imgui/backends/). One C++ file behind a C
# header (panel.h); only `sphlab view` (src/render/cmd_view.c) calls it, and
# nothing of the core or the tests' libraries is C++. Included by the top
# Makefile; the panel is required: `make deps` installs the package.

DEB_PKGS += libimgui-dev

# The C++ compiler that goes with CC: clang++ for `make check-clang` (CC=clang).
PANEL_CXX := $(if $(findstring clang,$(CC)),clang++,g++)
# Warnings are errors, as for the C files; ImGui's own headers are system headers.
PANEL_CXXFLAGS = $(CFLAGS) -std=c++11 -Wall -Wextra -Werror -Wshadow -fno-exceptions \
    -isystem /usr/include/imgui $(RENDER_PKG_CFLAGS)
PANEL_OBJ := $(BUILD)/panel/panel.o

MOD_OBJ  += $(PANEL_OBJ)
# libimgui.a is C++: the link (by the C compiler) also needs the C++ runtime.
MOD_LIBS += $(shell pkg-config --libs imgui 2>/dev/null || echo -limgui) -lstdc++

$(BUILD)/panel/%.o: src/panel/%.cpp src/panel/*.h src/core/*.h | $(BUILD)/panel
	$(PANEL_CXX) $(PANEL_CXXFLAGS) -Isrc/core -Isrc/panel -c -o $@ $<
$(BUILD)/render/cmd_view.o $(BUILD)/render/view_keys.o: src/panel/panel.h
$(BUILD)/render/cmd_view.o $(BUILD)/render/view_keys.o: CORE_CFLAGS += -Isrc/panel

$(BUILD)/panel:
	mkdir -p $@

.PHONY: check-clang-panel
check-clang: check-clang-panel
check-clang-panel:
	$(MAKE) CC=clang BUILD=build-clang build-clang/panel/panel.o
