/* Headless GL contexts: EGL surfaceless (default) and OSMesa. Each makes its
 * context current and fills the GL table (gl_table.h); on failure it names
 * the backend and the call that failed in err. */
#ifndef SPH_GL_CONTEXT_H
#define SPH_GL_CONTEXT_H

#include <stddef.h>

#include "gl_table.h"

typedef struct sph_glctx sph_glctx;

sph_glctx *sph_glctx_create_egl(sph_gl *gl, char *err, size_t n);
sph_glctx *sph_glctx_create_osmesa(sph_gl *gl, char *err, size_t n);
void sph_glctx_destroy(sph_glctx *c);        /* EGL */
void sph_glctx_destroy_osmesa(sph_glctx *c); /* OSMesa */

#endif
