/* sphlab bench: the seed's optimisation ladder, rebuilt live on this machine.
 *
 * Each level of the ladder is one line of bench_levels[] (bench_levels.c):
 * the scene keys that select it and the thread count. The benchmark scene is
 * a block of water falling in a box, made in code at any size (bench_scene).
 *
 *   bench_levels.c   the level table, the scene, making simulations
 *   bench_measure.c  timing (median steps/s, ms per pass) and the checks
 *                    (neighbour sets and state against a reference level)
 *   bench_machine.c  the machine's limits: streaming bandwidth, FMA throughput
 *   bench_chart.c    the charts (PLplot: log axes, stacked bars), PNG + PDF
 *   cmd_bench.c      the command line, machine, levels (bench_cmd.h: the
 *                    command's parts, shared with the lessons)
 *   bench_ladder.c   the ladder's measurements, bench_report.c its table,
 *                    CSV, JSON and chart; bench_scaling.c time against N */
#ifndef SPH_BENCH_H
#define SPH_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sph_levels.h"
#include "sph_sim.h"

/* ---- the ladder ------------------------------------------------------------ */

/* One level: what it adds, the scene overrides that select it, its threads.
 * The table lives in the core (src/core/sph_levels.h), where the window
 * reads it too; the bench's names stand for the core's. */
typedef sph_level bench_level;
#define bench_levels sph_levels
#define bench_level_count sph_level_count
enum { BENCH_MAX_LEVELS = 32 };
/* The ladder's search for the largest N stops at this size (marked "+" in the table). */
enum { BENCH_MAX_N_QUICK = 150000, BENCH_MAX_N = 4000000 };

/* Reference levels of the checks: brute force where it is affordable, the
 * seed's final design (hash + bitonic sort + offsets) at larger N. */
#define BENCH_REF_SMALL "L0"
#define BENCH_REF_LARGE "L2"
/* Index of the level named `name` in bench_levels[], or -1. */
static inline int bench_level_find(const char *name) { return sph_level_find(name); }
int bench_levels_cores(void); /* what threads = 0 means */
/* The level runs on the GL backend ([compute] backend = gl): measured only
 * where an OpenGL 4.3 context can be made, and named by its device. */
static inline bool bench_level_gl(const bench_level *L) { return sph_level_gl(L); }

/* Overrides from the command line (--set [LEVEL:]section.key=value). */
enum { BENCH_MAX_SETS = 32 };
typedef struct bench_config {
    int dim;
    bool watchdog;        /* keep the watchdog on while timing (off by default) */
    int n_sets;
    const char *set_level[BENCH_MAX_SETS]; /* NULL: every level */
    const char *set[BENCH_MAX_SETS];
} bench_config;

/* ---- the scene ------------------------------------------------------------- */

/* A block of n_x x n_y (x n_z) particles on a lattice of spacing s falling in a
 * box twice its size; h = 2 s (about 33 neighbours in 3D, 12 in 2D). Sizes
 * are numbered by k: in 3D n = k / 3 and k % 3 of the horizontal sides are
 * n + 1, so the count n^3, n^2 (n+1), n (n+1)^2, (n+1)^3 grows by steps of
 * about 1/n (2D likewise with k / 2). */
#define BENCH_SPACING 0.02
#define BENCH_JITTER 0.1       /* spacings: the timed block is off its lattice, as a fluid that has flowed */
#define BENCH_CHECK_JITTER 0.1 /* spacings: the checks move particles off it, so that no pair sits at r = h */
#define BENCH_CHECK_STEPS 10
#define BENCH_GL_WARM_MS 300.0 /* [ms] a GL level steps this long before it is timed (the GPU's clock rises) */
#define BENCH_GL_WARM_STEPS 200 /* ... or this many steps, whichever comes first */

