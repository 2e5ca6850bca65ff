/* The statistics reduced on the GL device (src/gpu/gpu_stats.c,
 * shaders/gpu_stats*.comp) against the CPU's sums over the downloaded
 * fields (sph_sim_stats on a fresh host copy): the same figures within
 * float rounding, read back as 48 bytes instead of five fields. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "sph_overlay.h"
#include "test_gl_util.h"
#include "test_util.h"


static void near(const char *what, double dev, double host, double tol)
{
    cr_expect(fabs(dev - host) <= tol, "%s: device %.9g, host %.9g (tolerance %.3g)", what, dev, host, tol);
}

static void check_stats(const char *ini, int steps)
{
    sph_scene_def def = test_scene(ini);
    def.backend = SPH_BACKEND_GL;
    sph_sim *sim;
    sph_error err;
    cr_assert_eq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    for (int s = 0; s < steps; s++) sph_sim_step(sim);
    cr_assert(sim->backend->stale & SPH_SYNC_FIELD(SPH_FIELD_VEL), "the host copy is stale after a step");
    uint64_t before = sph_gpu_downloaded_bytes(sim);
    sph_stats d, h;
    sph_sim_stats(sim, &d);
    cr_assert_eq(sph_gpu_downloaded_bytes(sim) - before, 48, "12 floats read back, not the fields (%llu bytes)",
                 (unsigned long long)(sph_gpu_downloaded_bytes(sim) - before));
    double err_dev = sph_density_error(sim);
    /* nothing ran since: the same reduction, not read back again */
    cr_assert_eq(sph_gpu_downloaded_bytes(sim) - before, 48, "the density error read back %llu bytes more",
                 (unsigned long long)(sph_gpu_downloaded_bytes(sim) - before - 48));
    sph_sim_sync(sim, SPH_SYNC_ALL);
    sph_sim_stats(sim, &h); /* the host copy is fresh: summed here in double */
    cr_assert_eq(d.n, h.n);
    const double e_scale = fabs(h.ekin) + fabs(h.epot) + fabs(h.eint);
    near("kinetic energy", d.ekin, h.ekin, 1e-5 * e_scale);
    near("gravitational energy", d.epot, h.epot, 1e-5 * e_scale);
    near("internal energy", d.eint, h.eint, 1e-5 * e_scale + 1e-3 * fabs(h.eint));
    double mass = 0;
    for (uint32_t i = 0; i < sim->n; i++) mass += sim->P.mass[i];
    for (int k = 0; k < sim->dim; k++) near("momentum", d.momentum[k], h.momentum[k], 1e-5 * mass * (h.max_speed + 1e-3));
    cr_expect_eq(d.rho_min, h.rho_min, "density min: the same float");
    cr_expect_eq(d.rho_max, h.rho_max, "density max: the same float");
    cr_expect_eq(d.rho_max_all, h.rho_max_all, "density max of all particles: the same float");
    near("density mean", d.rho_mean, h.rho_mean, 1e-5 * h.rho_mean);
    near("max speed", d.max_speed, h.max_speed, 1e-6 * h.max_speed);
    /* the HUD's density error, reduced and from the host copy */
    const double held = sph_density_held(sim, NULL); /* the fluid's, against the held density */
    near("density error", err_dev, (h.rho_max - held) / held, 1e-12);
    cr_assert(h.ekin > 0 && h.rho_max > 0, "a moving fluid with a density");
    /* a step later the kept reduction is not reused */
    sph_sim_step(sim);
    before = sph_gpu_downloaded_bytes(sim);
    sph_stats d2;
    sph_sim_stats(sim, &d2);
    cr_expect_eq(sph_gpu_downloaded_bytes(sim) - before, 48, "a new step: reduced and read back again");
    cr_expect(d2.ekin != d.ekin, "the kinetic energy of the step before (%.9g)", d.ekin);
    sph_sim_destroy(sim);
}

Test(gl_stats, reduced_on_the_device_as_on_the_host_2d)
{
    need_gl();
    check_stats("[scene]\nname=gl stats\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
                "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n"
                "[physics]\nviscosity=0.005\n[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n"
                "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n",
                20);
}

Test(gl_stats, reduced_on_the_device_as_on_the_host_3d_tait)
{
    need_gl();
    check_stats("[scene]\nname=gl stats 3d\ndimension=3\neffects=gravity pressure viscosity walls\njitter=0.2\n"
                "[domain]\nmin=-0.2 -0.2 -0.2\nmax=0.2 0.2 0.2\nwall_damping=0.3\n"
                "[physics]\neos=tait\nnegative_pressure=clamp\nviscosity=0.005\ngravity=0 -9.81 0\n"
                "[kernels]\nh=0.05\n[time]\ndt=0.001\ncfl=0.4\n"
                "[fluid a]\nmin=-0.2 -0.2 -0.2\nmax=0.0 0.0 0.0\nspacing=0.025\nvelocity=0 0 0.3\n",
                15);
}
