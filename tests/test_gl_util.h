/* Shared by the GL backend's tests: whether an OpenGL 4.3 context can be had. */
#ifndef TEST_GL_UTIL_H
#define TEST_GL_UTIL_H

#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"

/* No GL at all (no EGL display) is a reason to skip; a display without
 * OpenGL 4.3 is a failure: CI has Mesa, whose llvmpipe gives 4.5. Forced
 * onto software rendering, as CI has no GPU (setenv: _GNU_SOURCE before
 * the first include). */
static inline void need_gl(void)
{
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    sph_gpu_register();
    char dev[512];
    if (sph_gpu_probe(dev, sizeof dev)) return;
    if (strstr(dev, "eglGetPlatformDisplay") || strstr(dev, "EGL_MESA_platform_surfaceless") ||
        strstr(dev, "eglInitialize"))
        cr_skip_test("no EGL display on this machine: %s", dev);
    cr_assert_fail("an EGL display but no OpenGL 4.3 context: %s", dev);
}

#endif