int bench_k_min(int dim);
void bench_sides(int dim, int k, int side[3]);
double bench_count(int dim, int k);
int bench_k_at_least(int dim, double n); /* smallest k whose count is >= n */
int bench_k_near(int dim, double n);     /* k whose count is closest to n (ties: the smaller) */
/* The scene's INI text, particles moved off the lattice by up to `jitter` spacings. */
void bench_scene_ini(int dim, int k, double jitter, char *out, size_t cap);
/* The scene of size k for a level (L NULL: none), the level's and the
 * command line's overrides applied; `check`: the checks' variant (jittered).
 * False with a message in why. */
bool bench_scene_def(const bench_config *cfg, const bench_level *L, int k, bool check, sph_scene_def *def, char *why,
                     size_t n);
bool bench_make_sim(const bench_config *cfg, const bench_level *L, int k, bool check, sph_sim **out, char *why,
                    size_t n);

/* ---- timing ---------------------------------------------------------------- */

typedef struct bench_plan {
    int repeats;       /* repeats of `steps` steps; the median is kept */
    int steps;         /* steps per repeat */
    double budget_ms;  /* stop repeating once this much was spent (at least one repeat) */
    double decide_fps; /* > 0: stop after one repeat if clearly above (x1.5) or below (/3) it */
    bool pass_times;   /* true per-pass times: a GL level with timer queries has them at no cost; without
                          them it waits for each pass (glFinish), which costs it a little; false: then
                          passes are only queued, steps/s is the device's */
} bench_plan;

typedef struct bench_meas {
    uint32_t n;
    int threads;
    int repeats;                    /* done */
    double steps_per_s;             /* median over repeats */
    double ms_step;                 /* median over steps of sph_sim_step's wall time */
    double pass_ms[SPH_PASS_COUNT]; /* median over steps of each pass's time; NAN if not in the pipeline */
    double pairs;                   /* neighbour-list entries (i->j and j->i) of the last step */
    double create_ms;               /* making the simulation (not timed in steps/s) */
    double others;                  /* cores other processes kept busy meanwhile (NAN if unknown) */
    int attempts;                   /* measurements made (bench_measure_retry) */
    const char *timing;             /* a backend's way of timing passes (sph_backend.timing); NULL on the CPU */
    double peak_rss;                /* [B] the process's peak resident size so far (getrusage ru_maxrss),
                                       taken after the timed steps: at a large N, this level's own */
    double candidates;              /* distance tests of one build of the lists (bench_flops.c); NAN if unknown */
    bool fused;                     /* pressure force and viscosity in one walk (their flops in the first) */
    float skin;                     /* [1] Verlet skin in h: > 0, the lists are not built every step */
} bench_meas;

/* Makes the simulation of size k, runs one warm-up step, then times
 * repeats of steps (only sph_sim_step, with sph_now_ms). */
bool bench_measure(const bench_config *cfg, const bench_level *L, int k, const bench_plan *plan, bench_meas *out,
                   char *why, size_t n);

/* Measures again, up to `attempts` times in all (at most 8), while other
 * processes kept more than BENCH_BUSY cores busy during the measurement or
 * (fps > 0) while the rate is within 10% of fps on either side, and keeps
 * the median by steps/s of the quiet attempts (the lower one of an even
 * count). Symmetric: a size near the limit is neither favoured nor
 * penalised by the retries. */
#define BENCH_BUSY 0.25
bool bench_measure_retry(const bench_config *cfg, const bench_level *L, int k, const bench_plan *plan, double fps,
                         int attempts, bench_meas *out, char *why, size_t n);

/* ---- counted operations (bench_flops.c) ----------------------------------- */

/* Flops per neighbour-list entry of a pair pass (0 for the others), per
 * distance test of the search; the counts and how they were made are in
 * bench_flops.c. */
double bench_flops_per_entry(int pass, bool fused);
double bench_flops_per_candidate(void);
/* Fills m's candidates, fused and skin from a simulation after its steps. */
void bench_flops_of(const sph_sim *sim, bench_meas *m);
/* Counted flops of each pass in one step (NAN: not counted): list entries x
 * flops per entry for the pair passes, candidates x flops per test for the
 * neighbours pass (not with Verlet lists: not built every step). */
