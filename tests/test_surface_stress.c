/* surface_tension = stress (src/passes/surface_stress.c): the divergence of
 * the surface stress sigma (I - n n) delta_s. Its pairs' terms are equal and
 * opposite (momentum conserved to rounding), the tension it puts along a
 * disc's rim pulls the disc in by sigma / R per unit length, and a drop left
 * alone keeps round, where surface_tension = csf grows an n = 2 oscillation
 * from nothing (docs/accuracy.md, the drop). */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

#define PI 3.14159265358979323846

/* A disc of radius R (m) at (0.5, 0.5) on rings of spacing s (as validate drop lays it), each position moved
 * by up to jitter s along each axis (a fixed sequence); the block's other particles parked far apart. One
 * step of 1e-7 s computes the forces at these positions. */
static sph_sim *disc_sim(const char *tension, double R, double s, double jitter, uint32_t *inside)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=3 3\n"
             "[fluid b]\nmin=%.9g %.9g\nmax=%.9g %.9g\nspacing=%g\n"
             "[physics]\nsurface_tension=%s\nsigma=1\n[kernels]\nh=%g\ndensity=cubic\n[time]\ndt=1e-7\ncfl=0\n",
             0.5 - R, 0.5 - R, 0.5 + R, 0.5 + R, s, tension, 3 * s);
    sph_sim *sim = test_sim(ini, 1);
    sph_particles *P = &sim->P;
    uint32_t i = 0, seed = 12345;
    for (int l = 0; R - (l + 0.5) * s > 0.25 * s && i < sim->n; l++) {
        double r = R - (l + 0.5) * s;
        int m = (int)lround(2 * PI * r / s);
        if (m < 1) m = 1;
        for (int k = 0; k < m && i < sim->n; k++, i++) {
            double a = 2 * PI * (k + 0.5 * (l % 2)) / m, d[2];
            for (int c = 0; c < 2; c++) {
                seed = seed * 1664525u + 1013904223u;
                d[c] = jitter * s * ((seed >> 8) / 8388608.0 - 1.0);
            }
            P->pos[0][i] = (float)(0.5 + r * cos(a) + d[0]), P->pos[1][i] = (float)(0.5 + r * sin(a) + d[1]);
        }
    }
    *inside = i;
    for (uint32_t out = 0; i < sim->n; i++, out++)
        P->pos[0][i] = (float)(1.1 + 0.05 * (out % 36)), P->pos[1][i] = (float)(1.1 + 0.05 * (out / 36));
    sph_sim_step(sim);
    return sim;
}

/* A disordered disc (R = 20 spacings, each particle moved by up to 0.2 spacing): the forces sum to zero within
 * the float rounding of each particle's acceleration (1e-6 of the sum of their magnitudes; measured 2e-8). */
Test(surface_stress, momentum_is_conserved_to_rounding)
{
    uint32_t inside;
    sph_sim *sim = disc_sim("stress", 0.1, 0.005, 0.2, &inside);
    const sph_particles *P = &sim->P;
    cr_assert_not_null(P->acc_t[0], "surface_tension = stress allocates acc_t");
    double fx = 0, fy = 0, fsum = 0;
    int pulled = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        double m = P->mass[i], ax = P->acc_t[0][i], ay = P->acc_t[1][i];
        fx += m * ax, fy += m * ay, fsum += m * hypot(ax, ay);
        pulled += ax != 0 || ay != 0;
    }
    cr_assert_gt(pulled, 100, "%d of %u particles feel the force", pulled, inside);
    cr_log_info("net force (%g, %g) N/m of %g N/m: %.2g\n", fx, fy, fsum, hypot(fx, fy) / fsum);
    cr_assert_lt(hypot(fx, fy), 1e-6 * fsum, "net force (%g, %g) of %g", fx, fy, fsum);
    sph_sim_destroy(sim);
}

