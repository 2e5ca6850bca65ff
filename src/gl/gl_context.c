/* What all kinds of context share: the one sphlab made current last, the
 * caller's context, and the calls that dispatch on a context's kind. */
#define _GNU_SOURCE /* dl_iterate_phdr, RTLD_NOLOAD, RTLD_NODELETE */
#include <dlfcn.h>
#include <link.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"

sph_glctx *sph_glctx_last_current;

/* The caller's context: nothing but its kind (see gl_context.h). */
typedef struct caller_ctx {
    sph_glctx_kind kind; /* first */
} caller_ctx;

sph_glctx_kind sph_glctx_kind_of(const sph_glctx *c)
{
    return *(const sph_glctx_kind *)(const void *)c;
}

static int pin_module(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size, (void)data;
    if (info->dlpi_name && (strstr(info->dlpi_name, "/dri/") || strstr(info->dlpi_name, "gallium")))
        dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    return 0;
}

void sph_gl_pin_driver(void)
{
    dl_iterate_phdr(pin_module, NULL);
}

void sph_glctx_forget_current(void)
{
    sph_glctx_last_current = NULL;
}

sph_glctx *sph_glctx_create_caller(sph_gl *gl, char *err, size_t n)
{
    caller_ctx *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, n, "out of memory");
        return NULL;
    }
    c->kind = SPH_GLCTX_CALLER;
    sph_gl_load_epoxy(gl);
    sph_gl_pin_driver();
    return (sph_glctx *)(void *)c;
}

bool sph_glctx_make_current(sph_glctx *c)
{
    switch (sph_glctx_kind_of(c)) {
    case SPH_GLCTX_EGL: return sph_glctx_make_current_egl(c);
    case SPH_GLCTX_OSMESA: return sph_glctx_make_current_osmesa(c);
    default: return true;
    }
}

void sph_glctx_destroy(sph_glctx *c)
{
    if (!c) return;
    switch (sph_glctx_kind_of(c)) {
    case SPH_GLCTX_EGL: sph_glctx_destroy_egl(c); break;
    case SPH_GLCTX_OSMESA: sph_glctx_destroy_osmesa(c); break;
    default:
        if (sph_glctx_last_current == c) sph_glctx_last_current = NULL;
        free(c);
    }
}