void bench_pass_flops(const bench_meas *m, double flops[SPH_PASS_COUNT]);

/* ---- checks ---------------------------------------------------------------- */

/* Tolerances of the state after BENCH_CHECK_STEPS steps, particles matched by id. */
#define BENCH_TOL_X 1e-4    /* [m] position */
#define BENCH_TOL_V 1e-3    /* [m/s] velocity */
#define BENCH_TOL_RHO 1e-3  /* [1] relative density (one missing neighbour moves it by about 3%) */

/* A neighbour-set difference at a pair this close to the support's edge,
 * |r - h| <= BENCH_EDGE h, is float rounding's call (a fused multiply-add, a
 * sum in another order), not a wrong answer: it is counted apart. */
#define BENCH_EDGE 1e-5
/* ...but only a few: about 2e-3 ordered pairs per particle lie in that band
 * in 3D and a rounding decides a small share of them, so more than
 * max(BENCH_EDGE_MAX, BENCH_EDGE_SHARE x pairs) is a failure. */
#define BENCH_EDGE_MAX 8
#define BENCH_EDGE_SHARE 1e-5

/* What a run leaves to compare, indexed by particle id. */
typedef struct bench_state {
    uint32_t n;
    int dim;
    float h;
    uint32_t *nbr_start, *nbr; /* neighbour sets after the first step, as sorted ids */
    float *pred1[3];           /* predicted positions of the first step, where the sets were found */
    float *pos[3], *vel[3], *rho;
    double moved;              /* [m] largest displacement over the run (the scale of the check) */
    bool stopped;              /* the watchdog stopped it */
    char report[512];
} bench_state;

bool bench_state_run(const bench_config *cfg, const bench_level *L, int k, bench_state *out, char *why, size_t n);
void bench_state_free(bench_state *s);

typedef struct bench_diff {
    bool done, pass;
    int ref;                /* level index of the reference */
    uint32_t n;
    uint32_t sets_differ;   /* particles whose neighbour set differs (beyond the edge pairs) */
    uint32_t edge_pairs;    /* pairs in one set and not the other, at the support's edge */
    double pairs, ref_pairs;
    double dx, dv, drho;    /* largest differences (drho relative) */
    char why[160];          /* the first failure in words */
} bench_diff;

void bench_compare(const bench_state *ref, const bench_state *s, bench_diff *d);

/* ---- the machine ----------------------------------------------------------- */

typedef struct bench_machine {
    int cores;
    double mhz_cpuinfo;       /* "cpu MHz" of /proc/cpuinfo (0 if unknown) */
    double clock_ghz;         /* measured: a chain of dependent integer multiplications, 3 cycles each */
    int lanes;                /* floats per vector register the build uses (16 with AVX-512) */
    double fma_gflops[2];     /* measured: independent FMA chains, 1 thread and all cores */
    double peak_gflops_core;  /* clock x lanes x 2 (FMA) x FMA pipes (from the measurement, rounded), and at least
                               * the FMA throughput measured on one core */
    int fma_pipes;
    bool clock_low;           /* the clock read below what the FMA throughput needs (a busy host during its
                               * reading): the peak is then the measured throughput */
    double triad_gbs[2];      /* a[i] = b[i] + s c[i], 3 x 4 bytes per element, 1 thread and all cores */
    double read_gbs[2];       /* sum of a[i], 4 bytes per element */
    double array_mb;          /* size of each array */
} bench_machine;

void bench_machine_measure(bench_machine *m, bool quick);
/* The FMA pipes and the float peak from clock_ghz (or mhz_cpuinfo), lanes and fma_gflops[0]: the peak is at least
 * the throughput measured (clock_low then). */
