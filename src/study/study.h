/* The accuracy study: reference problems with known answers, each with an
 * error computed the same way every time (docs/accuracy.md), and the
 * machinery of `sphlab study` (knobs, combinations, the Pareto front).
 *
 * This part has no PLplot and no GL: the tests link it as a library
 * (build/study/libstudy.a). The charts and the commands are in
 * study_plot.c, cmd_study.c and cmd_estimate.c.
 *
 *   study_ref.c       the scene-based problems: density of a block, the
 *                     hydrostatic tank, the Taylor-Green vortex; one run
 *   study_estimate.c  kernel estimation of a known function (1D and 2D)
 *   study_vary.c      --vary knobs, combinations, the Pareto front, CSV */
#ifndef SPH_STUDY_H
#define SPH_STUDY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sph_sim.h"

/* ---- reference problems ------------------------------------------------- */

/* The metrics, each the error of one reference problem. */
#define STUDY_METRICS(X)                                                                               \
    X(DENSITY, "density", "interior density error, RMS of rho/rho0 - 1 over particles at least h inside the block") \
    X(DENSITY_SURFACE, "density-surface",                                                              \
      "free-surface density error, RMS of (rho - rho0 (1 - psi(d)))/rho0 over particles within h of one face") \
    X(HYDROSTATIC, "hydrostatic",                                                                      \
      "pressure profile error, RMS over depth layers of (p - rho0 g (H - y)) / (rho0 g H)")            \
    X(TAYLOR_GREEN, "taylor-green", "relative error of the decay rate of E_kin fitted over the run, |rate/(4 nu k^2) - 1|") \
    X(COMPRESSION, "compression",                                                                      \
      "each step's largest compression max(rho/rho_held - 1) over the fluid, averaged over time (rho_held: rho0 " \
      "for the equation of state, the lattice's rest sum for pcisph and dfsph)")

typedef enum study_metric {
#define STUDY_METRIC_ENUM(id, name, about) STUDY_METRIC_##id,
    STUDY_METRICS(STUDY_METRIC_ENUM)
#undef STUDY_METRIC_ENUM
    STUDY_METRIC_COUNT
} study_metric;

extern const char *const study_metric_names[STUDY_METRIC_COUNT];
extern const char *const study_metric_about[STUDY_METRIC_COUNT];

/* The metric named `name`, or -1. */
int study_metric_find(const char *name);
/* The reference problem a scene is, from its shape: a Taylor-Green block;
 * a tank (gravity, pressure, walls, every block as wide as the domain and
 * on its floor); or a block whose density is only computed (effects without
 * pressure). -1 if none. */
int study_metric_guess(const sph_scene_def *def);
/* Whether the metric applies to the scene; if not, a sentence in why. */
bool study_metric_check(study_metric m, const sph_scene_def *def, char *why, size_t n);

#define STUDY_MAX_EXTRA 5

/* Names of a metric's extra figures (CSV columns after the error); returns their count. */
int study_metric_extras(study_metric m, const char *names[STUDY_MAX_EXTRA]);

typedef struct study_result {
    double error;                  /* the metric's error [1]; NaN if the run was stopped */
    double extra[STUDY_MAX_EXTRA]; /* the metric's extra figures, named by study_metric_extras */
    uint32_t particles;
    uint64_t steps;
    double t_end;                  /* [s] simulated time at the end */
    double wall_ms;                /* [ms] time spent in sph_sim_step only (not in creating or measuring) */
    bool stopped;                  /* the watchdog stopped the run */
    char note[512];                /* why it stopped, or a remark on the measurement */
} study_result;

/* Fills the extras that depend on the run's wall time, once the study has
 * replaced r->wall_ms by the median of its repeats (compression: ms per
 * simulated second). */
void study_result_timed(study_metric m, study_result *r);

/* Called during a run, at most every few steps; done is the fraction of the run. */
typedef void (*study_progress_fn)(void *ctx, const sph_sim *sim, double done);

