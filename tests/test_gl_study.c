/* `sphlab study` on the GL backend: its measurements read the device's state.
 * They read sim->P, which on a backend is a host copy refreshed on demand
 * (sph_sim_sync): read without it, a Taylor-Green study on GL measured no
 * decay at all (error 1 for every setting, rate 4.6e-13) and called every
 * key inert. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "study.h"
#include "test_gl_util.h"

static study_result run_on(const char *ini, const char *backend, study_metric m, long steps)
{
    sph_scene_def def = test_scene(ini);
    sph_error err;
    char set[64];
    snprintf(set, sizeof set, "compute.backend=%s", backend);
    cr_assert_eq(sph_scene_set(&def, set, &err), SPH_ERR_OK, "%s", err.msg);
    study_result r;
    char why[1024];
    cr_assert(study_run(&def, m, steps, -1, 1, NULL, NULL, &r, why, sizeof why), "%s: %s", backend, why);
    cr_assert_not(r.stopped, "%s: %s", backend, r.note);
    return r;
}

#define TG_GL_INI                                                                                                \
    "[scene]\neffects = pressure viscosity\n[domain]\nmin = 0 0\nmax = 1 1\nperiodic = x y\n"                     \
    "[fluid vortex]\nmin = 0 0\nmax = 1 1\nspacing = 0.04\nvelocity = 1 0\nfield = taylor-green\n"                 \
    "[physics]\nstiffness = 100\nviscosity = 0.05\nnegative_pressure = keep\n"                                    \
    "[kernels]\nh = 0.16\ndensity = cubic\npressure = cubic\nviscosity = cubic\n[time]\ncfl = 0.4\ndt = 0.005\n"

#define TANK_GL_INI                                                                                              \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 1 0.6\n"      \
    "[fluid water]\nmin = 0 0\nmax = 1 0.3\nspacing = 0.04\n[physics]\nstiffness = 400\nviscosity = 0.01\n"       \
    "negative_pressure = clamp\n[kernels]\nh = 0.12\ndensity = wendland\npressure = wendland\n"                   \
    "viscosity = wendland\n[time]\ncfl = 0.4\ndt = 0.002\n"

Test(gl_study, measures_the_device_state, .timeout = 300)
{
    need_gl();
    study_result c = run_on(TG_GL_INI, "cpu", STUDY_METRIC_TAYLOR_GREEN, 40);
    study_result g = run_on(TG_GL_INI, "gl", STUDY_METRIC_TAYLOR_GREEN, 40);
    cr_assert(fabs(g.error - c.error) <= 1e-3 * fabs(c.error) + 1e-6,
              "Taylor-Green decay-rate error: %g on GL, %g on the CPU", g.error, c.error);
    c = run_on(TANK_GL_INI, "cpu", STUDY_METRIC_HYDROSTATIC, 40);
    g = run_on(TANK_GL_INI, "gl", STUDY_METRIC_HYDROSTATIC, 40);
    cr_assert(fabs(g.error - c.error) <= 1e-3 * fabs(c.error) + 1e-6,
              "hydrostatic profile error: %g on GL, %g on the CPU", g.error, c.error);
}