static inline void bench_machine_peak(bench_machine *m)
{
    double ghz = m->clock_ghz > 0 ? m->clock_ghz : m->mhz_cpuinfo / 1e3;
    double per_pipe = ghz * m->lanes * 2;
    /* FMA pipes: what the measured throughput says, rounded to a power of two (1 or 2 on x86-64 cores) */
    double pipes = per_pipe > 0 ? m->fma_gflops[0] / per_pipe : 1;
    m->fma_pipes = pipes > 1.4 ? 2 : 1;
    m->peak_gflops_core = per_pipe * m->fma_pipes;
    /* a peak below the throughput measured is no peak: the clock's reading was low (a review's quick run read
     * 2.23 GHz where the same run's start read 3.68, and a peak of 142.5 GFLOP/s under 223.3 measured) */
    m->clock_low = m->fma_gflops[0] > m->peak_gflops_core;
    if (m->clock_low) m->peak_gflops_core = m->fma_gflops[0];
}
/* The clock one core gets now [GHz], in about 20 ms (0 if unknown): below
 * the machine's usual figure when the host is busy, which the other-process
 * count cannot see (another virtual machine on the same cores). */
double bench_clock_probe(void);
void bench_machine_print(FILE *f, const bench_machine *m);
/* The figures as a cJSON object (the caller deletes it), NULL if out of memory. */
struct cJSON *bench_machine_to_json(const bench_machine *m);

/* ---- charts ---------------------------------------------------------------- */

enum { BENCH_CHART_PASSES = SPH_PASS_COUNT };

typedef struct bench_ladder_chart {
    char title[160], subtitle[200];
    int nl;
    char level[BENCH_MAX_LEVELS][56];     /* bar labels */
    double max_n[BENCH_MAX_LEVELS];       /* 0: none */
    char note[BENCH_MAX_LEVELS][48];      /* written at the end of the max-N bar */
    int np;                               /* passes in the stacked bars */
    char pass[BENCH_CHART_PASSES][24];
    double ms[BENCH_MAX_LEVELS][BENCH_CHART_PASSES]; /* NAN or 0: not run */
    char bars_title[120], stack_title[120];
    double target_n;                      /* a dashed line at this N (0: none) */
    char target_label[64];
} bench_ladder_chart;

typedef struct bench_scaling_series {
    char label[64];
    const double *n, *ms;
    size_t count;
} bench_scaling_series;

typedef struct bench_scaling_chart {
    char title[160], subtitle[200];
    int ns;
    bench_scaling_series s[BENCH_MAX_LEVELS];
    double fps; /* a dashed line at ms = 1000 / fps; 0: none */
} bench_scaling_chart;

/* Each writes DIR/BASE.png and DIR/BASE.pdf, staged through the plot
 * module's output files (renamed on plot_out_commit). */
bool bench_chart_ladder(const bench_ladder_chart *c, const char *dir, const char *base);
bool bench_chart_scaling(const bench_scaling_chart *c, const char *dir, const char *base);

/* ---- small helpers ---------------------------------------------------------- */

double bench_median(double *v, int n); /* sorts v; NAN if n == 0 */
/* CPU time on the machine and in this process, to tell how much of the
 * machine other processes took while we measured (the load average lags a
 * minute behind and counts us too). */
typedef struct bench_cpu {
    double busy_s; /* all cores' non-idle time, from /proc/stat (negative if unknown) */
    double self_s; /* this process's user + system time, all threads */
    double wall_ms;
} bench_cpu;
void bench_cpu_now(bench_cpu *c);
/* Cores that other processes kept busy on average between a and b (NAN if unknown). */
double bench_cpu_others(const bench_cpu *a, const bench_cpu *b);
void bench_loadavg(double out[3]);     /* /proc/loadavg, or -1s */
void bench_now_iso(char *out, size_t cap); /* local date and time, ISO 8601 */
void bench_fmt_count(char *out, size_t cap, double v); /* 12345 -> "12,345" */

#endif
