/* surface_tension = csf (shaders/gpu_csf.comp, with gpu_normals.comp's
 * volumes m_j / rho0) and viscosity_form = morris-artificial
 * (shaders/gpu_force_terms.glsl, both the viscosity shader and the fused
 * walk) on the GL backend against the CPU. Pass by pass: before each pass
 * the GL simulation takes the CPU's state, and what a force pass wrote must
 * agree within the force tolerance of tests/test_gl_backend.c; whole runs of
 * separate simulations: the positions within its whole-run tolerance. A
 * square drop held by csf (its corners curved, its sides flat), 2D and 3D,
 * and a jittered block with walls for the viscosity. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "test_gl_util.h"
#include "test_util.h"

#define TOL_FORCE 1e-5   /* as tests/test_gl_backend.c: of the field's largest magnitude on the CPU */
#define TOL_POS_RUN 1e-4 /* [m] positions after a whole run, as there */

/* A square of 17 x 17 particles without gravity, pulled round by csf at
 * sigma = 1 N (the drop of scenes/validate/drop.ini at twice its spacing). */
static const char *drop_2d =
    "[scene]\nname=gl csf 2d\ndimension=2\neffects=pressure viscosity\njitter=0.1\n"
    "[domain]\nmin=0 0\nmax=1 1\n"
    "[fluid drop]\nmin=0.415 0.415\nmax=0.585 0.585\nspacing=0.01\n"
    "[physics]\nstiffness=100\nnegative_pressure=clamp\nviscosity=0.0001\nsurface_tension=csf\nsigma=1\n"
    "[kernels]\nh=0.03\ndensity=cubic\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.4\ndt=0.001\n";

/* A cube of 8^3 particles: the two tangents of csf_div. */
static const char *drop_3d =
    "[scene]\nname=gl csf 3d\ndimension=3\neffects=pressure viscosity\njitter=0.1\n"
    "[domain]\nmin=0 0 0\nmax=1 1 1\n"
    "[fluid drop]\nmin=0.42 0.42 0.42\nmax=0.58 0.58 0.58\nspacing=0.02\n"
    "[physics]\nstiffness=100\nnegative_pressure=clamp\nviscosity=0.0001\nsurface_tension=csf\nsigma=1\n"
    "[kernels]\nh=0.06\ndensity=cubic\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.4\ndt=0.001\n";

/* tests/test_gl_backend.c's moving block, with morris-artificial (Morris
 * needs a kernel with W'(0) = 0: cubic). */
static const char *block_2d =
    "[scene]\nname=gl morris-artificial 2d\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n"
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\nviscosity_form=morris-artificial\nalpha=0.5\n"
    "[kernels]\nh=0.04\nviscosity=cubic\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n";

static const char *block_3d =
    "[scene]\nname=gl morris-artificial 3d\ndimension=3\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.2 -0.2 -0.2\nmax=0.2 0.2 0.2\nwall_damping=0.3\n"
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\nviscosity_form=morris-artificial\nalpha=0.5\n"
    "gravity=0 -9.81 0\n[kernels]\nh=0.05\nviscosity=cubic\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.2 -0.2 -0.2\nmax=0.0 0.0 0.0\nspacing=0.025\nvelocity=0 0 0.3\n";




/* One step in lockstep; the fields each listed pass wrote are compared and
 * must not be zero everywhere. Returns how many of the listed passes ran. */
static int lockstep(sph_sim *c, sph_sim *g, const sph_pass_id *check, int n_check, const char *what)
{
    int seen = 0;
    do {
        /* not before viscosity: with fuse_forces = on GL's pressure_force walk wrote acc_v */
        if (c->next_pass != SPH_PASS_VISCOSITY) test_gl_copy_state(g, c);
        sph_pass_id pc = sph_sim_step_pass(c), pg = sph_sim_step_pass(g);
        cr_assert_eq(pc, pg, "%s: the backends ran different passes", what);
        bool listed = false;
        for (int k = 0; k < n_check; k++) listed |= check[k] == pc;
        if (!listed) continue;
        seen++;
        for (int f = 0; f < SPH_FIELD_COUNT; f++) {
            if (!(sph_passes[pc]->writes & SPH_FIELD_BIT(f))) continue;
            double scale, err = test_gl_field_error(c, g, (sph_field_id)f, &scale);
            cr_expect(scale > 0, "%s, %s: field %s is zero everywhere", what, sph_passes[pc]->name,
                      sph_field_infos[f].name);
            cr_expect(err <= TOL_FORCE * scale, "%s, %s: field %s differs by %.3g, above %.1g of its scale %.4g", what,
                      sph_passes[pc]->name, sph_field_infos[f].name, err, TOL_FORCE, scale);
            if (getenv("SPH_TEST_VERBOSE"))
                fprintf(stderr, "%-28s %-14s %-6s error %.3g of scale %.4g: %.2g\n", what, sph_passes[pc]->name,
                        sph_field_infos[f].name, err, scale, scale > 0 ? err / scale : 0.0);
        }
    } while (c->next_pass != 0);
    return seen;
}

