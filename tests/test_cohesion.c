/* The cohesion pass (src/passes/cohesion.c, Akinci et al. 2013): its spline's
 * normalisation in 2D and 3D, momentum conservation, and a square drop in
 * zero gravity pulled round, against the same drop without cohesion. (On GL:
 * gl_backend/every_effect_matches_cpu.) */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>

#include "test_util.h"

/* The pass's spline C(r) (defined in src/passes/cohesion.c, not in a header:
 * the pass is one file). */
float sph_cohesion_c(int dim, float h, float r);

/* int C dV over space (3D) and int C dA over the plane (2D) are both 79/336:
 * the paper's 3D constant and the 2D one chosen to match it. */
Test(cohesion, spline_integral_is_79_over_336_in_2d_and_3d)
{
    const double want = 79.0 / 336.0, pi = 3.141592653589793;
    const float hs[] = {0.02f, 0.5f};
    for (int k = 0; k < 2; k++)
        for (int dim = 2; dim <= 3; dim++) {
            const float h = hs[k];
            const int steps = 20000;
            double sum = 0;
            for (int s = 0; s < steps; s++) {
                double r = (s + 0.5) * h / steps;
                double shell = dim == 3 ? 4 * pi * r * r : 2 * pi * r;
                sum += sph_cohesion_c(dim, h, (float)r) * shell * h / steps;
            }
            cr_assert(fabs(sum - want) < 1e-4 * want, "%dD, h = %g: integral %.7f, want %.7f", dim, h, sum, want);
        }
    /* attracting for h/2 < r < h, repelling near 0, nothing beyond h */
    cr_assert_gt(sph_cohesion_c(2, 1.0f, 0.7f), 0.0f);
    cr_assert_lt(sph_cohesion_c(3, 1.0f, 0.05f), 0.0f);
    cr_assert_eq(sph_cohesion_c(3, 1.0f, 1.0f), 0.0f);
}

static const char *const DROP =
    "[scene]\ndimension=2\neffects=pressure viscosity cohesion\njitter=0.1\n"
    "[domain]\nmin=0 0\nmax=1 1\n[fluid square]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.01\n"
    "[physics]\nstiffness=100\nviscosity=0.001\nnegative_pressure=clamp\ncohesion=%g\n"
    "[kernels]\nh=0.03\n[time]\ncfl=0.4\ndt=0.001\n";

/* Equal and opposite pair terms: the cohesion accelerations carry no net momentum. */
Test(cohesion, conserves_momentum)
{
    char ini[1024];
    snprintf(ini, sizeof ini, DROP, 1.0);
    sph_sim *sim = test_sim(ini, 2);
    sph_sim_step(sim);
    const sph_particles *P = &sim->P;
    for (int d = 0; d < 2; d++) {
        double net = 0, scale = 0;
        for (uint32_t i = 0; i < sim->n; i++) {
            net += P->mass[i] * P->acc_c[d][i];
            scale += P->mass[i] * fabs(P->acc_c[d][i]);
        }
        cr_assert_gt(scale, 0.0, "no cohesion at all");
        cr_assert(fabs(net) < 1e-5 * scale, "axis %d: net %g of %g", d, net, scale);
    }
    sph_sim_destroy(sim);
}

/* Largest over root-mean-square distance from the centroid: sqrt(3) = 1.73
 * for a square, sqrt(2) = 1.41 for a disc; and the RMS distance itself. */
static void shape(const sph_sim *sim, double *ratio, double *rms)
{
    const sph_particles *P = &sim->P;
    double cx = 0, cy = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        cx += P->pos[0][i];
        cy += P->pos[1][i];
    }
    cx /= sim->n;
    cy /= sim->n;
    double m = 0, s = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        double d2 = pow(P->pos[0][i] - cx, 2) + pow(P->pos[1][i] - cy, 2);
        s += d2;
        m = fmax(m, d2);
    }
    *rms = sqrt(s / sim->n);
    *ratio = sqrt(m) / *rms;
}

static void run_drop(double gamma, double *ratio0, double *rms0, double *ratio, double *rms)
{
    char ini[1024];
    snprintf(ini, sizeof ini, DROP, gamma);
    sph_sim *sim = test_sim(ini, 2);
    shape(sim, ratio0, rms0);
    while (sim->t < 1.0 && !sim->alarm.raised) sph_sim_step(sim);
    cr_assert(!sim->alarm.raised, "gamma %g: %s", gamma, sim->alarm.what);
    shape(sim, ratio, rms);
    sph_sim_destroy(sim);
}

/* A square of 400 particles with no gravity: with cohesion it contracts and
 * rounds to within 5% of a disc's shape in 1 s; without, the same square
 * spreads (clamped pressure pushes, nothing holds it together). */
Test(cohesion, square_drop_becomes_round, .timeout = 300)
{
    double r0, s0, r1, s1, c0, cs0, c1, cs1;
    run_drop(1.0, &r0, &s0, &r1, &s1);
    run_drop(0.0, &c0, &cs0, &c1, &cs1);
    cr_assert(r0 > 1.6, "the start is a square: ratio %.3f", r0);
    cr_assert(fabs(r1 - sqrt(2.0)) < 0.05 * sqrt(2.0), "with cohesion: ratio %.3f after 1 s, a disc's is 1.414", r1);
    cr_assert(s1 < s0, "with cohesion the drop contracts: rms %.4f -> %.4f m", s0, s1);
    cr_assert(cs1 > 1.05 * cs0, "without cohesion the square spreads: rms %.4f -> %.4f m", cs0, cs1);
    cr_log_info("cohesion: ratio %.3f -> %.3f, rms %.4f -> %.4f m; none: ratio %.3f -> %.3f, rms %.4f -> %.4f m", r0,
                r1, s0, s1, c0, c1, cs0, cs1);
}
