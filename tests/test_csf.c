/* surface_tension = csf (src/passes/csf.c): the continuum surface force on a
 * disc at rest, the delta's integral B on the lattice, the time step's
 * capillary bound, and the refusals. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

double sph_csf_delta_integral(const sph_kernel *k, int dim, double s);

#define PI 3.14159265358979323846

/* A disc of radius R (m) at (0.5, 0.5) cut from a square lattice of spacing
 * s, at rest; the lattice's other particles are parked far away, each
 * alone (no neighbour within h), so they feel and give nothing. One step
 * of 1e-7 s computes the forces at these positions. */
static sph_sim *disc_sim(double R, double s, double h, double sigma, const char *kernel, uint32_t *inside)
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
            P->pos[0][i] = (float)(0.5 + r * cos(a)), P->pos[1][i] = (float)(0.5 + r * sin(a));
        }
    }
    *inside = i;
    for (uint32_t out = 0; i < sim->n; i++, out++)
        P->pos[0][i] = (float)(1.1 + 0.05 * (out % 36)), P->pos[1][i] = (float)(1.1 + 0.05 * (out / 36));
    sph_sim_step(sim);
    return sim;
}

Test(csf, debug)
{
    uint32_t inside;
    const double R = 0.1, s = 0.005, sigma = 1;
    sph_sim *sim = disc_sim(R, s, 3 * s, sigma, "cubic", &inside);
    const sph_particles *P = &sim->P;
    double Reff = sqrt(inside * s * s / PI);
    double fr = 0, fx = 0, fy = 0, fabs_sum = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        double x = P->pos[0][i] - 0.5, y = P->pos[1][i] - 0.5, r = sqrt(x * x + y * y);
        if (r > R) continue;
        double m = P->mass[i], ax = P->acc_s[0][i], ay = P->acc_s[1][i];
        fx += m * ax, fy += m * ay, fabs_sum += m * sqrt(ax * ax + ay * ay);
        fr += m * (ax * x + ay * y) / r;
        if (r < 0.09 && hypot(ax, ay) > 0.01) printf("INNER r %.4f curv %.3f |n| %.3f a %.4f\n", r, P->curv[i], hypot(P->normal[0][i], P->normal[1][i]), hypot(ax, ay));
        if (0) printf("r %.4f y %.4f curv %.3f |n| %.3f a_r %.4f rho %.1f\n", r, y, P->curv[i], hypot(P->normal[0][i], P->normal[1][i]), (ax*x+ay*y)/r, P->rho[i]);
    }
    printf("inside %u Reff %.4f 1/R %.3f inward force per length %.4f (sigma/R %.3f) net %.3g %.3g of %.3g B %.4f\n", inside, Reff, 1/Reff,
           -fr / (2 * PI * Reff), sigma / Reff, fx, fy, fabs_sum, sph_csf_delta_integral(&sim->k_density, 2, s));
    sph_sim_destroy(sim);
}
