/* [compute] fuse_forces = on on the GL backend: one walk of the neighbours
 * (shaders/gpu_forces.comp, run as the pressure_force pass) writes both the
 * pressure force and the viscosity, and the viscosity pass does nothing.
 * Three simulations of one scene step pass by pass: the CPU, GL with the
 * passes apart and GL fused. Before every pass but viscosity both GL ones
 * take the CPU's state; before pressure_force their acc_v is poisoned (NaN),
 * so that the fused walk must have written it and the unfused
 * pressure_force must not have. After the viscosity pass acc_p and acc_v
 * must agree: fused with unfused, and both with the CPU, within the GL
 * tests' force tolerance (tests/test_gl_backend.c). Every form the two
 * shaders have: both pressure forms, the four viscosity forms, the three
 * wall models, the grid's stencil rows, 2D and 3D. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "test_gl_util.h"
#include "test_util.h"

#define TOL_FORCE 1e-5       /* as tests/test_gl_backend.c: of the field's largest magnitude on the CPU */
#define TOL_FUSED_GL 1e-6    /* fused against apart on GL: the same terms in the same order */

static const char *scene_2d =
    "[scene]\nname=gl fused 2d\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n"
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\n"
    "[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n";

static const char *scene_3d =
    "[scene]\nname=gl fused 3d\ndimension=3\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.2 -0.2 -0.2\nmax=0.2 0.2 0.2\nwall_damping=0.3\n"
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\ngravity=0 -9.81 0\n"
    "[kernels]\nh=0.05\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.2 -0.2 -0.2\nmax=0.0 0.0 0.0\nspacing=0.025\nvelocity=0 0 0.3\n";

