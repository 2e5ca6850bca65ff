/* GL contexts, one handle type for every kind: EGL (surfaceless, or on a
 * device), OSMesa, and the caller's (a context another library made current,
 * such as SDL's window). Making one fills the GL table (gl_table.h); on
 * failure the reason, naming the kind and the call that failed, is in err.
 *
 * The handle is what the renderer (src/render/) and the GL compute backend
 * (src/gpu/) pass between them: a simulation created with a context to share
 * (sph_sim_create_shared) runs its passes in it, and a renderer drawing in
 * the same context reads its buffers (gl_fields.h). */
#ifndef SPH_GL_CONTEXT_H
#define SPH_GL_CONTEXT_H

#include <stdbool.h>
#include <stddef.h>

#include "gl_table.h"

typedef struct sph_glctx sph_glctx;

/* Every kind of context starts with its kind, so that a pointer to any of
 * them tells which it is. */
typedef enum sph_glctx_kind { SPH_GLCTX_EGL = 1, SPH_GLCTX_OSMESA, SPH_GLCTX_CALLER } sph_glctx_kind;
sph_glctx_kind sph_glctx_kind_of(const sph_glctx *c);

sph_glctx *sph_glctx_create_egl(sph_gl *gl, char *err, size_t n); /* OpenGL 3.3 core (the renderer) */
/* OpenGL major.minor core or later (the GL compute backend asks for 4.3). */
sph_glctx *sph_glctx_create_egl_version(sph_gl *gl, int major, int minor, char *err, size_t n);
sph_glctx *sph_glctx_create_osmesa(sph_gl *gl, char *err, size_t n);
/* The context current on this thread, made by someone else (SDL): fills gl
 * from libepoxy. Keeping it current is the caller's job; destroying the
 * handle leaves the context alone. NULL only when out of memory. */
sph_glctx *sph_glctx_create_caller(sph_gl *gl, char *err, size_t n);

/* Makes c current again after another context was (the renderer and a GL
 * simulation with a context of its own take turns); false if EGL or OSMesa
 * refuses. The caller's context: nothing to do (the caller keeps it current). */
bool sph_glctx_make_current(sph_glctx *c);
void sph_glctx_destroy(sph_glctx *c); /* any kind; NULL is fine */

/* The context sphlab made current last (NULL: none or unknown). GL calls go
 * to the thread's current context whichever library made it current, and
 * each library knows only its own, so sphlab remembers its own. A window
 * that makes its own context current again calls sph_glctx_forget_current(). */
extern sph_glctx *sph_glctx_last_current;
void sph_glctx_forget_current(void);

/* Keeps the GL driver's modules (Mesa's dri and gallium libraries) loaded
 * until exit, once a context exists: Mesa unloads its driver when the last
 * display goes, and what the driver keeps until exit would then be reported
 * by LeakSanitizer from an "unknown module" that no suppression
 * (tests/lsan.supp) can name. Harmless otherwise: the driver stays loaded for
 * the process's life anyway. Called by every context's creation. */
void sph_gl_pin_driver(void);

/* The kinds' own calls (ctx_egl.c, ctx_osmesa.c), dispatched by the above. */
bool sph_glctx_make_current_egl(sph_glctx *c);
bool sph_glctx_make_current_osmesa(sph_glctx *c);
void sph_glctx_destroy_egl(sph_glctx *c);
void sph_glctx_destroy_osmesa(sph_glctx *c);

#endif