/* Runs the scene for `steps` steps, or until `until` seconds if until >= 0,
 * with the metric observing it, and fills *out. False (and a sentence in
 * why) if the simulation cannot be made or the metric does not apply; a run
 * the watchdog stops is not a failure (out->stopped, error NaN). */
bool study_run(const sph_scene_def *def, study_metric m, long steps, double until, int threads,
               study_progress_fn progress, void *ctx, study_result *out, char *why, size_t n);

/* ---- live figures (for a window beside the timings) ------------------------ */

/* Accuracy figures a live view can show after each step, cheap to update
 * (one pass over the particles, as sph_sim_stats):
 *   density_error  (rho_max - rho0) / rho0, the compression a weakly
 *                  compressible fluid is allowed (aim: a few %)
 *   density_rms    RMS of rho/rho0 - 1 over all particles (free surfaces
 *                  included, where it is low by design)
 *   energy_drift   (E - E0) / scale, E = E_kin + E_pot + E_int, E0 after the
 *                  first update, scale = max(|E0|, largest E_kin seen): > 0
 *                  means the scheme gains energy (viscosity and walls only
 *                  take it out). Call study_live_reset after a reconfigure. */
typedef struct study_live {
    bool started;
    double e0, scale;
    double density_error, density_rms, energy_drift; /* [1] */
} study_live;

void study_live_reset(study_live *l);
void study_live_update(study_live *l, const sph_sim *sim);

/* ---- kernel estimation --------------------------------------------------- */

typedef enum study_function { STUDY_FN_SIN, STUDY_FN_GAUSS, STUDY_FN_COUNT } study_function;
typedef enum study_samples { STUDY_SAMPLES_LATTICE, STUDY_SAMPLES_JITTER, STUDY_SAMPLES_RANDOM, STUDY_SAMPLES_COUNT } study_samples;
extern const char *const study_function_names[STUDY_FN_COUNT];
extern const char *const study_samples_names[STUDY_SAMPLES_COUNT];

#define STUDY_EST_H_MAX 0.125 /* [1] largest h: supports stay inside the sampled square */

typedef struct study_est_opts {
    int dim;                 /* 1 or 2 */
    study_function fn;       /* sin(2 pi x) [sin(2 pi y)], or a Gaussian bump of width 0.1 at the centre */
    sph_kernel_kind kernel;  /* any but the viscosity kernel (meant for its Laplacian) */
    study_samples samples;   /* lattice, jittered lattice, or uniform random */
    double jitter;           /* [spacing] for STUDY_SAMPLES_JITTER: offset up to this on each axis */
    uint64_t seed;
} study_est_opts;

typedef struct study_est_result {
    double error;      /* RMS of <f> - f over the evaluation points (f has amplitude 1) */
    double max_error;  /* largest |<f> - f| there */
    double bias;       /* predicted smoothing bias: RMS of (M2 / 2d) lap f over the same points */
    double samples;    /* number of samples over the unit square */
    double neighbours; /* mean number of samples inside the support of an evaluation point */
} study_est_result;

/* Estimates f from n samples per unit length (n^dim in all) with support
 * radius h (at most STUDY_EST_H_MAX): <f>(x) = sum_j (m_j / rho_j) f(x_j)
 * W(x - x_j, h), rho_j = sum_k m_k W(x_j - x_k, h) as the density pass
 * computes it, m_j = 1 / n^dim. The evaluation points are a fixed grid over
 * the centre [0.25, 0.75]^dim (201 points in 1D, 41 x 41 in 2D). */
bool study_estimate(const study_est_opts *o, double h, int n, study_est_result *r, char *why, size_t wn);
/* What `sphlab estimate` does after its options: the error for every n and h
 * (h_list / n_list NULL: the command's defaults; at most 16 of each), its
 * table on stdout unless quiet, and with out DIR/BASE.csv and the log-log
 * chart. Returns the command's exit status. */
int study_estimate_write(const study_est_opts *o, const double *h_list, int nh, const double *n_list, int nn,
                         const char *out, const char *base, bool quiet);

