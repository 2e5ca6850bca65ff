# GL compute backend (src/gpu/): the passes as GLSL compute shaders
# (shaders/gpu_*.comp), OpenGL 4.3 through the render module's EGL
# surfaceless context and GL table. Included by the top Makefile.

GPU_OBJ := $(BUILD)/gpu/gpu_backend.o

MOD_OBJ       += $(GPU_OBJ)
# The tests link the backend from a library before the render library (its
# EGL context and GL table), which draws from the backend's buffers, so the
# backend comes again after it; then the core again.
MOD_TEST_LIBS += $(BUILD)/gpu/libgpu.a $(BUILD)/render/librender.a $(BUILD)/gpu/libgpu.a $(BUILD)/libsphcore.a \
                 $(RENDER_LIBS)

$(BUILD)/sphlab-tests: $(BUILD)/gpu/libgpu.a

$(BUILD)/gpu/libgpu.a: $(GPU_OBJ)
	ar rcs $@ $^

# Compute shaders and their shared GLSL become C strings, as the render module's.
GPU_SHADERS := $(wildcard shaders/gpu_*.comp shaders/gpu_*.glsl)
$(BUILD)/gpu/gpu_shaders.h: $(GPU_SHADERS) src/render/embed-shaders.sh | $(BUILD)/gpu
	sh src/render/embed-shaders.sh $(GPU_SHADERS) > $@.tmp && mv $@.tmp $@

$(BUILD)/gpu/%.o: src/gpu/%.c src/gpu/*.h src/render/gl_table.h src/render/gl_context.h src/core/*.h \
                  $(BUILD)/gpu/gpu_shaders.h | $(BUILD)/gpu
	$(CC) $(CFLAGS) $(CORE_CFLAGS) $(RENDER_CFLAGS) -Isrc/render -I$(BUILD)/gpu -c -o $@ $<

$(BUILD)/gpu:
	mkdir -p $@

$(BUILD)/tests/test_gl_backend.o: CORE_CFLAGS += -Isrc/gpu

# Warnings are errors under clang too.
.PHONY: check-clang-gpu
check-clang: check-clang-gpu
check-clang-gpu:
	$(MAKE) CC=clang BUILD=build-clang $(patsubst $(BUILD)/%,build-clang/%,$(GPU_OBJ))
