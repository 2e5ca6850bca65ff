/* Fills the GL table from libepoxy (the EGL and SDL backends). epoxy/gl.h
 * defines each glFoo as a pointer to a resolver that looks the function up
 * in the current context on first call; copying the pointer is enough. */
#include <epoxy/gl.h>

#include <string.h>

#include "gl_table.h"

void sph_gl_load_epoxy(sph_gl *gl)
{
#define SPH_GL_FROM_EPOXY(ret, name, params) gl->name = gl##name;
    SPH_GL_FUNCS(SPH_GL_FROM_EPOXY)
#undef SPH_GL_FROM_EPOXY
}

void sph_gl_load_compute_epoxy(sph_gl_compute *gl)
{
#define SPH_GL_FROM_EPOXY(ret, name, params) gl->name = gl##name;
    SPH_GL_COMPUTE_FUNCS(SPH_GL_FROM_EPOXY)
#undef SPH_GL_FROM_EPOXY
}

const char *sph_gl_load_by_name(sph_gl *gl, void *(*getproc)(const char *name))
{
    /* ISO C forbids converting void * to a function pointer; POSIX allows it
     * (dlsym), and memcpy of the representation is the portable spelling. */
#define SPH_GL_BY_NAME(ret, name, params)                       \
    {                                                           \
        void *p = getproc("gl" #name);                          \
        if (!p) return "gl" #name;                              \
        memcpy(&gl->name, &p, sizeof p);                        \
    }
    SPH_GL_FUNCS(SPH_GL_BY_NAME)
#undef SPH_GL_BY_NAME
    return NULL;
}
