/* The GL compute backend against the CPU passes, on Mesa's llvmpipe through
 * EGL surfaceless (no GPU, no display). Pass by pass: before each pass the
 * GL simulation gets the CPU's state, both run the pass, and what the pass
 * wrote must agree: the index exactly (hash, both sorts, reorder, offsets),
 * the particle fields within the tolerances below; each form also over whole
 * runs (test_gl_whole_run), and every value of every choice runs or is
 * refused. Whole runs of the plain scenes, the hash at negative coordinates,
 * stepping pass by pass and the refusals: test_gl_runs.c. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "sph_obstacles.h"
#include "sph_search.h"
#include "test_gl_util.h"
#include "test_util.h"

/* Tolerances, as a fraction of the largest magnitude of the field in the
 * CPU's result. The density and pressure sums run in another order (cells
 * walked on the GPU, lists on the CPU): a few float roundings of the sum.
 * Force sums cancel (a fluid at rest sums to ~0 from terms of ~g), so their
 * error is measured against the largest force, not each particle's own. */
#define TOL_EXACT_KINEMATICS 1e-6 /* external, integrate, walls: the same operations in the same order */
#define TOL_DENSITY 1e-5          /* rho, vol */
#define TOL_PRESSURE 1e-5         /* p, p / rho^2 (from identical densities) */
#define TOL_FORCE 1e-5            /* the accelerations (acc_p, acc_v, acc_c, ...) */
/* The pressure solvers' fields (pcisph, dfsph). Each correction is
 * proportional to rho* - rho_r, the difference of two floats near rho_r, of
 * about solver_tolerance rho_r (1e-3 here, the default): its relative error
 * is a few roundings of rho* (the sum's order and kernels differ, as in
 * TOL_DENSITY) divided by 1e-3, and the accelerations, differences of
 * pressures, carry it on. 16 roundings: 1.9e-3. Largest measured in the
 * solver tests below: p_pci 1.7e-4, acc_pci 5.7e-4, kappa 2e-5, acc_df
 * 4.6e-5; the fields before a correction as the density's: rho_pci 2.4e-7,
 * x_pci 1e-7, alpha 1.8e-7. */
#define TOL_SOLVER (16 * FLT_EPSILON / 1e-3)

/* The 2D and 3D scenes of the backend's tests (test_gl_util.h). */
static const char *scene_2d = TEST_GL_SCENE_2D;
static const char *scene_3d = TEST_GL_SCENE_3D;

/* Largest |gl - cpu| of a field over particles and components, and the
 * largest |cpu| (the scale the tolerances are fractions of). */
static double field_error(const sph_sim *c, const sph_sim *g, sph_field_id f, double *scale, const char **name)
{
    sph_field fc;
    cr_assert(sph_sim_field(c, f, &fc), "field %d missing", (int)f);
    *name = fc.name;
    return test_gl_field_error(c, g, f, scale);
}

static void expect_field(const sph_sim *c, const sph_sim *g, sph_field_id f, double tol, const char *what)
{
    const char *name;
    double scale, err = field_error(c, g, f, &scale, &name);
    cr_expect(err <= tol * scale + 1e-30, "%s: field %s differs by %.3g, above %.1g of its scale %.4g", what, name,
              err, tol, scale);
    if (getenv("SPH_TEST_VERBOSE")) fprintf(stderr, "%-15s %-7s error %.3g of scale %.4g: %.2g\n", what, name, err,
                                            scale, scale > 0 ? err / scale : 0.0);
}

static void expect_index(const sph_sim *c, const sph_sim *g, const char *what)
{
    sph_sim_sync(g, SPH_SYNC_INDEX);
    for (uint32_t i = 0; i < c->n; i++) {
        const sph_entry *a = &c->S.entries[i], *b = &g->S.entries[i];
        cr_assert(a->key == b->key && a->hash == b->hash && a->index == b->index,
                  "%s: entry %u is (%u, %u, %u) on the GPU, (%u, %u, %u) on the CPU", what, i, b->key, b->hash,
                  b->index, a->key, a->hash, a->index);
    }
}

