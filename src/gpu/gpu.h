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
#include <stdint.h>

#include "sph_sim.h"

/* src/gl/gl_fields.h; only a pointer to it passes through here. */
typedef struct sph_gl_fields sph_gl_fields;

/* Registers the GL backend with the core, so that scenes with
 * [compute] backend = gl (or --backend gl) run on it. */
void sph_gpu_register(void);

/* The factory sph_sim_create calls (registered by sph_gpu_register). share:
 * NULL, an EGL surfaceless context of its own; else an sph_glctx
 * (src/gl/gl_context.h) to run in, OpenGL 4.3 core or later, which the caller
 * (the window, the renderer) keeps alive until the simulation is destroyed.
 * Refuses, naming the key and value, scene options it does not implement,
 * and a machine or shared context without OpenGL 4.3, naming the reason. */
sph_error_code sph_gpu_backend_create(sph_sim *sim, void *share, sph_backend **out, sph_error *err);

/* Whether an OpenGL 4.3 context can be made here: true with the device
 * ("GL_RENDERER, OpenGL GL_VERSION") in device; false with the reason in device. */
bool sph_gpu_probe(char *device, size_t n);

/* Per-pass times come from timer queries where the context has them
 * (GL_TIMESTAMP before and after each pass, read back a step or more later:
 * nothing waits; sph_backend.timing says which method runs). Without them,
 * or with the queries off, each pass waits for the device (glFinish) so that
 * the host clock's table is true; with pass_sync off too, passes are only
 * queued and the step's time lands in the integrate pass, which reads back
 * the CFL maxima. pass_sync is on by default; a benchmark of whole steps may
 * switch it off. */
void sph_gpu_set_pass_sync(sph_sim *sim, bool on);
/* Timer queries on (the default where the context has them) or off; returns
 * whether they are on now (false: not on the GL backend, or none). */
bool sph_gpu_set_timer_queries(sph_sim *sim, bool on);
/* glFinish calls the passes have made since creation (a debug counter: 0
 * with timer queries on). 0 if sim is not on the GL backend. */
uint64_t sph_gpu_finish_count(const sph_sim *sim);

/* ---- drawing from the device's buffers ------------------------------------
 * A window or renderer that draws in the simulation's own context reads the
 * particles where they are: any buffer object can be a vertex source. */

/* The buffers of sim for a drawer (src/gl/gl_fields.h: their context, and
 * the two calls below); NULL if sim is not on the GL backend. */
const sph_gl_fields *sph_gpu_fields(const sph_sim *sim);
/* The GL name (a plain unsigned: no GL header here) of the buffer holding
 * field f now, laid out as component d of particle i at float d * N + i.
 * The reorder pass swaps buffers every step, so ask for it every frame;
 * particles are in the sorted order (their ids in no buffer asked for here).
 * False if sim is not on the GL backend or lacks the field. */
bool sph_gpu_field_buffer(const sph_sim *sim, sph_field_id f, unsigned *gl_name);
/* Computes on the device the smallest and largest finite value of field f
 * (norm: of its vectors' lengths) into a buffer of 4 uints, named in
 * *gl_name: [0] and [1] are the min and max as ordered keys (a float's bits,
 * all flipped if negative, else with the sign bit set; min > max: no finite
 * value). lo_hi non-NULL: also reads the two floats back (8 bytes; 0 and 0 if
 * none). False if sim is not on the GL backend or lacks the field. */
bool sph_gpu_field_range(const sph_sim *sim, sph_field_id f, bool norm, unsigned *gl_name, float lo_hi[2]);
/* The hash health (sph_hash_health.h) computed on the device whatever the
 * host copy (sph_sim_hash_health does so only when that copy is stale): the
 * figures without the neighbour count (neighbours and share NaN), 20 bytes
 * read back. False if sim is not on the GL backend or has no hash table. */
struct sph_hash_health;
bool sph_gpu_hash_health(const sph_sim *sim, struct sph_hash_health *out);
/* Bytes this simulation's backend copied to the host so far: sph_sim_sync's
 * downloads and range reads (not the integrate pass's 8-byte CFL maxima,
 * which every step reads). 0 if sim is not on the GL backend. */
uint64_t sph_gpu_downloaded_bytes(const sph_sim *sim);

#endif