/* The rim's tension pulls the disc in: the inward forces summed over the disc (R = 20 spacings, on rings), per
 * unit length of its rim, are sigma / R within 5 % (the tension across a cut is sigma by the stress's
 * calibration, delta_s = s_i / (V_i c_i); the force a curved rim under that tension takes is sigma / R). */
Test(surface_stress, disc_is_pulled_in_by_sigma_over_r)
{
    uint32_t inside;
    const double R = 0.1;
    sph_sim *sim = disc_sim("stress", R, 0.005, 0.0, &inside);
    const sph_particles *P = &sim->P;
    double fr = 0;
    for (uint32_t i = 0; i < sim->n; i++) { /* the step may have reordered the particles */
        double x = P->pos[0][i] - 0.5, y = P->pos[1][i] - 0.5, r = hypot(x, y);
        if (r > 0 && r < 2 * R) fr += P->mass[i] * (P->acc_t[0][i] * x + P->acc_t[1][i] * y) / r;
    }
    double per_length = -fr / (2 * PI * R);
    cr_log_info("inward force per length %g N/m, sigma/R %g\n", per_length, 1 / R);
    cr_assert(fabs(per_length * R - 1) < 0.05, "inward force per length %g N/m, sigma/R = %g", per_length, 1 / R);
    sph_sim_destroy(sim);
}

/* validate drop's drop (scenes/validate/drop.ini's physics but negp, the negative_pressure choice; R = 0.1 m,
 * spacing R / res), laid on rings, settled by damping to t = 1 s and then left alone, never kicked, to t_end:
 * *p the magnitude of its total momentum [kg m/s per metre], *aniso the largest |D_x - D_y| [m] from 1.5 s
 * (D = 4 sqrt(<x^2>)), *ke its largest kinetic energy [J/m] from 1.5 s. */
static void drop_left_alone(const char *tension, const char *negp, int res, double t_end, double *p, double *aniso,
                            double *ke)
{
    const double R = 0.1, s = R / res;
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=pressure viscosity\n[domain]\nmin=0 0\nmax=1 1\n"
             "[fluid drop]\nmin=0.4114 0.4114\nmax=0.5886 0.5886\nspacing=%g\n"
             "[physics]\nstiffness=100\nnegative_pressure=%s\nviscosity=0.0001\nsurface_tension=%s\nsigma=1\n"
             "density_method=continuity\ndelta=0.1\ndamping_time=1\n"
             "[kernels]\nh=%g\ndensity=cubic\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.4\ndt=0.001\n",
             s, negp, tension, 3 * s);
    sph_sim *sim = test_sim(ini, 2);
    sph_particles *P = &sim->P;
    const uint32_t n = sim->n;
    const double Rd = sqrt(n * s * s / PI), cx = 0.5 - sim->origin[0], cy = 0.5 - sim->origin[1];
    uint32_t i = 0;
    for (int l = 0; i < n; l++) { /* validate drop's rings (val_drop.c) */
        double r = Rd - (l + 0.5) * s;
        int m = r > 0.25 * s ? (int)lround(2 * PI * r / s) : 1;
        if (r <= 0.25 * s || i + (uint32_t)m > n) m = (int)(n - i), r = fmax(r, 0.0);
        for (int k = 0; k < m; k++, i++) {
            double a = 2 * PI * (k + 0.5 * (l % 2)) / m, rr = m == 1 ? 0.0 : fmax(r, 0.5 * s);
            P->pos[0][i] = (float)(cx + rr * cos(a)), P->pos[1][i] = (float)(cy + rr * sin(a));
        }
    }
    for (i = 0; i < n; i++) P->rho_c[i] = sim->def.rest_density;
    sim->rho_carried = true;
    *aniso = 0, *ke = 0;
    cr_assert(fabs(Rd - R) < 0.01);
    while (sim->t < t_end) {
        sph_sim_step(sim);
        cr_assert(!sim->alarm.raised, "%s: the watchdog stopped the drop at t = %g s", tension, sim->t);
        if (sim->t < 1.5) continue;
        double c[2] = {0, 0}, m2[2] = {0, 0};
        for (i = 0; i < n; i++) c[0] += P->pos[0][i] / n, c[1] += P->pos[1][i] / n;
        for (i = 0; i < n; i++)
            for (int d = 0; d < 2; d++) m2[d] += (P->pos[d][i] - c[d]) * (P->pos[d][i] - c[d]) / n;
        *aniso = fmax(*aniso, fabs(4 * (sqrt(m2[0]) - sqrt(m2[1]))));
        double e = 0;
        for (i = 0; i < n; i++) e += 0.5 * P->mass[i] * (P->vel[0][i] * P->vel[0][i] + P->vel[1][i] * P->vel[1][i]);
        *ke = fmax(*ke, e);
    }
    double px = 0, py = 0;
    for (i = 0; i < n; i++) px += P->mass[i] * P->vel[0][i], py += P->mass[i] * P->vel[1][i];
    *p = hypot(px, py);
    sph_sim_destroy(sim);
}