/* One step in lockstep, each pass checked against the CPU's. */
static void lockstep(sph_sim *c, sph_sim *g)
{
    do {
        test_gl_copy_state(g, c);
        sph_pass_id pc = sph_sim_step_pass(c), pg = sph_sim_step_pass(g);
        cr_assert_eq(pc, pg,
                     "the backends ran different passes: %s on the CPU, %s on GL (alarms %d, %d; "
                     "solver iteration %d, %d)",
                     pc < SPH_PASS_COUNT ? sph_passes[pc]->name : "none",
                     pg < SPH_PASS_COUNT ? sph_passes[pg]->name : "none",
                     c->alarm.raised, g->alarm.raised, c->solver.iteration, g->solver.iteration);
        const char *name = sph_passes[pc]->name;
        switch (pc) {
        case SPH_PASS_EXTERNAL:
        case SPH_PASS_INTEGRATE:
        case SPH_PASS_WALLS:
            expect_field(c, g, SPH_FIELD_VEL, TOL_EXACT_KINEMATICS, name);
            expect_field(c, g, pc == SPH_PASS_EXTERNAL ? SPH_FIELD_PRED : SPH_FIELD_POS, TOL_EXACT_KINEMATICS, name);
            if (pc == SPH_PASS_INTEGRATE) {
                cr_expect(fabsf(g->max_speed - c->max_speed) <= 1e-6f * c->max_speed, "max speed %g, CPU %g",
                          g->max_speed, c->max_speed);
                cr_expect(fabsf(g->max_acc - c->max_acc) <= 1e-5f * c->max_acc, "max acc %g, CPU %g", g->max_acc,
                          c->max_acc);
            }
            break;
        case SPH_PASS_HASH:
        case SPH_PASS_SORT: expect_index(c, g, name); break;
        case SPH_PASS_REORDER:
            expect_index(c, g, name);
            sph_sim_sync(g, SPH_SYNC_ID);
            cr_expect(memcmp(c->P.id, g->P.id, c->n * sizeof *c->P.id) == 0, "reorder: ids differ");
            expect_field(c, g, SPH_FIELD_POS, 0, name);
            break;
        case SPH_PASS_OFFSETS:
            sph_sim_sync(g, SPH_SYNC_INDEX);
            cr_expect(memcmp(c->S.start, g->S.start, c->S.table_size * sizeof *c->S.start) == 0,
                      "offsets: start tables differ");
            break;
        case SPH_PASS_NEIGHBOURS: {
            /* on GL the lists exist only on the host, built on demand from the device's index */
            sph_sim_sync(g, SPH_SYNC_LISTS);
            cr_expect(memcmp(c->S.nbr_start, g->S.nbr_start, (c->n + 1) * sizeof *c->S.nbr_start) == 0,
                      "neighbour counts differ");
            break;
        }
        case SPH_PASS_DENSITY:
            expect_field(c, g, SPH_FIELD_RHO, TOL_DENSITY, name);
            expect_field(c, g, SPH_FIELD_VOL, TOL_DENSITY, name);
            if (c->P.rho_c) expect_field(c, g, SPH_FIELD_RHO_C, TOL_DENSITY, name);
            break;
        case SPH_PASS_PRESSURE:
            expect_field(c, g, SPH_FIELD_P, TOL_PRESSURE, name);
            expect_field(c, g, SPH_FIELD_PRHO2, TOL_PRESSURE, name);
            break;
        case SPH_PASS_PCISPH:
        case SPH_PASS_DFSPH: /* one iteration, from the same state: every field it writes */
            for (int f = 0; f < SPH_FIELD_COUNT; f++)
                if (sph_passes[pc]->writes & SPH_FIELD_BIT(f)) expect_field(c, g, (sph_field_id)f, TOL_SOLVER, name);
            /* the error measured: (rho* - rho_r) / rho_r, within a few roundings of rho* */
            cr_expect(fabs(g->solver.error - c->solver.error) <= 4 * FLT_EPSILON,
                      "%s: error %g after iteration %d on GL, %g on the CPU", name, g->solver.error,
                      g->solver.iteration, c->solver.error);
            break;
        default: /* a force pass: every field it writes (the registry's masks) */
            for (int f = 0; f < SPH_FIELD_COUNT; f++)
                if (sph_passes[pc]->writes & SPH_FIELD_BIT(f)) expect_field(c, g, (sph_field_id)f, TOL_FORCE, name);
            break;
        }
    } while (c->next_pass != 0);
}

