# Video module (src/video/): MP4 (H.264 through libavcodec's libx264,
# libavformat, libswscale) and animated GIF (giflib) from RGB frames; used by
# `sphlab render --video` and the window's record key (src/render/). It
# includes nothing of the core, the GL layer or the renderer: frames come in
# as RGB bytes. Included by the top Makefile.

VIDEO_PKGS   := libavcodec libavformat libswscale libavutil
VIDEO_CFLAGS := $(shell pkg-config --cflags $(VIDEO_PKGS) 2>/dev/null)
VIDEO_LIBS   := $(shell pkg-config --libs $(VIDEO_PKGS) 2>/dev/null || echo -lavformat -lavcodec -lswscale -lavutil) -lgif

# Debian's libavcodec is built with libx264 (H.264); giflib for GIF.
DEB_PKGS += libavcodec-dev libavformat-dev libswscale-dev libavutil-dev libgif-dev

VIDEO_SRC := video video_mp4 video_gif
VIDEO_OBJ := $(VIDEO_SRC:%=$(BUILD)/video/%.o)

MOD_OBJ  += $(VIDEO_OBJ)
MOD_LIBS += $(VIDEO_LIBS)
# A layer below the render module (which calls it): with the base libraries.
BASE_TEST_LIBS += $(BUILD)/video/libvideo.a
MOD_TEST_SYS_LIBS += $(VIDEO_LIBS)

$(BUILD)/sphlab-tests: $(BUILD)/video/libvideo.a

$(BUILD)/video/libvideo.a: $(VIDEO_OBJ)
	rm -f $@ && ar rcs $@ $^

# Not the core's flags: this module stands on libc and the libraries alone.
$(BUILD)/video/%.o: src/video/%.c src/video/*.h | $(BUILD)/video
	$(CC) $(CFLAGS) $(WARN) $(VIDEO_CFLAGS) -c -o $@ $<

$(BUILD)/video:
	mkdir -p $@

# The render commands and the tests include video.h.
VIDEO_USERS := $(patsubst %,$(BUILD)/render/%.o,cmd_render cmd_view view_keys view_record)
$(VIDEO_USERS): src/video/video.h
$(VIDEO_USERS): RENDER_INC += -Isrc/video
$(BUILD)/tests/test_render_video.o: CORE_CFLAGS += -Isrc/video $(VIDEO_CFLAGS)
$(BUILD)/tests/test_render_video.o: src/video/video.h

.PHONY: check-clang-video
check-clang: check-clang-video
check-clang-video:
	$(MAKE) CC=clang BUILD=build-clang $(VIDEO_SRC:%=build-clang/video/%.o)
