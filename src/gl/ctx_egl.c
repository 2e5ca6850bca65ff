/* EGL context without a window: no display, no window system, no GPU needed.
 * Where EGL lists a GPU device (EGL_EXT_platform_device: NVIDIA's EGL, or
 * Mesa's with a DRM device) the context is made on it; otherwise Mesa's
 * EGL_MESA_platform_surfaceless gives a display without any window system
 * and renders with llvmpipe. We draw into a framebuffer object, so the
 * context needs no surface at all.
 * EGL itself is called through libEGL; GL through libepoxy (gl_epoxy.c). */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"

struct sph_glctx {
    sph_glctx_kind kind; /* first: see gl_context.h */
    EGLDisplay dpy;
    EGLContext ctx;
};

/* EGL displays are not reference-counted: eglTerminate ends every context on
 * the display, also those another library made on it (SDL's offscreen driver
 * opens the same device display). So sphlab never terminates a display: the
 * process's exit releases it. */

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: return "an unknown EGL error";
    }
}

static bool has_word(const char *list, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = list; p && (p = strstr(p, word)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

sph_glctx *sph_glctx_create_egl(sph_gl *gl, char *err, size_t n)
{
    return sph_glctx_create_egl_version(gl, 3, 3, err, n);
}

/* A GPU's display through EGL_EXT_platform_device: the way to a GPU without
 * a window system (NVIDIA's EGL offers no surfaceless platform). Devices that
 * are Mesa's software renderer are passed over unless `any`, since the
 * surfaceless platform gives the same llvmpipe. EGL_NO_DISPLAY if none. */
static EGLDisplay device_display(const char *ext, bool any)
{
    if (!has_word(ext, "EGL_EXT_platform_device") ||
        !(has_word(ext, "EGL_EXT_device_enumeration") || has_word(ext, "EGL_EXT_device_base")))
        return EGL_NO_DISPLAY;
    PFNEGLQUERYDEVICESEXTPROC query = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC str = (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    EGLDeviceEXT dev[16];
    EGLint count = 0;
    if (!query || !str || !query(16, dev, &count)) return EGL_NO_DISPLAY;
    for (EGLint k = 0; k < count; k++) {
        const char *dext = str(dev[k], EGL_EXTENSIONS);
        if (!any && dext && has_word(dext, "EGL_MESA_device_software")) continue;
        /* the first that starts: libglvnd may list devices of several vendors */
        EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, dev[k], NULL);
        EGLint major, minor;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
    }
    return EGL_NO_DISPLAY;
}

sph_glctx *sph_glctx_create_egl_version(sph_gl *gl, int major_want, int minor_want, char *err, size_t n)
{
    /* SPHLAB_EGL_DEVICE: unset, a GPU if EGL lists one, else surfaceless;
     * "software", surfaceless only (llvmpipe even beside a GPU); "any", the
     * first device EGL lists, software included (tests the device path);
     * "none", no context at all. */
    const char *want = getenv("SPHLAB_EGL_DEVICE");
    /* without SPHLAB_EGL_DEVICE, Mesa's LIBGL_ALWAYS_SOFTWARE also means llvmpipe
     * (`render` sets it: the same bytes on every machine, GPU or not) */
    const char *soft = getenv("LIBGL_ALWAYS_SOFTWARE");
    const bool software_only = want ? strcmp(want, "software") == 0 : soft && *soft && strcmp(soft, "0") != 0,
               any = want && strcmp(want, "any") == 0;
    if (want && strcmp(want, "none") == 0) { /* the paths without GL, on any machine (the tests) */
        snprintf(err, n, "EGL: no device (SPHLAB_EGL_DEVICE=none)");
        return NULL;
    }
    if (want && *want && strcmp(want, "software") != 0 && strcmp(want, "any") != 0) { /* a typo ran unsaid */
        snprintf(err, n, "EGL: SPHLAB_EGL_DEVICE=%.60s: unknown value (accepted: software, any, none; unset: a GPU "
                         "if EGL lists one, else software)", want);
        return NULL;
    }
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    EGLDisplay dpy = ext && !software_only ? device_display(ext, any) : EGL_NO_DISPLAY;
    if (dpy == EGL_NO_DISPLAY && (!ext || !has_word(ext, "EGL_MESA_platform_surfaceless"))) {
        snprintf(err, n, "EGL (surfaceless): this EGL has no EGL_MESA_platform_surfaceless and no GPU device "
                         "(install Debian's libegl-mesa0 and libgl1-mesa-dri, or try --gl osmesa)");
        return NULL;
    }
    sph_glctx *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, n, "EGL: out of memory");
        return NULL;
    }
    c->kind = SPH_GLCTX_EGL;
    c->dpy = dpy != EGL_NO_DISPLAY ? dpy : eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major = 0, minor = 0;
    const char *what = NULL;
    char ask[64];
    snprintf(ask, sizeof ask, "eglCreateContext (OpenGL %d.%d core)", major_want, minor_want);
    bool initialised = c->dpy != EGL_NO_DISPLAY && eglInitialize(c->dpy, &major, &minor);
    const char *kind = dpy != EGL_NO_DISPLAY ? "EGL (device)" : "EGL (surfaceless)";
    if (c->dpy == EGL_NO_DISPLAY) {
        what = "eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA)";
    } else if (!initialised) {
        what = "eglInitialize";
        c->dpy = EGL_NO_DISPLAY;
    } else if (!eglBindAPI(EGL_OPENGL_API)) {
        what = "eglBindAPI(EGL_OPENGL_API)";
    } else {
        const EGLint cfg_attr[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        const EGLint pbuf_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig cfg = NULL;
        EGLint ncfg = 0;
        if (!eglChooseConfig(c->dpy, cfg_attr, &cfg, 1, &ncfg)) ncfg = 0;
        /* a device display may list only pbuffer configs; the context still needs no surface */
        if (!ncfg && !eglChooseConfig(c->dpy, pbuf_attr, &cfg, 1, &ncfg)) ncfg = 0;
        const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, major_want, EGL_CONTEXT_MINOR_VERSION, minor_want,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        /* surfaceless contexts may have no config (EGL_KHR_no_config_context) */
        c->ctx = eglCreateContext(c->dpy, ncfg ? cfg : (EGLConfig)0, EGL_NO_CONTEXT, ctx_attr);
        if (c->ctx == EGL_NO_CONTEXT)
            what = ask;
        else if (!eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c->ctx))
            what = "eglMakeCurrent without a surface";
        else
            sph_glctx_last_current = c;
    }
    if (what) {
        snprintf(err, n, "%s: %s failed: %s (no usable OpenGL %d.%d%s)", kind, what,
                 egl_error_name(eglGetError()), major_want, minor_want,
                 major_want * 10 + minor_want <= 33 ? "; try --gl osmesa" : "");
        sph_glctx_destroy_egl(c);
        return NULL;
    }
    sph_gl_load_epoxy(gl);
    sph_gl_pin_driver();
    return c;
}

bool sph_glctx_make_current_egl(sph_glctx *c)
{
    if (sph_glctx_last_current == c && eglGetCurrentContext() == c->ctx) return true;
    sph_glctx_last_current = c;
    /* EGL skips a make-current of the context it believes current, though
     * OSMesa may have taken the thread's GL since: release it first */
    if (eglGetCurrentContext() == c->ctx) eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    return eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c->ctx);
}

void sph_glctx_destroy_egl(sph_glctx *c)
{
    if (!c) return;
    if (sph_glctx_last_current == c) sph_glctx_last_current = NULL;
    if (c->dpy != EGL_NO_DISPLAY) {
        if (eglGetCurrentContext() == c->ctx) eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (c->ctx != EGL_NO_CONTEXT) eglDestroyContext(c->dpy, c->ctx);
    }
    free(c);
}