static void lockstep_steps(const char *ini, const char *const *sets, int n_sets, int steps)
{
    need_gl();
    sph_sim *c = test_gl_make(ini, sets, n_sets, false), *g = test_gl_make(ini, sets, n_sets, true);
    for (int k = 0; k < 2; k++) { /* the mouse, for scenes with the interaction effect */
        sph_sim *s = k ? g : c;
        /* the passes' equality is checked here, not the watchdog's: a solver's first step from the jittered
         * lattice puts in energy (144 to 266 J/m in 2D) that the energy check stops. It was kept from looking
         * by the mouse's button, held down in every scene, until only a pass in the pipeline could do work. */
        s->watchdog = false;
        s->interaction_active = true;
        s->interaction_point[0] = -0.15f;
        s->interaction_point[1] = 0.0f;
        s->interaction_sign = -1.0f;
    }
    for (int s = 0; s < 3; s++) sph_sim_step(c); /* the fluid moves before the checked steps */
    for (int s = 0; s < steps; s++) lockstep(c, g);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

Test(gl_backend, passes_match_cpu_2d_counting)
{
    lockstep_steps(scene_2d, NULL, 0, 2);
}

Test(gl_backend, passes_match_cpu_2d_bitonic)
{
    const char *sets[] = {"search.sort=bitonic"};
    lockstep_steps(scene_2d, sets, 1, 2);
}

Test(gl_backend, passes_match_cpu_3d_counting)
{
    lockstep_steps(scene_3d, NULL, 0, 2);
}

Test(gl_backend, passes_match_cpu_3d_bitonic_no_reorder)
{
    const char *sets[] = {"search.sort=bitonic", "search.reorder=off"};
    lockstep_steps(scene_3d, sets, 2, 1);
}

/* Few keys: long runs of mixed cells in each key, the stable rank's hard case. */
Test(gl_backend, passes_match_cpu_few_keys)
{
    const char *sets[] = {"search.table_size=7"};
    lockstep_steps(scene_2d, sets, 1, 1);
}

/* The other forms and kernels: shared pressure, smoothing viscosity, Tait,
 * reflecting walls, the grid search. */
Test(gl_backend, passes_match_cpu_other_forms)
{
    const char *sets[] = {"physics.pressure_form=shared", "physics.viscosity_form=smoothing", "physics.eos=tait",
                          "domain.wall_model=reflect",     "search.method=grid",              "kernels.density=wendland",
                          "kernels.pressure=cubic",        "kernels.viscosity=cubic"};
    lockstep_steps(scene_2d, sets, 8, 1);
}

/* The volume walls with the shared form and other kernels: the block fills a
 * corner (the corner table in 2D, the three walls' vertex in 3D). */
Test(gl_backend, passes_match_cpu_volume_walls_shared)
{
    const char *sets[] = {"physics.pressure_form=shared", "domain.wall_model=volume", "kernels.density=wendland",
                          "kernels.pressure=cubic"};
    lockstep_steps(scene_2d, sets, 4, 1);
    lockstep_steps(scene_3d, sets, 4, 1);
}

/* The volume walls' ghost force (wall_force = ghost): the pressure kernel's
 * tables and the second moments, with the gravity ramp's share; with the
 * continuity equation too (its wall term in the step's frame). */
Test(gl_backend, passes_match_cpu_volume_walls_ghost)
{
    const char *sets[] = {"domain.wall_model=volume", "domain.wall_force=ghost", "physics.gravity_ramp=0.01",
                          "kernels.density=wendland", "kernels.pressure=cubic"};
    lockstep_steps(scene_2d, sets, 5, 1);
    lockstep_steps(scene_3d, sets, 5, 1);
    const char *cont[] = {"domain.wall_model=volume", "domain.wall_force=ghost", "physics.density_method=continuity",
                          "physics.pressure_form=shared"};
    lockstep_steps(scene_2d, cont, 4, 1);
}

/* Every effect at once, so every pass of the pipeline runs: a pass without
 * a row in the GL table is refused and fails here, one whose shader differs
 * from its C fails the lockstep. */
Test(gl_backend, every_effect_matches_cpu)
{
    char effects[512] = "scene.effects=";
    for (int e = 0; e < SPH_EFFECT_COUNT; e++) {
        strcat(effects, sph_effect_names[e]);
        strcat(effects, " ");
    }
    const char *sets[] = {effects};
    lockstep_steps(scene_2d, sets, 1, 2);
    lockstep_steps(scene_3d, sets, 1, 1);
}

Test(gl_backend, passes_match_cpu_interaction)
{
    const char *sets[] = {"scene.effects=gravity pressure viscosity walls interaction"};
    lockstep_steps(scene_2d, sets, 1, 2);
}

/* The dense grid's row runs (gpu_walk.glsl, u_rows) in 3D, and with y and z
 * wrapping (rows still one run each; x does not wrap) */
Test(gl_backend, passes_match_cpu_3d_grid_rows)
{
    const char *sets[] = {"search.method=grid"};
    lockstep_steps(scene_3d, sets, 1, 2);
}

Test(gl_backend, passes_match_cpu_3d_grid_periodic_yz)
{
    const char *sets[] = {"search.method=grid", "domain.periodic=y z"};
    lockstep_steps(scene_3d, sets, 2, 2);
}

Test(gl_backend, passes_match_cpu_2d_grid_periodic_morris)
{
    const char *sets[] = {"search.method=grid", "domain.periodic=y", "physics.viscosity_form=morris",
                          "kernels.viscosity=cubic"};
    lockstep_steps(scene_2d, sets, 4, 2);
}

/* Monaghan's artificial viscosity, and the start-up ramps of gravity and
 * damping part-way through (their factors are uniforms of the external pass) */
Test(gl_backend, passes_match_cpu_artificial_viscosity_ramps)
{
    const char *sets[] = {"physics.viscosity_form=artificial", "physics.alpha=0.5", "physics.gravity_ramp=0.01",
                          "physics.damping_time=0.02"};
    lockstep_steps(scene_2d, sets, 4, 2);
    const char *sets3[] = {"physics.viscosity_form=artificial", "kernels.pressure=wendland"};
    lockstep_steps(scene_3d, sets3, 2, 1);
}

/* Monaghan's term with wall particles sees a wall at v_w + g dt, the frame of the kicked fluid
 * (sph_wall_kick); the fused walk: tests/test_gl_fused.c */
Test(gl_backend, passes_match_cpu_artificial_viscosity_wall_particles)
{
    const char *sets[] = {"physics.viscosity_form=artificial", "physics.alpha=0.5", "domain.wall_model=particles",
                          "compute.fuse_forces=off"};
    lockstep_steps(scene_2d, sets, 4, 2);
    const char *both[] = {"physics.viscosity_form=morris-artificial", "physics.alpha=0.5",
                          "domain.wall_model=particles", "kernels.viscosity=cubic"};
    lockstep_steps(scene_2d, both, 4, 2);
}

Test(gl_backend, passes_match_cpu_periodic_brute)
{
    const char *sets[] = {"domain.periodic=x", "search.method=brute"};
    lockstep_steps(scene_2d, sets, 2, 1);
}

/* Wall particles (Adami et al. 2012): the wall_state pass, the walls' zero
 * accelerations, their place in the external, integrate and walls passes,
 * a free-slip floor among no-slip walls. */
Test(gl_backend, passes_match_cpu_wall_particles)
{
    const char *sets[] = {"domain.wall_model=particles", "domain.wall_slip_ymin=free", "physics.eos=tait"};
    lockstep_steps(scene_2d, sets, 3, 2);
    lockstep_steps(scene_3d, sets, 2, 1);
}

/* The no-slip mirror's curvature term (wall_state.c), nu high enough for a cell Reynolds number below 1.
 * (A wall particle with one fluid neighbour once had it on GL and not on the CPU: its spread along the
 * wall, zero, read as float rounding.) */
Test(gl_backend, passes_match_cpu_wall_particles_mirror_curvature)
{
    const char *curv[] = {"domain.wall_model=particles", "physics.viscosity=0.05", "physics.viscosity_form=morris",
                          "kernels.viscosity=cubic"};
    lockstep_steps(scene_2d, curv, 4, 2);
    lockstep_steps(scene_3d, curv, 4, 1);
}

/* density_method = continuity with Molteni's diffusion, with Antuono's and
 * wall particles (the density_gradient pass, a wall's density from
 * wall_state), and with volume walls (the hidden share's rate). */
Test(gl_backend, passes_match_cpu_continuity)
{
    const char *molteni[] = {"physics.density_method=continuity", "physics.delta=0.1"};
    lockstep_steps(scene_2d, molteni, 2, 2);
    const char *antuono[] = {"physics.density_method=continuity", "physics.delta_form=antuono",
                             "domain.wall_model=particles"};
    lockstep_steps(scene_2d, antuono, 3, 2);
    lockstep_steps(scene_3d, antuono, 3, 1);
    const char *volume[] = {"physics.density_method=continuity", "domain.wall_model=volume", "domain.periodic=x"};
    lockstep_steps(scene_2d, volume, 3, 1);
}

/* shifting = lind: the surface marks exactly, the shift within TOL_FORCE. */
Test(gl_backend, passes_match_cpu_shifting)
{
    const char *sets[] = {"physics.shifting=lind", "domain.wall_model=particles"};
    lockstep_steps(scene_2d, sets, 2, 2);
    lockstep_steps(scene_3d, sets, 1, 1);
}

/* The incompressible pressure solvers: every iteration is a call of the
 * pass, checked against the CPU's from the same state (its pressure, kappa,
 * predicted positions and densities); the same number of calls, or the
 * lockstep stops at the first call where one backend moves on. Volume and
 * reflecting walls (the solvers refuse wall particles and periodic axes). */
Test(gl_backend, passes_match_cpu_solvers, .timeout = 600)
{
    const char *pci[] = {"physics.pressure_solver=pcisph"}, *df[] = {"physics.pressure_solver=dfsph"};
    const char *pci_r[] = {"physics.pressure_solver=pcisph", "domain.wall_model=reflect"};
    const char *df_r[] = {"physics.pressure_solver=dfsph", "domain.wall_model=reflect", "kernels.pressure=wendland"};
    lockstep_steps(scene_2d, pci, 1, 3);
    lockstep_steps(scene_2d, df, 1, 3);
    lockstep_steps(scene_2d, pci_r, 2, 1);
    lockstep_steps(scene_2d, df_r, 3, 1);
    lockstep_steps(scene_3d, pci, 1, 1);
    lockstep_steps(scene_3d, df, 1, 1);
}

/* A 2D dam break where the water meets the far wall (steps 20 to 34 at
 * 0.5 ms), with both solvers: their iterations pass by pass. */
Test(gl_backend, passes_match_cpu_solvers_dam, .timeout = 300)
{
    const char *ini = "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n"
                      "[domain]\nmin=0 0\nmax=0.8 0.5\nwall_damping=0.3\n"
                      "[fluid column]\nmin=0 0\nmax=0.3 0.3\nspacing=0.02\n"
                      "[physics]\nstiffness=1000\nviscosity=0.002\n[kernels]\nh=0.04\n[time]\ndt=0.0005\ncfl=0\n";
    const char *solvers[][1] = {{"physics.pressure_solver=pcisph"}, {"physics.pressure_solver=dfsph"}};
    need_gl();
    for (int k = 0; k < 2; k++) {
        sph_sim *c = test_gl_make(ini, solvers[k], 1, false), *g = test_gl_make(ini, solvers[k], 1, true);
        for (int s = 0; s < 20; s++) sph_sim_step(c);
        for (int s = 0; s < 15; s++) lockstep(c, g);
        sph_sim_destroy(g);
        sph_sim_destroy(c);
    }
}

/* Every value of every choice and kernel key either runs on GL and matches
 * the CPU pass by pass, or is refused when the simulation is made, by key and
 * value. Nothing in between: a form added on the CPU and unknown to the
 * shaders must not run as some other form. Values the CPU itself refuses for
 * this scene are left out, after trying the companion key they need. */
static bool try_make(const char *ini, const char *const *sets, int n_sets, bool gl, sph_sim **out, sph_error *err)
{
    sph_scene_def def = test_scene(ini);
    for (int i = 0; i < n_sets; i++)
        if (sph_scene_set(&def, sets[i], err) != SPH_ERR_OK) return false;
    def.backend = gl ? SPH_BACKEND_GL : SPH_BACKEND_CPU;
    return sph_sim_create(&def, 2, out, err) == SPH_ERR_OK;
}

Test(gl_backend, every_choice_runs_or_is_refused, .timeout = 900)
{
    need_gl();
    int ran = 0, refused = 0;
    for (int k = 0; k < sph_scene_key_count; k++) {
        const sph_key *key = &sph_scene_keys[k];
        if ((key->type != SPH_KEY_CHOICE && key->type != SPH_KEY_KERNEL) || strcmp(key->section, "compute") == 0)
            continue;
        for (int v = 0; v < key->n_choices; v++) {
            char set[200];
            if (strcmp(key->section, "fluid") == 0)
                snprintf(set, sizeof set, "fluid.a.%s=%s", key->name, key->choices[v]);
            else
                snprintf(set, sizeof set, "%s.%s=%s", key->section, key->name, key->choices[v]);
            const char *sets[2] = {set, "kernels.viscosity=cubic"}; /* morris needs W.(0) = 0 */
            sph_sim *c = NULL, *g = NULL;
            sph_error err;
            int n_sets = 1;
            if (!try_make(scene_2d, sets, 1, false, &c, &err)) {
                n_sets = 2;
                if (!try_make(scene_2d, sets, 2, false, &c, &err)) continue; /* not a valid scene on the CPU either */
            }
            if (!try_make(scene_2d, sets, n_sets, true, &g, &err)) {
                cr_expect(strstr(err.msg, key->name) && strstr(err.msg, key->choices[v]),
                          "%s: refused without naming the key and value: %s", set, err.msg);
                refused++;
                sph_sim_destroy(c);
                continue;
            }
            /* the passes' fields are compared, not the watchdog's verdict: its
             * energy check stops pressure_solver = pcisph at step 1 on this
             * jittered block (the solver undoes the jitter's compression, +122
             * J, which no internal energy accounts for) */
            c->watchdog = g->watchdog = false;
            for (int st = 0; st < 2; st++) sph_sim_step(c);
            if (getenv("SPH_TEST_VERBOSE")) fprintf(stderr, "-- %s\n", set);
            lockstep(c, g);
            ran++;
            sph_sim_destroy(g);
            sph_sim_destroy(c);
        }
    }
    if (getenv("SPH_TEST_VERBOSE")) fprintf(stderr, "%d values ran on GL, %d were refused\n", ran, refused);
    cr_expect(ran >= 20 && refused >= 2, "%d values ran on GL, %d were refused", ran, refused);
}

/* xsph > 0 (Monaghan 1989): the smoothing acceleration pass by pass, with
 * wall particles (which neither get nor give any) and periodic, then whole
 * runs of separate simulations. */
Test(gl_backend, passes_match_cpu_xsph)
{
    const char *sets[] = {"physics.xsph=0.3", "domain.wall_model=particles", "domain.periodic=x"};
    lockstep_steps(scene_2d, sets, 2, 2);
    lockstep_steps(scene_2d, sets, 3, 1);
    lockstep_steps(scene_3d, sets, 1, 1);
    test_gl_whole_run(scene_2d, sets, 1);
    test_gl_whole_run(scene_3d, sets, 2);
}

/* surface_tension = akinci (Akinci et al. 2013): the normals, the curvature
 * term and the cohesion term with the model's gamma, pass by pass and over
 * 40-step runs; with wall particles, which get none. A gamma large enough
 * that the terms are of the order of gravity. */
Test(gl_backend, passes_match_cpu_akinci)
{
    const char *sets[] = {"physics.surface_tension=akinci", "physics.surface_tension_coefficient=2",
                          "domain.wall_model=particles"};
    lockstep_steps(scene_2d, sets, 3, 2);
    lockstep_steps(scene_2d, sets, 2, 1);
    lockstep_steps(scene_3d, sets, 3, 1);
    test_gl_whole_run(scene_2d, sets, 2);
    test_gl_whole_run(scene_3d, sets, 3);
}

/* delta_form = fourtakas (Fourtakas et al. 2019): the hydrostatic density
 * difference in density_rate, with the linear and Tait equations of state,
 * wall particles and a gravity ramp part-way (its factor is a uniform), pass
 * by pass and over 40-step runs. */
Test(gl_backend, passes_match_cpu_fourtakas)
{
    const char *sets[] = {"physics.density_method=continuity", "physics.delta=0.1", "physics.delta_form=fourtakas",
                          "domain.wall_model=particles", "physics.eos=tait", "physics.gravity_ramp=0.01"};
    lockstep_steps(scene_2d, sets, 3, 2);
    lockstep_steps(scene_2d, sets, 6, 2);
    lockstep_steps(scene_3d, sets, 4, 1);
    test_gl_whole_run(scene_2d, sets, 4);
    test_gl_whole_run(scene_3d, sets, 5);
}

/* eos_rest = lattice: the equation of state's reference (EOS_RHO0) in the
 * pressure, the walls' inverse equation of state, Fourtakas's hydrostatic
 * term and the internal energy, linear and Tait, pass by pass and over
 * 40-step runs. */
Test(gl_backend, passes_match_cpu_eos_rest_lattice)
{
    const char *sets[] = {"physics.eos_rest=lattice", "domain.wall_model=particles", "physics.eos=tait",
                          "physics.density_method=continuity", "physics.delta_form=fourtakas"};
    lockstep_steps(scene_2d, sets, 2, 2);
    lockstep_steps(scene_2d, sets, 5, 2);
    lockstep_steps(scene_3d, sets, 3, 1);
    test_gl_whole_run(scene_2d, sets, 3);
    test_gl_whole_run(scene_3d, sets, 5);
    sph_sim *c = test_gl_make(scene_2d, sets, 3, false), *g = test_gl_make(scene_2d, sets, 3, true);
    sph_sim_step(c); /* after a step GL sums the statistics on the device (gpu_stats.comp's eos_energy) */
    sph_sim_step(g);
    sph_stats sc, sg;
    sph_sim_stats(c, &sc);
    sph_sim_stats(g, &sg);
    cr_expect(sc.eint > 0 && fabs(sg.eint - sc.eint) <= 1e-2 * sc.eint, "internal energy %g on GL, %g on the CPU",
              sg.eint, sc.eint);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

/* shifting = tvf (Adami et al. 2013): the background pressure's drift, in
 * jittered boxes the fluid fills (what it is meant for: no free surface),
 * periodic, and closed by wall particles, which count in the sum and never
 * move; pass by pass and over 40-step runs. */
static const char *scene_tvf_2d =
    "[scene]\nname=gl tvf 2d\ndimension=2\neffects=pressure viscosity\njitter=0.2\n"
    "[domain]\nmin=-0.2 -0.2\nmax=0.2 0.2\n"
    "[physics]\nviscosity=0.005\nshifting=tvf\n"
    "[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.2 -0.2\nmax=0.2 0.2\nspacing=0.02\nvelocity=0.5 0.2\n";
static const char *scene_tvf_3d =
    "[scene]\nname=gl tvf 3d\ndimension=3\neffects=pressure viscosity\njitter=0.2\n"
    "[domain]\nmin=-0.1 -0.1 -0.1\nmax=0.1 0.1 0.1\n"
    "[physics]\nviscosity=0.005\nshifting=tvf\n"
    "[kernels]\nh=0.05\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.1 -0.1 -0.1\nmax=0.1 0.1 0.1\nspacing=0.025\nvelocity=0 0.2 0.3\n";

Test(gl_backend, passes_match_cpu_tvf)
{
    const char *periodic[] = {"domain.periodic=x y z", "domain.periodic=x y"};
    const char *walls[] = {"domain.wall_model=particles", "physics.eos=tait"};
    lockstep_steps(scene_tvf_2d, periodic + 1, 1, 2);
    lockstep_steps(scene_tvf_2d, walls, 2, 2);
    lockstep_steps(scene_tvf_3d, periodic, 1, 1);
    lockstep_steps(scene_tvf_3d, walls, 1, 1);
    test_gl_whole_run(scene_tvf_2d, periodic + 1, 1);
    test_gl_whole_run(scene_tvf_2d, walls, 1);
    test_gl_whole_run(scene_tvf_3d, periodic, 1);
}

/* position_sum = compensated (Kahan's sum of x += dt v, integrate.c): pass by pass (the remainder pos_r carried
 * through reorder, added to the predicted positions) and over 40 steps, with wall particles and the carried
 * density as in the hydrostatic validation. */
Test(gl_backend, passes_match_cpu_compensated_positions)
{
    const char *sets[] = {"time.position_sum=compensated", "physics.density_method=continuity",
                          "domain.wall_model=particles"};
    lockstep_steps(scene_2d, sets, 3, 2);
    lockstep_steps(scene_3d, sets, 1, 1);
    test_gl_whole_run(scene_2d, sets, 3);
}
