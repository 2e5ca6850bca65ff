/* Far coordinates: a scene shifted far from 0 runs as at 0 (the simulation
 * works relative to the domain's point nearest 0); a domain too long for float
 * positions at its h, or for int cell counts, is refused with the reason. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_memory.h"
#include "sph_search.h"
#include "test_util.h"

/* A 0.3 x 0.5 m water column in a 1 m box whose lower corner is at (x0, 0). */
static void column_ini(char *buf, size_t n, double x0, const char *extra)
{
    snprintf(buf, n,
             "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = %.17g 0\nmax = %.17g 1\n"
             "[fluid column]\nmin = %.17g 0\nmax = %.17g 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
             "[physics]\nstiffness = 400\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n%s",
             x0, x0 + 1, x0 + 0.5, x0 + 0.8, extra);
}

static sph_error_code load(const char *ini, sph_scene_def *def, sph_error *err)
{
    *def = sph_default_scene_def();
    sph_error_code c = sph_scene_load_string(ini, "far.ini", def, err);
    return c ? c : sph_scene_validate(def, err);
}

/* The same column at x0 = 0, 1e4 and 1e5 m: the same 375 particles and,
 * after 200 steps, the same positions relative to the box (the frames are
 * identical, so the relative positions agree to the last bit; the bound
 * allows a float's rounding there). It made 350 particles at 1e4 m, and at
 * 1e5 m the watchdog stopped it at step 8. */
Test(far, shifted_column_runs_as_at_the_origin, .timeout = 120)
{
    static const double shifts[] = {1e4, 1e5};
    char ini[2048];
    column_ini(ini, sizeof ini, 0, "");
    sph_sim *ref = test_sim(ini, 1);
    cr_assert_eq(ref->n, 375u);
    for (int k = 0; k < 200; k++) sph_sim_step(ref);
    cr_assert(!ref->alarm.raised, "%s", ref->alarm.what);
    for (size_t s = 0; s < sizeof shifts / sizeof shifts[0]; s++) {
        column_ini(ini, sizeof ini, shifts[s], "");
        sph_sim *sim = test_sim(ini, 1);
        cr_expect_eq(sim->n, ref->n, "at x = %g m: %u particles, at 0: %u", shifts[s], sim->n, ref->n);
        cr_expect_eq(sim->origin[0], shifts[s]);
        for (int k = 0; k < 200 && sim->n == ref->n; k++) sph_sim_step(sim);
        cr_expect(!sim->alarm.raised, "at x = %g m: %s", shifts[s], sim->alarm.what);
        double worst = 0;
        for (uint32_t i = 0; i < sim->n && sim->n == ref->n; i++)
            for (int d = 0; d < 2; d++) {
                /* absolute minus the shift against the unshifted run's absolute position */
                double a = sph_sim_abs(sim, d, sim->P.pos[d][i]) - (d == 0 ? shifts[s] : 0.0);
                double b = sph_sim_abs(ref, d, ref->P.pos[d][i]);
                worst = fmax(worst, fabs(a - b));
            }
        cr_expect(worst <= 1.2e-7, "at x = %g m positions differ from the run at 0 by %g m", shifts[s], worst);
        sph_sim_destroy(sim);
    }
    sph_sim_destroy(ref);
}

/* Hash search against brute force on a periodic axis far from 0. */
Test(far, periodic_hash_matches_brute_force_far_from_zero, .timeout = 60)
{
    char ini[2048];
    double rho[2][400];
    const char *methods[] = {"[search]\nmethod = hash\n", "[search]\nmethod = brute\n"};
    uint32_t n = 0;
    for (int m = 0; m < 2; m++) {
        char extra[256];
        snprintf(extra, sizeof extra, "%s", methods[m]);
        column_ini(ini, sizeof ini, 1e4, extra);
        /* periodic along x: the domain's walls go, the column wraps */
        char *p = strstr(ini, "[domain]\n");
        cr_assert(p);
        char with[2300];
        snprintf(with, sizeof with, "%.*s[domain]\nperiodic = x\n%s", (int)(p - ini), ini, p + strlen("[domain]\n"));
        sph_sim *sim = test_sim(with, 1);
        n = sim->n;
        cr_assert(n <= 400);
        for (int k = 0; k < 5; k++) sph_sim_step(sim);
        for (uint32_t i = 0; i < n; i++) rho[m][sim->P.id[i]] = sim->P.rho[i];
        sph_sim_destroy(sim);
    }
    double worst = 0;
    for (uint32_t i = 0; i < n; i++) worst = fmax(worst, fabs(rho[0][i] - rho[1][i]) / rho[1][i]);
    cr_expect(worst < 1e-5, "hash and brute force densities differ by %.3g (relative)", worst);
}