static void lockstep_steps(const char *ini, const char *const *sets, int n_sets, const sph_pass_id *check,
                           int n_check, int steps, const char *what)
{
    need_gl();
    sph_sim *c = test_gl_make(ini, sets, n_sets, false), *g = test_gl_make(ini, sets, n_sets, true);
    for (int s = 0; s < 3; s++) sph_sim_step(c); /* the fluid moves before the checked steps */
    int seen = 0;
    for (int s = 0; s < steps; s++) seen += lockstep(c, g, check, n_check, what);
    cr_expect_eq(seen, steps * n_check, "%s: %d of the checked passes ran in %d steps", what, seen, steps);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

/* Separate simulations: after `steps` steps the positions agree within
 * TOL_POS_RUN, matched by id, and the fluid has moved. */
static void whole_run(const char *ini, const char *const *sets, int n_sets, int steps, const char *what)
{
    need_gl();
    sph_sim *c = test_gl_make(ini, sets, n_sets, false), *g = test_gl_make(ini, sets, n_sets, true);
    for (int s = 0; s < steps; s++) {
        sph_sim_step(c);
        sph_sim_step(g);
    }
    cr_assert(!g->alarm.raised && !c->alarm.raised, "%s: the watchdog stopped a run", what);
    cr_expect(fabs(g->t - c->t) <= 1e-6 * c->t, "%s: simulated time %g on GL, %g on the CPU", what, g->t, c->t);
    sph_sim_sync(g, SPH_SYNC_ALL);
    sph_sim *c0 = test_gl_make(ini, sets, n_sets, false);
    uint32_t *where = malloc(c->n * sizeof *where), *start = malloc(c->n * sizeof *start);
    cr_assert(where && start);
    for (uint32_t i = 0; i < g->n; i++) where[g->P.id[i]] = i;
    for (uint32_t i = 0; i < c0->n; i++) start[c0->P.id[i]] = i;
    double err = 0, moved = 0;
    for (uint32_t i = 0; i < c->n; i++)
        for (int d = 0; d < c->dim; d++) {
            err = fmax(err, fabs((double)g->P.pos[d][where[c->P.id[i]]] - c->P.pos[d][i]));
            moved = fmax(moved, fabs((double)c0->P.pos[d][start[c->P.id[i]]] - c->P.pos[d][i]));
        }
    free(where);
    free(start);
    if (getenv("SPH_TEST_VERBOSE"))
        fprintf(stderr, "%s, %d steps (%.4g s): positions differ by %.3g m, the fluid moved up to %.3g m\n", what,
                steps, c->t, err, moved);
    cr_expect(moved > 10 * TOL_POS_RUN, "%s: the fluid moved %.3g m at most in %d steps", what, moved, steps);
    cr_expect(err <= TOL_POS_RUN, "%s: positions after %d steps differ by %.3g m (tolerance %g m)", what, steps, err,
              TOL_POS_RUN);
    sph_sim_destroy(c0);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

static const sph_pass_id csf_passes[] = {SPH_PASS_NORMALS, SPH_PASS_CSF};
static const sph_pass_id visc_passes[] = {SPH_PASS_PRESSURE_FORCE, SPH_PASS_VISCOSITY};

Test(gl_csf, csf_passes_match_cpu_2d_3d)
{
    lockstep_steps(drop_2d, NULL, 0, csf_passes, 2, 2, "csf 2d hash");
    const char *grid[] = {"search.method=grid"};
    lockstep_steps(drop_2d, grid, 1, csf_passes, 2, 1, "csf 2d grid rows");
    lockstep_steps(drop_3d, NULL, 0, csf_passes, 2, 1, "csf 3d");
}

/* Wall particles: they get no normal and no force, and are left out of the sums. */
Test(gl_csf, csf_passes_match_cpu_wall_particles)
{
    const char *sets[] = {"domain.wall_model=particles", "scene.effects=pressure viscosity walls",
                          "fluid.drop.min=0.415 0.0", "fluid.drop.max=0.585 0.17"};
    lockstep_steps(drop_2d, sets, 4, csf_passes, 2, 1, "csf 2d wall particles");
}

Test(gl_csf, csf_drop_run_matches_cpu, .timeout = 300)
{
    whole_run(drop_2d, NULL, 0, 60, "csf drop 2d");
}

Test(gl_csf, morris_artificial_passes_match_cpu)
{
    const char *apart[] = {"compute.fuse_forces=off"}, *fused[] = {"compute.fuse_forces=on"};
    lockstep_steps(block_2d, apart, 1, visc_passes, 2, 2, "morris-artificial 2d");
    lockstep_steps(block_2d, fused, 1, visc_passes, 2, 1, "morris-artificial 2d fused");
    lockstep_steps(block_3d, apart, 1, visc_passes, 2, 1, "morris-artificial 3d");
    /* the neighbours' vel_visc (a no-slip wall's mirrored velocity) in Morris's term only */
    const char *walls[] = {"domain.wall_model=particles", "domain.wall_slip_ymin=free", "physics.eos=tait"};
    lockstep_steps(block_2d, walls, 3, visc_passes, 2, 1, "morris-artificial wall particles");
}

Test(gl_csf, morris_artificial_run_matches_cpu, .timeout = 300)
{
    whole_run(block_2d, NULL, 0, 40, "morris-artificial 2d");
    const char *fused[] = {"compute.fuse_forces=on"};
    whole_run(block_2d, fused, 1, 40, "morris-artificial 2d fused");
}
