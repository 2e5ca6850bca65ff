/* surface_tension = csf (src/passes/csf.c): the continuum surface force on a
 * disc at rest (its curvature and each particle's share of the rim), its
 * stiffness against the n = 2 mode of an ellipse, the time
 * step's capillary bound, and a run on the GL backend. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

#define PI 3.14159265358979323846

/* A disc of radius R (m) at (0.5, 0.5) cut from a square lattice of spacing
 * s, at rest; the lattice's other particles are parked far away, each
 * alone (no neighbour within h), so they feel and give nothing. One step
 * of 1e-7 s computes the forces at these positions. */
static sph_sim *ellipse_sim(double R, double s, double h, double sigma, const char *kernel, double e, uint32_t *inside)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=3 3\n"
             "[fluid b]\nmin=%.9g %.9g\nmax=%.9g %.9g\nspacing=%g\n"
             "[physics]\nsurface_tension=csf\nsigma=%g\n[kernels]\nh=%g\ndensity=%s\n[time]\ndt=1e-7\ncfl=0\n",
             0.5 - R, 0.5 - R, 0.5 + R, 0.5 + R, s, sigma, h, kernel);
    sph_sim *sim = test_sim(ini, 1);
    sph_particles *P = &sim->P;
    /* rings of radius R - (l + 1/2) s, each of round(2 pi r / s) particles, down to the centre */
    uint32_t i = 0;
    for (int l = 0; R - (l + 0.5) * s > 0.25 * s && i < sim->n; l++) {
        double r = R - (l + 0.5) * s;
        int m = (int)lround(2 * PI * r / s);
        if (m < 1) m = 1;
        for (int k = 0; k < m && i < sim->n; k++, i++) {
            double a = 2 * PI * (k + 0.5 * (l % 2)) / m;
            P->pos[0][i] = (float)(0.5 + (1 + e) * r * cos(a)), P->pos[1][i] = (float)(0.5 + r * sin(a) / (1 + e));
        }
    }
    *inside = i;
    for (uint32_t out = 0; i < sim->n; i++, out++)
        P->pos[0][i] = (float)(1.1 + 0.05 * (out % 36)), P->pos[1][i] = (float)(1.1 + 0.05 * (out / 36));
    sph_sim_step(sim);
    return sim;
}

static sph_sim *disc_sim(double R, double s, double h, double sigma, const char *kernel, uint32_t *inside)
{
    return ellipse_sim(R, s, h, sigma, kernel, 0.0, inside);
}

/* A disc of R = 20 spacings (cubic kernel, h = 3 spacings, sigma = 1 N in
 * 2D): every particle the force acts on is pulled towards the centre; the
 * outer ring's curvature is within 5 % of 1/r, r its radius R - s/2; the inward force summed over
 * the disc, per unit length of its rim, is sigma/R within 2 % (measured
 * -0.5 %: each particle's share of the rim is a partition of it; the flat
 * lattice's constant B this pass used before read +3.0 %); the net force is
 * below 3 % of the sum of the magnitudes (the rings' staggered starts break the symmetry). */
Test(csf, disc_is_pulled_in_by_sigma_over_r)
{
    uint32_t inside;
    const double R = 0.1, s = 0.005, sigma = 1;
    sph_sim *sim = disc_sim(R, s, 3 * s, sigma, "cubic", &inside);
    const sph_particles *P = &sim->P;
    cr_assert_not_null(P->acc_s[0], "surface_tension = csf allocates acc_s");
    double fr = 0, fx = 0, fy = 0, fsum = 0;
    int outer = 0;
    for (uint32_t i = 0; i < sim->n; i++) { /* the step may have reordered the particles */
        double x = P->pos[0][i] - 0.5, y = P->pos[1][i] - 0.5, r = sqrt(x * x + y * y);
        if (r > R) continue;
        double m = P->mass[i], ax = P->acc_s[0][i], ay = P->acc_s[1][i], a = sqrt(ax * ax + ay * ay);
        fx += m * ax, fy += m * ay, fsum += m * a;
        if (a > 0) {
            fr += m * (ax * x + ay * y) / r;
            cr_assert_lt((ax * x + ay * y) / r, -0.9 * a, "particle at r = %.4f: a = (%g, %g) is not inward", r, ax, ay);
        }
        if (r > R - s) {
            outer++;
            cr_assert(fabs(P->curv[i] * r - 1) < 0.05, "outer ring, r = %.4f: curvature %g 1/m, 1/r = %g", r,
                      P->curv[i], 1 / r);
        }
    }
    cr_assert_gt(outer, 100, "%u particles in the disc, %d on its outer ring", inside, outer);
    double per_length = -fr / (2 * PI * R);
    cr_assert(fabs(per_length / (sigma / R) - 1) < 0.02, "inward force per length %g N/m, sigma/R = %g", per_length,
              sigma / R);
    cr_assert_lt(hypot(fx, fy), 0.03 * fsum, "net force (%g, %g) of %g", fx, fy, fsum);
    sph_sim_destroy(sim);
}

/* A block at rest: no force inside, and none at the middle of a flat side
 * (curvature below 1/(20 L) there, L the block's side), where a corner pulls in. */