/* The drop left alone keeps still: its momentum stays below 1e-5 kg m/s per metre (its mass, 31.4 kg/m, at
 * the capillary speed sqrt(sigma / (rho R)) = 0.1 m/s carries 3.1; measured 1.8e-8), and its n = 2 moment
 * |D_x - D_y| below 1e-3 m (measured 1.0e-4). surface_tension = csf on the same drop fails it: momentum
 * 2.5e-3 (its surface particles' forces have no reactions and sum to a net force), |D_x - D_y| 5.5e-5 m.
 * Its kinetic energy from 1.5 to 2.5 s stays below 7e-4 J/m (3.5 times the 2e-4 of validate drop's kick):
 * with the stress carried from |h grad c| > 0.3 (csf's cut, on the second row) it reached 1.3e-3 J/m at 2 s,
 * from 0.6 (surface_stress.c) 4.9e-4. These figures are with the pressure clamped at 0 (the scene's choice then;
 * the R/10 drop does not need keep, the R/20 one does: r20_drop_left_alone_keeps_its_energy). */
Test(surface_stress, drop_left_alone_keeps_still_and_round, .timeout = 300)
{
    double p, aniso, ke;
    drop_left_alone("stress", "clamp", 10, 2.5, &p, &aniso, &ke);
    cr_log_info("stress: momentum %g kg m/s, |D_x - D_y| %g m, kinetic energy %g J/m\n", p, aniso, ke);
    cr_assert_lt(p, 1e-5, "momentum %g kg m/s per metre", p);
    cr_assert_lt(aniso, 1e-3, "|D_x - D_y| %g m", aniso);
    cr_assert_lt(ke, 7e-4, "kinetic energy %g J/m", ke);
}

/* The R/20 drop (1225 particles) left alone to 3 s with the scene's negative_pressure = keep: its kinetic energy
 * from 1.5 s stays below 1e-3 J/m (measured 5.3e-4; the scene, one thread: 3.7e-4 at 3 s). With the pressure
 * clamped at 0 this test fails (0.052 J/m at 3 s) and the kicked drop of validate drop went past the watchdog:
 * the particles the cubic kernel's pairing noise expands below rho0 under the surface got p = 0, were clumped
 * by the surface stress's tangential pull (pairs at 0.37 spacings) and thrown out (docs/accuracy.md, the drop). */
Test(surface_stress, r20_drop_left_alone_keeps_its_energy, .timeout = 900)
{
    double p, aniso, ke;
    drop_left_alone("stress", "keep", 20, 3.0, &p, &aniso, &ke);
    cr_log_info("R/20: momentum %g kg m/s, |D_x - D_y| %g m, kinetic energy %g J/m\n", p, aniso, ke);
    cr_assert_lt(ke, 1e-3, "kinetic energy %g J/m", ke);
    cr_assert_lt(aniso, 1e-3, "|D_x - D_y| %g m", aniso);
}
