# GL compute backend (src/gpu/): the passes as GLSL compute shaders
# (shaders/gpu_*.comp), OpenGL 4.3 through the GL platform layer (src/gl/:
# its EGL context or one shared with it, its GL table and program builder).
# Included by the top Makefile.

GPU_OBJ := $(BUILD)/gpu/gpu_backend.o $(BUILD)/gpu/gpu_passes.o $(BUILD)/gpu/gpu_program.o $(BUILD)/gpu/gpu_timing.o $(BUILD)/gpu/gpu_stats.o $(BUILD)/gpu/gpu_health.o

MOD_OBJ       += $(GPU_OBJ)
# A module library: linked before the GL layer (libsphgl.a) and the core.
MOD_TEST_LIBS += $(BUILD)/gpu/libgpu.a

$(BUILD)/sphlab-tests: $(BUILD)/gpu/libgpu.a

$(BUILD)/gpu/libgpu.a: $(GPU_OBJ)
	rm -f $@ && ar rcs $@ $^

# Compute shaders and their shared GLSL become C strings, as the renderer's.
GPU_SHADERS := $(wildcard shaders/gpu_*.comp shaders/gpu_*.glsl)
$(BUILD)/gpu/gpu_shaders.h: $(GPU_SHADERS) src/gl/embed-shaders.sh | $(BUILD)/gpu
	sh src/gl/embed-shaders.sh $(GPU_SHADERS) > $@.tmp && mv $@.tmp $@

$(BUILD)/gpu/%.o: src/gpu/%.c src/gpu/*.h src/gl/*.h src/core/*.h src/passes/solver.h src/passes/csf.h $(BUILD)/gpu/gpu_shaders.h | $(BUILD)/gpu
	$(CC) $(CFLAGS) $(CORE_CFLAGS) $(GL_CFLAGS) -Isrc/gl -Isrc/passes -I$(BUILD)/gpu -c -o $@ $<

$(BUILD)/gpu:
	mkdir -p $@

$(BUILD)/tests/test_gl_backend.o $(BUILD)/tests/test_gl_runs.o $(BUILD)/tests/test_gl_timing.o \
    $(BUILD)/tests/test_gl_sort.o $(BUILD)/tests/test_gl_stats.o \
    $(BUILD)/tests/test_gl_solvers.o $(BUILD)/tests/test_gl_fused.o $(BUILD)/tests/test_gl_health.o \
    $(BUILD)/tests/test_gl_csf.o: CORE_CFLAGS += -Isrc/gpu

# Warnings are errors under clang too.
.PHONY: check-clang-gpu
check-clang: check-clang-gpu
check-clang-gpu:
	$(MAKE) CC=clang BUILD=build-clang $(patsubst $(BUILD)/%,build-clang/%,$(GPU_OBJ))
$(BUILD)/tests/test_gl_stats.o: CORE_CFLAGS += -Isrc/overlay
