/* The GL compute backend: the passes of the time step as GLSL compute
 * shaders (shaders/gpu_*.comp), OpenGL 4.3 or later through an EGL
 * surfaceless context: the GPU where there is one, Mesa's llvmpipe (on the
 * CPU) where there is none. The particle data stay on the device, one buffer
 * per field; sim->P is a host copy refreshed by sph_sim_sync(). The core sees
 * only the sph_backend table (sph_sim.h); no GL header is included here. */
#ifndef SPH_GPU_H
#define SPH_GPU_H

#include <stdbool.h>
#include <stddef.h>

#include "sph_sim.h"

/* Registers the GL backend with the core, so that scenes with
 * [compute] backend = gl (or --backend gl) run on it. */
void sph_gpu_register(void);

/* The factory sph_sim_create calls (registered by sph_gpu_register). Refuses,
 * naming the key and value, scene options it does not implement, and a
 * machine without an OpenGL 4.3 context, naming the reason. */
sph_error_code sph_gpu_backend_create(sph_sim *sim, sph_backend **out, sph_error *err);

/* Whether an OpenGL 4.3 context can be made here: true with the device
 * ("GL_RENDERER, OpenGL GL_VERSION") in device; false with the reason in device. */
bool sph_gpu_probe(char *device, size_t n);

/* Per-pass timing waits for each pass to finish on the device (glFinish), so
 * that the timing table is true; off, passes are only queued and the step's
 * time lands in the integrate pass, which reads back the CFL maxima. On by
 * default; a benchmark of whole steps may switch it off. */
void sph_gpu_set_pass_sync(sph_sim *sim, bool on);

#endif
