/* The pieces every problem of `sphlab validate` is built from (validate_run.c). */
#ifndef SPH_VALIDATE_RUN_H
#define SPH_VALIDATE_RUN_H

#include "plot.h"
#include "sph_sim.h"
#include "validate.h"

/* Loads scenes/validate/FILE with every block's spacing set to `spacing` [m]
 * and h scaled with it (the scene's h / spacing kept); message and false on
 * failure. */
bool val_scene(const char *file, double spacing, sph_scene_def *def);
/* The same without the scene's checks, for a problem that sizes the domain
 * to the spacing before it checks the scene itself (the channels). */
bool val_scene_unchecked(const char *file, double spacing, sph_scene_def *def);

/* Called at t = 0 and after every step. */
typedef void (*val_observe_fn)(void *ctx, const sph_sim *sim);
/* Runs the scene until t_end [s] with a progress line on stderr (label);
 * false with a message if it cannot be made or the watchdog stops it. */
bool val_run(const val_ctx *c, const char *label, const sph_scene_def *def, double t_end, val_observe_fn fn, void *ctx);

/* The error measure of the problem's run number `run` (0: the first val_run
 * since the last verdict), written beside its cost in NAME-cost.csv. */
void val_cost_error(int run, double error);

/* For a problem that steps its own sim (validate drop): the clock started
 * before the sim was made, and the cost of that sim's run recorded when it
 * ends, as val_run records its own. */
typedef struct val_clock {
    double ms, cpu_s; /* [ms] sph_now_ms, [s] process CPU time */
} val_clock;
val_clock val_clock_start(void);
void val_cost_add(const char *label, const sph_sim *sim, val_clock since);

/* Number of fluid particles (wall particles left out). */
double val_fluid_count(const sph_sim *sim);

/* Staged outputs in c->out, renamed only by val_verdict. */
FILE *val_csv(const val_ctx *c, const char *file);
bool val_csv_close(const val_ctx *c, FILE *f, const char *file);
bool val_chart(const val_ctx *c, const char *base, const plot_lines *chart);

/* Commits the outputs (with NAME-cost.csv: each run's particles, steps, CPU
 * and wall seconds, ms per simulated second and error) and prints
 * "validate NAME: PASS|FAIL: text" on stdout, then a line with each run's
 * cost; returns VAL_PASS or VAL_FAIL, or VAL_ERROR (outputs dropped) if
 * !outputs_ok or the commit fails. */
int val_verdict(const val_ctx *c, const val_problem *p, bool outputs_ok, bool pass, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* printf at the end of buf. */
void val_append(char *buf, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* A series of (x, y) samples that grows. */
typedef struct val_series {
    double *x, *y;
    size_t n, cap;
} val_series;
bool val_series_add(val_series *s, double x, double y);
void val_series_free(val_series *s);
/* Linear interpolation at x (x increasing); NaN outside. */
double val_series_at(const val_series *s, double x);

/* The problems (one file each). */
int val_run_dam_break(const val_ctx *c, const val_problem *p);
int val_run_hydrostatic(const val_ctx *c, const val_problem *p);
int val_run_taylor_green(const val_ctx *c, const val_problem *p);
int val_run_poiseuille(const val_ctx *c, const val_problem *p);
int val_run_couette(const val_ctx *c, const val_problem *p);
int val_run_obstacle(const val_ctx *c, const val_problem *p);
int val_run_drop(const val_ctx *c, const val_problem *p);
int val_run_drop_3d(const val_ctx *c, const val_problem *p);

#endif
