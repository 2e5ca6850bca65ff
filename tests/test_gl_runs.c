/* The GL compute backend as a whole, on Mesa's llvmpipe through EGL
 * surfaceless (no GPU, no display): whole runs against the CPU's (with
 * obstacles, after a switch of variant, a slow drift), the hash at negative
 * coordinates, stepping pass by pass, uploads after a change on the host,
 * the device's name and the refusals. The passes one by one against the
 * CPU's: test_gl_backend.c. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "sph_obstacles.h"
#include "sph_search.h"
#include "test_gl_util.h"
#include "test_util.h"

static const char *scene_2d = TEST_GL_SCENE_2D;
static const char *scene_3d = TEST_GL_SCENE_3D;

/* Obstacles (wall particles of their own, one free-slip) in separate runs:
 * positions, and the fluid's force on each obstacle (the --stats columns,
 * computed on the host from the synchronised state). */
Test(gl_backend, obstacles_match_cpu)
{
    need_gl();
    const char *ini =
        "[scene]\nname=gl obstacles\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
        "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_model=particles\n"
        "[physics]\nnegative_pressure=clamp\nviscosity=0.005\n"
        "[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n"
        "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n"
        "[obstacle b]\nmin=-0.1 -0.2\nmax=0.0 -0.1\nslip=free\n"
        "[obstacle c]\nshape=circle\ncentre=-0.2 0.0\nradius=0.05\n";
    const char *sets[] = {"physics.density_method=continuity", "physics.delta_form=antuono", "physics.shifting=lind"};
    sph_sim *c = test_gl_make(ini, sets, 3, false), *g = test_gl_make(ini, sets, 3, true);
    cr_assert_eq(c->def.n_obstacles, 2);
    for (int s = 0; s < 40; s++) {
        sph_sim_step(c);
        sph_sim_step(g);
    }
    cr_assert(!g->alarm.raised && !c->alarm.raised, "the watchdog stopped a run");
    sph_sim_sync(g, SPH_SYNC_ALL);
    double err = test_gl_position_gap(c, g);
    double fc[2][3], fg[2][3], ferr = 0, fbig = 0;
    cr_assert_eq(sph_obstacle_forces(c, fc), 2);
    cr_assert_eq(sph_obstacle_forces(g, fg), 2);
    for (int k = 0; k < 2; k++)
        for (int d = 0; d < 2; d++) {
            ferr = fmax(ferr, fabs(fg[k][d] - fc[k][d]));
            fbig = fmax(fbig, fabs(fc[k][d]));
        }
    if (getenv("SPH_TEST_VERBOSE"))
        fprintf(stderr, "obstacles, 40 steps: positions differ by %.3g m, forces by %.3g of %.4g N/m\n", err, ferr,
                fbig);
    cr_expect(err <= TEST_GL_TOL_POS_RUN, "positions after 40 steps differ by %.3g m (tolerance %g m)", err,
              TEST_GL_TOL_POS_RUN);
    cr_expect(fbig > 0 && ferr <= 1e-3 * fbig, "obstacle forces differ by %.3g N/m of %.4g", ferr, fbig);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

static void whole_run(const char *ini)
{
    test_gl_whole_run(ini, NULL, 0);
}

Test(gl_backend, whole_run_2d)
{
    whole_run(scene_2d);
}

Test(gl_backend, whole_run_3d)
{
    whole_run(scene_3d);
}

/* A particle just below zero is in cell -1 (floor), not 0 (truncation), and
 * its hash wraps in unsigned arithmetic as the CPU's does. */
Test(gl_backend, hash_negative_coordinates)
{
    need_gl();
    const char *ini = "[scene]\neffects=density\n[domain]\nmin=-1 -1\nmax=1 1\n[kernels]\nh=0.1\n"
                      "[fluid a]\nmin=-0.3 -0.3\nmax=0.3 0.3\nspacing=0.1\n";
    sph_sim *g = test_gl_make(ini, NULL, 0, true);
    sph_sim_step_pass(g); /* external: pred = pos */
    sph_sim_step_pass(g); /* hash */
    sph_sim_sync(g, SPH_SYNC_INDEX | SPH_SYNC_FIELD(SPH_FIELD_PRED));
    int checked = 0;
    for (uint32_t i = 0; i < g->n; i++) {
        float x = g->P.pred[0][i], y = g->P.pred[1][i];
        if (!(x < 0 && x > -g->S.cells.size[0] && y < 0 && y > -g->S.cells.size[1])) continue;
        uint32_t want = sph_hash_cell(2, -1, -1, 0);
        cr_expect_eq(g->S.entries[i].hash, want, "particle at (%g, %g): hash %u, cell (-1, -1) has %u", x, y,
                     g->S.entries[i].hash, want);
        cr_expect_eq(g->S.entries[i].key, want % g->S.table_size);
        checked++;
    }
    cr_assert_eq(checked, 1, "expected one particle in cell (-1, -1), found %d", checked);
    sph_sim_destroy(g);
}

/* A step taken pass by pass gives what a whole step gives (the GL backend is
 * deterministic: the counting sort ranks each run, no float atomics). */
Test(gl_backend, stepping_pass_by_pass)
{
    need_gl();
    sph_sim *a = test_gl_make(scene_2d, NULL, 0, true), *b = test_gl_make(scene_2d, NULL, 0, true);
    for (int s = 0; s < 3; s++) {
        int passes = 0;
        do {
            sph_sim_step_pass(a);
            passes++;
            /* the host copy follows every pass */
            sph_field pos;
            cr_assert(sph_sim_field(a, SPH_FIELD_POS, &pos));
        } while (a->next_pass != 0);
        cr_expect_eq(passes, 12, "a step of this scene has 12 passes, stepped %d", passes);
        sph_sim_step(b);
    }
    cr_assert_eq(a->step, b->step);
    sph_sim_sync(a, SPH_SYNC_ALL);
    sph_sim_sync(b, SPH_SYNC_ALL);
    for (int d = 0; d < 2; d++)
        cr_expect(memcmp(a->P.pos[d], b->P.pos[d], a->n * sizeof(float)) == 0, "positions differ on axis %d", d);
    cr_expect(memcmp(a->P.rho, b->P.rho, a->n * sizeof(float)) == 0, "densities differ");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* The CPU changes particles, uploads, and the device continues from there. */
Test(gl_backend, upload_after_cpu_change)
{
    need_gl();
    sph_sim *g = test_gl_make(scene_2d, NULL, 0, true);
    sph_sim_step(g);
    sph_sim_sync(g, SPH_SYNC_ALL);
    for (uint32_t i = 0; i < g->n; i++) g->P.vel[0][i] = 2.0f;
    sph_sim_upload(g);
    sph_sim_step_pass(g); /* external: pred = x + v dt with the new v */
    sph_sim_sync(g, SPH_SYNC_ALL);
    for (uint32_t i = 0; i < g->n; i++)
        cr_assert_float_eq(g->P.pred[0][i], g->P.pos[0][i] + 2.0f * g->dt, 1e-6f, "particle %u", i);
    sph_sim_destroy(g);
}

Test(gl_backend, refuses_what_it_does_not_implement)
{
    need_gl();
    const char *cases[][2] = {{"search.sort=qsort", "[search] sort = qsort"},
                              {"search.sort=none", "[search] sort = none"},
                              {"physics.accumulate=double", "[physics] accumulate = double"},
                              {"compute.packed_records=on", "[compute] packed_records = on"},
                              {"compute.uniform_mass=on", "[compute] uniform_mass = on"},
                              {"search.cell_batch=on", "[search] cell_batch = on"},
                              {"compute.wide_density=on", "[compute] wide_density = on"},
                              {"search.wide_batch=on", "[search] wide_batch = on"},
                              {"search.lists_resident=on", "[search] lists_resident = on"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        sph_scene_def def = test_scene(scene_2d);
        sph_error err;
        cr_assert_eq(sph_scene_set(&def, cases[k][0], &err), SPH_ERR_OK);
        def.backend = SPH_BACKEND_GL;
        sph_sim *sim = NULL;
        cr_expect_neq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK, "%s accepted", cases[k][0]);
        cr_expect_null(sim);
        cr_expect(strstr(err.msg, cases[k][1]), "message does not name '%s': %s", cases[k][1], err.msg);
        sph_sim_destroy(sim);
    }
}

/* The device is named, for tables and the bench. */
Test(gl_backend, names_its_device)
{
    need_gl();
    sph_sim *g = test_gl_make(scene_2d, NULL, 0, true);
    cr_expect(strstr(g->backend->device, "OpenGL"), "device '%s'", g->backend->device);
    sph_sim_destroy(g);
}

/* A variant switched at run time (the window's toggles): the particles move
 * from the old device buffers to the new ones and the run goes on as the CPU's. */
Test(gl_backend, reconfigure_keeps_particles)
{
    need_gl();
    sph_sim *c = test_gl_make(scene_2d, NULL, 0, false), *g = test_gl_make(scene_2d, NULL, 0, true);
    for (int s = 0; s < 5; s++) {
        sph_sim_step(c);
        sph_sim_step(g);
    }
    sph_error err;
    sph_scene_def next = c->def;
    next.sort = SPH_SORT_BITONIC;
    cr_assert_eq(sph_sim_reconfigure(c, &next, &err), SPH_ERR_OK, "%s", err.msg);
    next.backend = SPH_BACKEND_GL;
    cr_assert_eq(sph_sim_reconfigure(g, &next, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert(g->backend, "the reconfigured simulation lost its backend");
    for (int s = 0; s < 5; s++) {
        sph_sim_step(c);
        sph_sim_step(g);
    }
    sph_sim_sync(g, SPH_SYNC_ALL);
    double err_pos = 0;
    for (uint32_t i = 0; i < c->n; i++)
        for (int d = 0; d < 2; d++) {
            cr_assert_eq(g->P.id[i], c->P.id[i], "particle %u: id %u on GL, %u on the CPU", i, g->P.id[i], c->P.id[i]);
            err_pos = fmax(err_pos, fabs((double)g->P.pos[d][i] - c->P.pos[d][i]));
        }
    cr_expect(err_pos <= TEST_GL_TOL_POS_RUN, "positions differ by %.3g m after the switch", err_pos);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

/* A block drifting 1e-9 m a step near x = 0.15 m, under half a float spacing (1.49e-8 m / 2): on GL too float
 * positions never move and compensated ones move the 2e-6 m to within a float spacing (the CPU's test:
 * hydro_accuracy/slow_drift_needs_compensated_positions). */
Test(gl_backend, slow_drift_compensated_positions)
{
    need_gl();
    const char *ini = "[scene]\ndimension=2\neffects=viscosity\n[domain]\nmin=0 0\nmax=0.3 0.3\n"
                      "[fluid a]\nmin=0.14 0.1\nmax=0.16 0.12\nspacing=0.005\nvelocity=1e-5 0\n"
                      "[physics]\nviscosity=0.001\n[time]\ncfl=0\ndt=1e-4\n";
    const char *float_sum[] = {"time.position_sum=float"}, *comp_sum[] = {"time.position_sum=compensated"};
    for (int k = 0; k < 2; k++) {
        sph_sim *g = test_gl_make(ini, k ? comp_sum : float_sum, 1, true);
        double x0[64];
        cr_assert_leq(g->n, 64u);
        sph_sim_sync(g, SPH_SYNC_ALL);
        for (uint32_t i = 0; i < g->n; i++) x0[g->P.id[i]] = g->P.pos[0][i];
        for (int s = 0; s < 2000; s++) sph_sim_step(g);
        sph_sim_sync(g, SPH_SYNC_ALL);
        double worst = 0, moved = 0;
        for (uint32_t i = 0; i < g->n; i++) {
            double dx = (double)g->P.pos[0][i] - x0[g->P.id[i]];
            worst = fmax(worst, fabs(dx - 2000 * 1e-4 * 1e-5));
            moved = fmax(moved, fabs(dx));
        }
        if (k == 0) cr_expect_eq(moved, 0.0, "GL float positions moved %g m", moved);
        if (k == 1) cr_expect_lt(worst, 1.49e-8, "GL compensated displacement off by %g m of 2e-6 m", worst);
        sph_sim_destroy(g);
    }
}

/* A run the watchdog stops on the GL backend: it looks once a step, after integrate (sph_sim.c), so the report
 * names that pass; it named the step's first pass to write the field ('external' on an H200, for a particle that
 * integrate had sent out of the box). The CPU names the pass that wrote the value. A DFSPH dam break held to
 * 2 iterations a 10 ms step runs away within a few steps. */
Test(gl_backend, watchdog_names_where_it_looked)
{
    need_gl();
    const char *ini = "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=3 1.5\n"
                      "[fluid column]\nmin=0 0\nmax=1 1\nspacing=0.02\n[kernels]\nh=0.04\n"
                      "[physics]\npressure_solver=dfsph\nsolver_max_iterations=2\nviscosity=0.002\n"
                      "[time]\ndt=0.01\ncfl=1\n";
    for (int gl = 0; gl < 2; gl++) {
        sph_sim *sim = test_gl_make(ini, NULL, 0, gl);
        for (int k = 0; k < 200 && !sim->alarm.raised; k++) sph_sim_step(sim);
        cr_assert(sim->alarm.raised, "%s: 2 iterations a 10 ms step ran %g s", gl ? "gl" : "cpu", sim->t);
        char buf[8192];
        sph_sim_alarm_report(sim, buf, sizeof buf);
        if (gl)
            cr_expect(strstr(buf, "found after pass 'integrate' (the gl backend is checked once a step"),
                      "gl: the report does not name integrate: %.300s", buf);
        else
            cr_expect(strstr(buf, "), after pass '") && !strstr(buf, "found after"),
                      "cpu: the report does not name the pass that wrote the value: %.300s", buf);
        sph_sim_destroy(sim);
    }
}
