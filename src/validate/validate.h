/* sphlab validate: reference problems with published data or exact
 * solutions, each run by one command that writes a CSV, a chart against the
 * reference (PNG + PDF) and a pass/fail line with its tolerance
 * (docs/accuracy.md, "Validation").
 *
 *   validate_ref.c       the published numbers and the exact solutions (no
 *                        simulation, no PLplot: the tests link it as
 *                        build/validate/libvalidate.a)
 *   validate_run.c       what every problem shares: its scene at a
 *                        resolution, the stepping loop, the outputs, the verdict
 *   cmd_validate.c       the command and the table of problems
 *   val_dam_break.c, val_hydrostatic.c, val_taylor_green.c,
 *   val_poiseuille.c, val_couette.c, val_obstacle.c,
 *   val_drop.c   one problem each */
#ifndef SPH_VALIDATE_H
#define SPH_VALIDATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* ---- reference data (validate_ref.c) ------------------------------------- */

/* A published curve: n points (x[i], y[i]), x increasing. */
typedef struct val_curve {
    const char *label;  /* legend text */
    const char *source; /* the publication, figure or table */
    const double *x, *y;
    int n;
} val_curve;

/* Surge front of the collapsing column, n^2 = 2 (height 2a, width a):
 * Z = front / a against T = t sqrt(2 g / a).
 *   [0] Martin & Moyce 1952, a = 1.125 in
 *   [1] Martin & Moyce 1952, a = 2.25 in
 *   [2] Koshizuka & Oka 1996 (experiment, column L x 2L) */
enum { VAL_SURGE_CURVES = 3 };
extern const val_curve val_surge[VAL_SURGE_CURVES];
/* The same a = 2.25 in front as Martin & Moyce's Table 2 lists it (Z against
 * T): the reference `validate dam-break` judges (the "Table 2"); the
 * three curves above are shown beside it and their error reported. */
extern const val_curve val_surge_table2;
/* Residual column height of the same collapse (Martin & Moyce 1952, Table 6,
 * n^2 = 2, a = 2.25 in): H = height at the back wall / 2a against
 * tau = t sqrt(g/a) = T / n. (Koshizuka & Oka 1996 plot theirs too; no
 * numbers of it are shipped.) */
extern const val_curve val_column;

/* Linear interpolation of the curve at x; NaN outside [x[0], x[n-1]]. */
double val_curve_at(const val_curve *c, double x);

/* Start-up plane Poiseuille flow between no-slip walls at y = 0 and y = L,
 * driven by the body force F [m/s^2] along x, fluid at rest at t = 0
 * (Morris, Fox & Zhu 1997, J. Comput. Phys. 136:214, eq. 21):
 *   u(y, t) = F/(2 nu) y (L - y)
 *           - sum_{n>=0} 4 F L^2 / (nu pi^3 (2n+1)^3) sin(pi y (2n+1)/L)
 *                        exp(-(2n+1)^2 pi^2 nu t / L^2)
 * summed over `terms` terms [m/s]. */
double val_poiseuille(double y, double t, double F, double nu, double L, int terms);
/* Its steady state F/(2 nu) y (L - y) and the largest speed F L^2 / (8 nu). */
double val_poiseuille_steady(double y, double F, double nu, double L);

/* Start-up Couette flow: the wall at y = L moves at U from t = 0, the wall
 * at y = 0 stands still (Morris et al. 1997, section 5.1, the series of the
 * same diffusion problem):
 *   u(y, t) = U y / L + sum_{n>=1} 2 U (-1)^n / (n pi) sin(n pi y / L)
 *                       exp(-n^2 pi^2 nu t / L^2)   [m/s] */
double val_couette(double y, double t, double U, double nu, double L, int terms);

/* The Taylor-Green vortex in the periodic square of side L, as the scene's
 * field = taylor-green starts it (x, y from the domain's corner):
 * u = U exp(b t) sin(2 pi x/L) cos(2 pi y/L), v = -U exp(b t) cos(2 pi x/L)
 * sin(2 pi y/L), b = -8 pi^2 nu / L^2. PySPH's example (Re = U L / nu) uses
 * the same vortex shifted by a quarter period, so the speed, the kinetic
 * energy and the L1 error of the speed are the same. */
double val_tg_decay(double nu, double L, double t); /* exp(b t) [1] */
void val_tg_velocity(double x, double y, double t, double U, double nu, double L, double v[2]);

/* The equation of state of a weakly compressible fluid: p = k (rho - rho0)
 * (linear, tait_gamma = 0) or p = (k rho0 / gamma) ((rho/rho0)^gamma - 1)
 * (Tait, gamma = tait_gamma > 0); k [m^2/s^2] = c^2, rho0 [kg/m^dim]. */
typedef struct val_eos {
    double rho0, k, tait_gamma;
} val_eos;

