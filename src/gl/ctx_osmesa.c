/* OSMesa context: Mesa's off-screen library, linked directly. libepoxy cannot
 * dispatch GL under it (epoxy knows GLX and EGL contexts only, and aborts
 * when it finds neither), so the GL table is filled from
 * OSMesaGetProcAddress instead (see gl_table.h). */
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"

typedef struct osmesa_ctx {
    sph_glctx_kind kind; /* first: see gl_context.h */
    OSMesaContext ctx;
    unsigned char buf[16 * 16 * 4]; /* the default framebuffer; we draw into an FBO */
} osmesa_ctx;

static void *getproc(const char *name)
{
    OSMESAproc p = OSMesaGetProcAddress(name);
    void *v;
    memcpy(&v, &p, sizeof v);
    return v;
}

sph_glctx *sph_glctx_create_osmesa(sph_gl *gl, char *err, size_t n)
{
    osmesa_ctx *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, n, "OSMesa: out of memory");
        return NULL;
    }
    const int attr[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 0,
                        OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                        OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    c->kind = SPH_GLCTX_OSMESA;
    c->ctx = OSMesaCreateContextAttribs(attr, NULL);
    if (!c->ctx) {
        snprintf(err, n, "OSMesa: OSMesaCreateContextAttribs (OpenGL 3.3 core) failed (no usable OpenGL; try --gl egl)");
        free(c);
        return NULL;
    }
    sph_glctx_last_current = (sph_glctx *)c;
    if (!OSMesaMakeCurrent(c->ctx, c->buf, GL_UNSIGNED_BYTE, 16, 16)) {
        snprintf(err, n, "OSMesa: OSMesaMakeCurrent failed");
        OSMesaDestroyContext(c->ctx);
        free(c);
        return NULL;
    }
    const char *missing = sph_gl_load_by_name(gl, getproc);
    if (missing) {
        snprintf(err, n, "OSMesa: OSMesaGetProcAddress has no %s", missing);
        OSMesaDestroyContext(c->ctx);
        free(c);
        return NULL;
    }
    sph_gl_pin_driver();
    return (sph_glctx *)c;
}

bool sph_glctx_make_current_osmesa(sph_glctx *ctx)
{
    osmesa_ctx *c = (osmesa_ctx *)ctx;
    if (sph_glctx_last_current == ctx && OSMesaGetCurrentContext() == c->ctx) return true;
    sph_glctx_last_current = ctx;
    return OSMesaMakeCurrent(c->ctx, c->buf, GL_UNSIGNED_BYTE, 16, 16);
}

void sph_glctx_destroy_osmesa(sph_glctx *ctx)
{
    osmesa_ctx *c = (osmesa_ctx *)ctx;
    if (!c) return;
    if (sph_glctx_last_current == ctx) sph_glctx_last_current = NULL;
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(c->ctx);
    free(c);
}
