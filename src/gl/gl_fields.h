/* Particle fields held in GL buffers: what the GL compute backend (src/gpu/)
 * offers whoever draws (the renderer, src/render/), so that neither includes
 * the other's headers. The backend hands out one per simulation
 * (sph_gpu_fields in src/gpu/gpu.h); the window or `render` command passes
 * it to the renderer in the view it draws (sph_view.device). No GL type here. */
#ifndef SPH_GL_FIELDS_H
#define SPH_GL_FIELDS_H

#include <stdbool.h>

typedef struct sph_glctx sph_glctx;
typedef struct sph_sim sph_sim;

typedef struct sph_gl_fields {
    /* The context the buffer names are valid in: a drawer reads them straight
     * only if it draws in that very context. */
    const sph_glctx *ctx;
    /* The GL name of the buffer holding field `field` (an sph_field_id) of
     * sim now, component d of particle i at float d * N + i; false if the
     * backend lacks it. The reorder pass swaps buffers every step: ask again
     * every frame. */
    bool (*buffer)(const sph_sim *sim, int field, unsigned *gl_name);
    /* Computes on the device the smallest and largest finite value of the
     * field (norm: of its vectors' lengths) into a buffer of 4 uints named in
     * *gl_name (ordered keys: see src/gpu/gpu.h); lo_hi non-NULL: also reads
     * the two floats back (8 bytes). The backend makes its context current
     * for this: a drawer makes its own current again afterwards. */
    bool (*range)(const sph_sim *sim, int field, bool norm, unsigned *gl_name, float lo_hi[2]);
} sph_gl_fields;

#endif