Test(csf, flat_side_has_no_curvature)
{
    sph_sim *sim = test_sim("[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid b]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.005\n"
                            "[physics]\nsurface_tension=csf\nsigma=1\n[kernels]\nh=0.015\ndensity=cubic\n"
                            "[time]\ndt=1e-7\ncfl=0\n", 1);
    sph_sim_step(sim);
    const sph_particles *P = &sim->P;
    int side = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        double x = P->pos[0][i] - 0.5, y = P->pos[1][i] - 0.5;
        if (fabs(x) < 0.08 && fabs(y) < 0.08)
            cr_assert(P->acc_s[0][i] == 0 && P->acc_s[1][i] == 0, "inside (%g, %g): a csf (%g, %g)", x, y,
                      P->acc_s[0][i], P->acc_s[1][i]);
        if (fabs(x) < 0.03 && y > 0.097) {
            side++;
            cr_assert_lt(fabs(P->curv[i]), 1 / (20 * 0.2), "flat side at x = %g: curvature %g", x, P->curv[i]);
        }
    }
    cr_assert_gt(side, 5);
    sph_sim_destroy(sim);
}

/* The GL backend runs csf (tests/test_gl_csf.c compares it with the CPU):
 * a run there may fail only for want of an OpenGL 4.3 context, never by
 * refusing it. */
Test(csf, gl_backend_runs_it)
{
    const char *scene = test_write_temp("[scene]\ndimension=2\neffects=density\n[domain]\nmax=1 1\n"
                                        "[fluid b]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.02\n"
                                        "[physics]\nsurface_tension=csf\nsigma=0.5\n[kernels]\nh=0.04\n",
                                        ".ini");
    char args[600], out[8192];
    snprintf(args, sizeof args, "run %s --backend gl --steps 1 -q", scene);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0 || strstr(out, "no OpenGL 4.3 context"), "%s: %s", args, out);
    cr_assert(!strstr(out, "not implemented by the GL backend"), "%s: %s", args, out);
}

/* The perimeter of the ellipse of semi-axes R (1 + e) and R / (1 + e) (midpoint rule, 4096 points). */
static double ellipse_perimeter(double R, double e)
{
    double a = R * (1 + e), b = R / (1 + e), P = 0;
    for (int k = 0; k < 4096; k++) {
        double t = 2 * PI * (k + 0.5) / 4096;
        P += hypot(a * sin(t), b * cos(t));
    }
    return P * 2 * PI / 4096;
}

/* The restoring force of the n = 2 mode, the stiffness behind Rayleigh's period. The disc stretched to the
 * ellipse x (1 + e), y / (1 + e) (area kept) has the surface energy sigma P(e), P its perimeter,
 * 2 pi R (1 + 3 e^2 / 4 + O(e^3)); the mode's generalised force, the work of the forces per unit de along
 * the stretch's velocity field (x, -y), is Q = sum_i m_i a_i . (x_i, -y_i), and the exact one is
 * -sigma dP/de (-3 pi sigma R e for small e: with the mode's mass rho pi R^4 / 2, omega^2 = 6 sigma /
 * (rho R^3)). R is the radius of the disc of the particles' area. Measured, Q against -sigma dP/de:
 * R/10 0.961 (e = 0.01), 0.970 (0.02); R/20 0.991, 1.002; so the csf force's stiffness lengthens the period
 * by at most 2 % at R/10 (1 / sqrt(0.961)) and 0.5 % at R/20. Held within 5 %. */
Test(csf, ellipse_restoring_force_is_rayleighs)
{
    const double R = 0.1, sigma = 1;
    const double es[] = {0.01, 0.02};
    for (int res = 10; res <= 20; res *= 2)
        for (int k = 0; k < 2; k++) {
            uint32_t inside;
            const double s = R / res, e = es[k];
            sph_sim *sim = ellipse_sim(R, s, 3 * s, sigma, "cubic", e, &inside);
            const sph_particles *P = &sim->P;
            double Q = 0, cx = 0, cy = 0;
            int n = 0;
            for (uint32_t i = 0; i < sim->n; i++) /* the drop's particles; the parked ones sit beyond x = 1 */
                if (P->pos[0][i] < 1.0f) cx += P->pos[0][i], cy += P->pos[1][i], n++;
            cx /= n, cy /= n;
            for (uint32_t i = 0; i < sim->n; i++) {
                if (P->pos[0][i] >= 1.0f) continue;
                double x = P->pos[0][i] - cx, y = P->pos[1][i] - cy;
                Q += P->mass[i] * (P->acc_s[0][i] * x - P->acc_s[1][i] * y);
            }
            const double Rf = s * sqrt(inside / PI), de = 1e-4;
            const double Q_exact = -sigma * (ellipse_perimeter(Rf, e + de) - ellipse_perimeter(Rf, e - de)) / (2 * de);
            cr_log_info("R/%d e %.3f: Q %.5g N, -sigma dP/de %.5g N (per metre of depth), ratio %.4f", res, e, Q,
                        Q_exact, Q / Q_exact);
            cr_expect(fabs(Q / Q_exact - 1) < 0.05, "R/%d, e = %.2f: Q %g N, -sigma dP/de %g N", res, e, Q, Q_exact);
            sph_sim_destroy(sim);
        }
}

/* The pass's description names sigma in the key's unit: per metre of depth in 2D (N), N/m in 3D; it said
 * N/m in 2D too. */
Test(csf, description_names_sigma_in_the_dimensions_unit)
{
    sph_scene_def def;
    memset(&def, 0, sizeof def);
    def.surface_tension = SPH_STENSION_CSF;
    def.sigma = 0.0728f;
    char out[256];
    def.dim = 2;
    sph_passes[SPH_PASS_CSF]->describe(&def, out, (int)sizeof out);
    cr_assert(strstr(out, "sigma 0.0728 N") && !strstr(out, "N/m"), "2D: %s", out);
    def.dim = 3;
    sph_passes[SPH_PASS_CSF]->describe(&def, out, (int)sizeof out);
    cr_assert(strstr(out, "sigma 0.0728 N/m"), "3D: %s", out);
}