/* The periodic axis of +-1e4 m with h = 0.5 mm: the frame stays at 0
 * (the domain contains it) and a float's step at 1e4 m is 1 mm, twice h.
 * Refused at load, naming the key and why. */
Test(far, periodic_axis_too_long_for_float_positions_is_refused)
{
    const char *ini = "[scene]\neffects = gravity pressure viscosity\n[domain]\nmin = -1e4 0\nmax = 1e4 1\n"
                      "periodic = x\n[fluid a]\nmin = 0 0\nmax = 0.01 0.01\nspacing = 0.00025\n[kernels]\nh = 0.0005\n";
    sph_scene_def def;
    sph_error err;
    cr_assert_eq(load(ini, &def, &err), SPH_ERR_RANGE);
    cr_expect(strstr(err.msg, "far.ini:5: [domain] x from -10000 to 10000 m") && strstr(err.msg, "10000 m from it") &&
                  strstr(err.msg, "float"),
              "%s", err.msg);
}

/* +-1e6 m: the cell count along a periodic axis (4e9 cells of 0.5 mm) used
 * to overflow int in sph_sim_create; now counted in double and refused. With
 * the grid search the same for every axis. No step of it runs, so no
 * undefined behaviour (the suite runs under UBSan in `make test`). */
Test(far, a_million_metres_is_refused_without_overflow)
{
    const char *inis[] = {
        "[scene]\neffects = gravity pressure viscosity\n[domain]\nmin = -1e6 0\nmax = 1e6 1\nperiodic = x\n"
        "[fluid a]\nmin = 0 0\nmax = 0.01 0.01\nspacing = 0.00025\n[kernels]\nh = 0.0005\n",
        "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = -1e6 0\nmax = 1e6 1\n"
        "[fluid a]\nmin = 0 0\nmax = 0.01 0.01\nspacing = 0.00025\n[kernels]\nh = 0.0005\n[search]\nmethod = grid\n",
    };
    for (size_t i = 0; i < sizeof inis / sizeof inis[0]; i++) {
        sph_scene_def def;
        sph_error err;
        cr_expect_eq(load(inis[i], &def, &err), SPH_ERR_RANGE, "case %zu", i);
        cr_expect(strstr(err.msg, "cells") && strstr(err.msg, "far.ini"), "case %zu: %s", i, err.msg);
    }
}

/* The bound itself: a float's step at the domain's length <= h / 2048.
 * With h = 0.04 m that is 1.95e-5 m, kept below 256 m (step 1.5e-5 m) and
 * lost from 256 m (3.1e-5 m). */
Test(far, precision_bound_sits_where_the_float_step_doubles)
{
    char ini[1024];
    const double lens[] = {255.9, 256.1};
    for (int k = 0; k < 2; k++) {
        snprintf(ini, sizeof ini,
                 "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 5000 0\nmax = %.17g 1\n"
                 "[fluid a]\nmin = 5000 0\nmax = 5000.2 0.2\nspacing = 0.02\n[kernels]\nh = 0.04\n",
                 5000 + lens[k]);
        sph_scene_def def;
        sph_error err;
        sph_error_code c = load(ini, &def, &err);
        if (k == 0)
            cr_expect_eq(c, SPH_ERR_OK, "%g m: %s", lens[k], err.msg);
        else
            cr_expect(c == SPH_ERR_RANGE && strstr(err.msg, "at most 256 m"), "%g m: %s", lens[k],
                      c ? err.msg : "accepted");
    }
    sph_scene_def def = sph_default_scene_def();
    def.h = 0.04f;
    cr_expect_float_eq(sph_scene_position_step_bound(&def), 0.04f / 2048.0, 1e-12);
}

/* Output is absolute: the dump's x column is near 1e4 m, not near 0. */
Test(far, dump_gives_absolute_coordinates, .timeout = 60)
{
    char ini[2048], args[600], out[4096];
    column_ini(ini, sizeof ini, 1e4, "");
    const char *scene = test_write_temp(ini, ".ini");
    char dump[300];
    snprintf(dump, sizeof dump, "%s.csv", scene);
    snprintf(args, sizeof args, "run %s --steps 2 --quiet --dump %s", scene, dump);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert_eq(rc, 0, "%s", out);
    FILE *f = fopen(dump, "r");
    cr_assert(f);
    char line[1024];
    cr_assert(fgets(line, sizeof line, f) && fgets(line, sizeof line, f));
    fclose(f);
    unsigned id;
    double x, y;
    cr_assert_eq(sscanf(line, "%u,%lf,%lf", &id, &x, &y), 3, "%s", line);
    cr_expect(x > 10000.5 && x < 10000.8, "first particle at x = %.10g m: %s", x, line);
    /* the first lattice node, 0.01 m in from the block's corner, to the float's precision near 0.5 m */
    cr_expect(fabs(x - 10000.51) < 1e-3, "x = %.10g", x);
    remove(dump);
    remove(scene);
}
