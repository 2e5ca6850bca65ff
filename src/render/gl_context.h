/* Headless GL contexts: EGL surfaceless (default) and OSMesa. Each makes its
 * context current and fills the GL table (gl_table.h); on failure it names
 * the backend and the call that failed in err. */
#ifndef SPH_GL_CONTEXT_H
#define SPH_GL_CONTEXT_H

#include <stdbool.h>
#include <stddef.h>

#include "gl_table.h"

typedef struct sph_glctx sph_glctx;

sph_glctx *sph_glctx_create_egl(sph_gl *gl, char *err, size_t n); /* OpenGL 3.3 core (the renderer) */
/* OpenGL major.minor core or later (the GL compute backend asks for 4.3). */
sph_glctx *sph_glctx_create_egl_version(sph_gl *gl, int major, int minor, char *err, size_t n);
/* Makes the context current again after another one was (the renderer and
 * the GL compute backend each have theirs); false if EGL refuses. */
bool sph_glctx_make_current(sph_glctx *c);
bool sph_glctx_make_current_osmesa(sph_glctx *c);
/* Both kinds of context start with their kind, so that a pointer to either
 * (sph_glctx_last_current may hold an OSMesa one) can tell which it is. */
typedef enum sph_glctx_kind { SPH_GLCTX_EGL = 1, SPH_GLCTX_OSMESA } sph_glctx_kind;
/* The context sphlab made current last (NULL: none or unknown). A window
 * that makes its own context current calls sph_glctx_forget_current(). */
extern sph_glctx *sph_glctx_last_current;
void sph_glctx_forget_current(void);
/* The sphlab EGL context current on this thread, or NULL (none, or another
 * library's, such as SDL's): what a GL simulation adopting the current
 * context makes current again before its passes. */
sph_glctx *sph_glctx_current(void);
sph_glctx *sph_glctx_create_osmesa(sph_gl *gl, char *err, size_t n);
void sph_glctx_destroy(sph_glctx *c);        /* EGL */
void sph_glctx_destroy_osmesa(sph_glctx *c); /* OSMesa */

#endif