/* Pressure [Pa] at height y [m] above the floor of a column at rest of that
 * weakly compressible fluid, under gravity g [m/s^2], whose mass equals
 * rho0 H0 per unit floor area: dp/dy = -rho(p) g with p(0) = rho0 g H0
 * (the floor carries the whole weight), integrated numerically. With the
 * linear equation of state it is k rho0 ((1 + g H0/k) exp(-g y/k) - 1);
 * as k grows, rho0 g (H0 - y). The compressed column stands lower than H0
 * (by about g H0^2 / 2k). */
double val_hydrostatic_p(const val_eos *e, double g, double H0, double y);

/* The column at rest a run of `validate hydrostatic` is compared with
 * (validate_ref.c reads the run's state, it steps nothing): *e the run's
 * equation of state, whose rho0 is the density its pressure is relative to
 * (sim->eos_rho0: rest_density, or the lattice's with [physics] eos_rest =
 * lattice); returns H0 [m] such that rho0 g H0 is the fluid's weight per
 * unit floor (its mass over the domain's width along x, times g), i.e. the
 * depth that mass would have at that rho0. */
struct sph_sim;
double val_hydrostatic_column(const struct sph_sim *sim, val_eos *e);

/* The front of the main body of a particle cloud: the largest x among the
 * points (x[i], y[i]) of the largest group linked by distance < link [m]
 * (two points are in one group when a chain of such links joins them), so
 * that a drop or a lone particle thrown ahead of the water does not count;
 * *body (if not NULL) gets that group's size. NaN when n == 0, link <= 0 or
 * out of memory. (validate dam-break) */
double val_front_connected(const double *x, const double *y, size_t n, double link, size_t *body);

/* Observed order of convergence between two resolutions: log(e1/e2) / log(r2/r1). */
double val_order(double r1, double e1, double r2, double e2);

/* ---- the command's parts (validate_run.c, the binary only) ---------------- */

enum {
    VAL_PASS = 0,   /* every target met */
    VAL_FAIL = 1,   /* a target missed: the line says which and by how much */
    VAL_USAGE = 2,  /* bad command line */
    VAL_ERROR = 3,  /* the run could not be made or finished: scene, watchdog, output */
};

#define VAL_MAX_RES 8

typedef struct val_ctx {
    const char *out;        /* directory of the outputs */
    int res[VAL_MAX_RES];   /* the resolutions to run, in order */
    int nres;
    bool quick;             /* the quick resolution and a shorter run, for tests */
    bool quiet;
    int threads;
} val_ctx;

typedef struct val_problem {
    const char *name;
    const char *about;      /* one line */
    const char *reference;  /* what it is compared with */
    const char *target;     /* the tolerance, in words */
    const char *res_meaning; /* what R counts */
    int res_default[3];     /* the three resolutions of a plain run */
    int res_quick;          /* --quick */
    int res_min, res_max;   /* accepted range of R */
    int (*run)(const val_ctx *c, const struct val_problem *p); /* NULL: not written yet */
} val_problem;

extern const val_problem val_problems[];
extern const int val_problem_count;

/* The period of an oscillation (x time, increasing) from the crossings of y through its mean: twice
 * the mean time between the first and the last crossing over an even number of half periods (a record
 * that does not hold whole periods has its mean off the centre line, which makes the half periods
 * alternate short and long); the crossings counted in *k; NaN below 3 crossings. (validate drop) */
double val_period_crossings(const double *x, const double *y, size_t n, int *k);
/* The times (x) at which y crosses its mean, as val_period_crossings finds them, into t (at most max); their
 * count. */
int val_crossing_times(const double *x, const double *y, size_t n, double *t, int max);
/* The spread of the half periods between k crossing times, (longest - shortest) / their mean; NaN below 3. */
double val_half_period_spread(const double *t, int k);
/* The largest spread a steady (or decaying) sine's half periods show when crossings are taken through the mean
 * of a record of `periods` periods: the record's mean sits up to a / (pi periods) off the centre, a the first
 * amplitude (the mean of a sin (omega t + phi) over [0, 2 pi P] is at most 2 a / (2 pi P)), which moves each
 * crossing by asin(delta / a_t) / omega, a_t the amplitude there (at least the last, a / decay), one half period
 * longer and the next shorter by that twice: spread 4 asin(decay / (pi P)) / pi (a steady sine over 1.5
 * periods: 0.27; over 3: 0.135). A larger spread is no steady period. NaN for periods <= 0 or decay < 1. */
double val_half_period_bound(double periods, double decay);
/* decay for it: the largest |y - mean| between the first two crossings t[0], t[1] over that between the last two
 * (at least 1); NaN below 3 crossings. */
double val_amplitude_ratio(const double *x, const double *y, size_t n, const double *t, int k);
/* The drop's period against Rayleigh's as the verdict line gives it: "period T s (from the first 4 of its 5
 * half periods: whole periods only) vs Rayleigh T_ray s (+e%)",
 * or, where the record crossed its mean fewer than 3 times (T NaN), "no period: k crossings of the mean in
 * the run (3 needed), Rayleigh T_ray s" rather than a NaN; the same for T_ray NaN (sigma not measurable). */
void val_period_text(char *buf, size_t n, double T, double T_ray, int crossings);

#endif