static sph_sim *make(const char *ini, const char *const *sets, int n_sets, bool gl, bool fused)
{
    sph_scene_def def = test_scene(ini);
    sph_error err;
    for (int i = 0; i < n_sets; i++)
        cr_assert_eq(sph_scene_set(&def, sets[i], &err), SPH_ERR_OK, "--set %s: %s", sets[i], err.msg);
    def.backend = gl ? SPH_BACKEND_GL : SPH_BACKEND_CPU;
    def.fuse_forces = fused ? SPH_ON : SPH_OFF;
    sph_sim *sim;
    cr_assert_eq(sph_sim_create(&def, 2, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert(!gl || sim->backend, "the GL simulation has no backend");
    return sim;
}

/* g takes c's particles (every field), time step and CFL maxima; acc_v
 * poisoned with NaN if asked. */
static void copy_state(sph_sim *g, const sph_sim *c, bool poison)
{
    test_gl_copy_state(g, c);
    if (!poison) return;
    for (int d = 0; d < g->dim; d++)
        for (uint32_t i = 0; i < c->n; i++) g->P.acc_v[d][i] = NAN;
    sph_sim_upload(g);
}


static void expect_close(const sph_sim *a, const sph_sim *b, sph_field_id f, double tol, const char *what)
{
    double scale, err = test_gl_field_error(a, b, f, &scale);
    cr_expect(scale > 0, "%s: field %s is zero everywhere", what, sph_field_infos[f].name);
    cr_expect(err <= tol * scale, "%s: %s differs by %.3g, above %.1g of its scale %.4g", what,
              sph_field_infos[f].name, err, tol, scale);
    if (getenv("SPH_TEST_VERBOSE"))
        fprintf(stderr, "%-34s %-6s error %.3g of scale %.4g: %.2g\n", what, sph_field_infos[f].name, err, scale,
                scale > 0 ? err / scale : 0.0);
}

/* acc_v of g on the host: every component finite (true) or every one NaN (false). */
static bool acc_v_written(const sph_sim *g, bool *uniform)
{
    sph_sim_sync(g, SPH_SYNC_FIELD(SPH_FIELD_ACC_V));
    uint32_t finite = 0, total = 0;
    for (int d = 0; d < g->dim; d++)
        for (uint32_t i = 0; i < g->n; i++, total++) finite += isfinite(g->P.acc_v[d][i]) != 0;
    *uniform = finite == 0 || finite == total;
    return finite == total;
}

static void fused_step(sph_sim *c, sph_sim *u, sph_sim *f, const char *what)
{
    bool seen = false;
    do {
        const int next = c->next_pass;
        if (next != SPH_PASS_VISCOSITY) { /* the fused walk's acc_v must reach the viscosity pass */
            copy_state(u, c, next == SPH_PASS_PRESSURE_FORCE);
            copy_state(f, c, next == SPH_PASS_PRESSURE_FORCE);
        }
        sph_pass_id pc = sph_sim_step_pass(c), pu = sph_sim_step_pass(u), pf = sph_sim_step_pass(f);
        cr_assert(pc == pu && pc == pf, "the simulations ran different passes");
        bool uniform;
        if (pc == SPH_PASS_PRESSURE_FORCE) {
            cr_expect(acc_v_written(f, &uniform), "%s: the fused pressure_force pass did not write acc_v", what);
            cr_expect(!acc_v_written(u, &uniform) && uniform, "%s: pressure_force apart wrote acc_v", what);
        }
        if (pc != SPH_PASS_VISCOSITY) continue;
        seen = true;
        expect_close(u, c, SPH_FIELD_ACC_P, TOL_FORCE, what);
        expect_close(u, c, SPH_FIELD_ACC_V, TOL_FORCE, what);
        expect_close(f, c, SPH_FIELD_ACC_P, TOL_FORCE, what);
        expect_close(f, c, SPH_FIELD_ACC_V, TOL_FORCE, what);
        expect_close(f, u, SPH_FIELD_ACC_P, TOL_FUSED_GL, what);
        expect_close(f, u, SPH_FIELD_ACC_V, TOL_FUSED_GL, what);
    } while (c->next_pass != 0);
    cr_expect(seen, "%s: no viscosity pass ran", what);
}

static void check(const char *ini, const char *const *sets, int n_sets, int steps, const char *what)
{
    need_gl();
    sph_sim *c = make(ini, sets, n_sets, false, true), *u = make(ini, sets, n_sets, true, false),
            *f = make(ini, sets, n_sets, true, true);
    for (int s = 0; s < 3; s++) sph_sim_step(c); /* the fluid moves before the checked steps */
    for (int s = 0; s < steps; s++) fused_step(c, u, f, what);
    sph_sim_destroy(f);
    sph_sim_destroy(u);
    sph_sim_destroy(c);
}

Test(gl_fused, laplacian_symmetric_2d_3d_grid_rows)
{
    check(scene_2d, NULL, 0, 2, "2d hash");
    const char *grid[] = {"search.method=grid"};
    check(scene_3d, grid, 1, 2, "3d grid rows");
}

Test(gl_fused, shared_smoothing_cubic)
{
    const char *sets[] = {"physics.pressure_form=shared", "physics.viscosity_form=smoothing",
                          "kernels.pressure=cubic", "kernels.viscosity=cubic", "search.method=grid"};
    check(scene_2d, sets, 5, 2, "shared, smoothing");
}

Test(gl_fused, morris_periodic)
{
    const char *sets[] = {"search.method=grid", "domain.periodic=y", "physics.viscosity_form=morris",
                          "kernels.viscosity=cubic"};
    check(scene_2d, sets, 4, 2, "morris, periodic y");
}

Test(gl_fused, artificial_volume_walls)
{
    const char *sets[] = {"physics.viscosity_form=artificial", "physics.alpha=0.5", "domain.wall_model=volume"};
    check(scene_2d, sets, 3, 2, "artificial, volume walls 2d");
    check(scene_3d, sets, 3, 1, "artificial, volume walls 3d");
}

/* wall particles: their accelerations zero, the neighbours' vel_visc */
Test(gl_fused, wall_particles)
{
    const char *sets[] = {"domain.wall_model=particles", "domain.wall_slip_ymin=free", "physics.eos=tait"};
    check(scene_2d, sets, 3, 2, "wall particles 2d");
    check(scene_3d, sets, 2, 1, "wall particles 3d");
}

/* Monaghan's term with wall particles: the fused walk sees a wall at v_w + g dt (sph_wall_kick), as the
 * viscosity pass does */
Test(gl_fused, artificial_wall_particles)
{
    const char *sets[] = {"physics.viscosity_form=morris-artificial", "physics.alpha=0.5",
                          "domain.wall_model=particles", "kernels.viscosity=cubic"};
    check(scene_2d, sets, 4, 2, "morris-artificial, wall particles 2d");
}

/* With the viscosity pass switched off (the window's pass toggles) the
 * pressure force runs alone: acc_v keeps what it had. */
Test(gl_fused, viscosity_off_runs_the_pressure_force_alone)
{
    need_gl();
    sph_sim *f = make(scene_2d, NULL, 0, true, true);
    sph_sim_step(f);
    f->enabled[SPH_PASS_VISCOSITY] = false;
    sph_sim_sync(f, SPH_SYNC_ALL);
    for (int d = 0; d < f->dim; d++)
        for (uint32_t i = 0; i < f->n; i++) f->P.acc_v[d][i] = NAN;
    sph_sim_upload(f);
    sph_sim_step(f);
    bool uniform;
    cr_expect(!acc_v_written(f, &uniform) && uniform, "acc_v was written with the viscosity pass off");
    sph_sim_destroy(f);
}