/* The 1D kernels: the core's shapes with 1D normalisation (the integral over
 * the line is 1): poly6 35/(32 h^7), spiky 2/h^4, cubic 4/(3h), Wendland
 * 3/(2h). The viscosity kernel has no 1D form here (0). */
double study_kernel1d_sigma(sph_kernel_kind kind, double h);
double study_kernel1d_w(sph_kernel_kind kind, double h, double r);
/* Second moment M2 = integral of r^2 W over the line (1D) or plane (2D) [m^2]. */
double study_kernel_m2(sph_kernel_kind kind, int dim, double h);

/* ---- the study: knobs and combinations ------------------------------------ */

#define STUDY_MAX_KNOBS 8
#define STUDY_MAX_VALUES 32
#define STUDY_MAX_COMBOS 4096

/* One --vary KEY=V1,V2,...: a scene key (section.key, as for --set), or a
 * derived knob: h_over_spacing (kernels.h = value x the finest spacing) or
 * kernel (kernels.density, .pressure and .viscosity all set to one kernel),
 * or a linked knob, scene keys joined by '+' whose values are joined by '+'
 * too (KEY1+KEY2=A1+B1,A2+B2: the keys change together, not as a product). */
typedef struct study_knob {
    char key[96];
    int n;
    char value[STUDY_MAX_VALUES][64];
} study_knob;

typedef struct study_plan {
    study_knob knob[STUDY_MAX_KNOBS];
    int n_knobs;
} study_plan;

/* Parses one --vary argument into the plan; false and a sentence in why
 * for a missing '=', an empty list or value, a repeated key, too many. */
bool study_plan_add(study_plan *p, const char *arg, char *why, size_t n);
/* Number of combinations (the product of the list lengths). */
long study_plan_count(const study_plan *p);
/* The values of combination c: idx[k] is the value index of knob k. The
 * first knob varies slowest. */
void study_plan_combo(const study_plan *p, long c, int idx[STUDY_MAX_KNOBS]);
/* Applies combination c to *def (scene keys first, in order, then the
 * derived knobs) and validates the result. False and the message if a key is
 * unknown, a value does not parse or is out of range, or the scene does not
 * validate. */
bool study_plan_apply(const study_plan *p, long c, sph_scene_def *def, char *why, size_t n);
/* The same; *usage: a knob's key or value was refused (a bad command line, exit 2), not the scene it makes. */
bool study_plan_apply_why(const study_plan *p, long c, sph_scene_def *def, char *why, size_t n, bool *usage);

/* Pareto front of the points (time, error), both smaller is better: front[i]
 * is true if point i is valid (both finite, time > 0, error >= 0) and no
 * other valid point is at least as good in both and better in one. Returns
 * the number of points on the front. */
int study_pareto(const double *time, const double *error, int n, bool *front);

/* Median of v[0..n) (finite values; NaN if none). Does not change v. */
double study_median(const double *v, int n);

/* A row of study.csv and of the table. */
typedef struct study_row {
    int idx[STUDY_MAX_KNOBS];
    study_result r;        /* of the first repeat; wall_ms replaced by the median */
    double ms_per_step;    /* median wall time / steps */
    double total_s;        /* median wall time of a run [s] */
    double h_over_s;       /* [1] kernels.h over the finest spacing, NAN without a block */
    bool front;
} study_row;

/* True if knob k acted on nothing: it has two or more values, and every pair
 * of rows that differ only in k's value has the same particles, steps and
 * error (bit for bit; rows that stopped or have no finite error decide
 * nothing, and a knob with no deciding pair is not called inert). A study
 * that varies a key the scene's pipeline never reads (surface_tension on a
 * scene whose effects are density only) is told so rather than charting
 * identical points as if they were a finding. */
bool study_knob_inert(const study_plan *p, const study_row *rows, long n, int k);

/* Writes the CSV: combo, the knob keys, particles, steps, t_end, error,
 * ms_per_step, total_s, pareto, stopped, then the metric's extras. */
bool study_write_csv(FILE *f, const study_plan *p, study_metric m, const study_row *rows, int n);

#endif
