/* The `sphlab bench` command's own parts, shared by its files:
 *   cmd_bench.c      the command line, progress lines, `machine` and `levels`
 *   bench_ladder.c   the ladder's measurements (largest N at F steps/s, ms per
 *                    pass at a fixed N, checks against the references)
 *   bench_report.c   the ladder's table, CSV, JSON and chart
 *   bench_scaling.c  time per step against N, its table, CSV and chart
 * The lesson exporter (src/lesson) calls these too, so that it reads the
 * ladder from a struct, not from the printed table. */
#ifndef SPH_BENCH_CMD_H
#define SPH_BENCH_CMD_H

#include <stdbool.h>
#include <stdio.h>

#include "bench.h"


typedef struct bench_opts {
    const char *what, *out, *levels;
    const char *solvers; /* solvers: --solvers, the rows to run besides eos; NULL: all */
    double fps, at;
    double time;  /* [s] solvers: --time, the simulated window; < 0 if not given */
    int repeats;  /* solvers: --repeats, interleaved rounds; < 0 if not given */
    int threads;  /* pair: --threads; < 0 if not given (then 1) */
    bool quick, quiet, at_given, trace;
    bench_config cfg;
    int sel[BENCH_MAX_LEVELS], nsel;
    bool progress;
} bench_opts;

/* The options the command line starts from (3D, 60 steps/s, every level,
 * DIR ., the fixed N of --quick or not), without a command line. */
void bench_opts_init(bench_opts *o, bool quick);

/* Progress line on stderr (only on a terminal, not with --quiet), and one line
 * per measurement with --trace; they follow the options of the running command. */
void bench_progress_opts(const bench_opts *o);
void bench_progress(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void bench_progress_done(void);
void bench_trace(const bench_level *L, const bench_meas *m, const char *what);

const char *bench_dim_tag(int dim); /* "2d" or "3d" */
/* V as "%.Nf" prints it with N = DECIMALS, for a number cJSON then prints short (NaN stays NaN). */
double bench_round_fixed(double v, int decimals);
/* OBJ's KEY: a load average (1, 5, 15 minutes) as 3 numbers with 2 decimals; false if out of memory. */
bool bench_json_add_load(struct cJSON *obj, const char *key, const double l[3]);
void bench_csv_num(FILE *f, double v, const char *fmt); /* ",v", or "," if v is not finite */

/* The level table (`sphlab bench levels`) of the selected levels. */
void bench_levels_print(FILE *f, const bench_opts *o);

typedef struct level_result {
    bool searched;
    double max_n, rate_at_max; /* 0 if even the smallest size is too slow */
    bool capped;               /* the largest size tried still ran fast enough */
    int measurements;
    bench_meas at;             /* at the fixed N */
    bool at_ok;
    double search_ms, force_ms, search_rate, force_rate; /* rates: pairs per second per core */
    double flops[SPH_PASS_COUNT];  /* counted flops of each pass in one step (bench_pass_flops), NAN: none */
    double search_gflops, force_gflops; /* [GFLOP/s] counted flops over the search's / pair passes' time */
    double peak_gflops;        /* [GFLOP/s] the machine's measured FMA throughput on this level's threads */
    bench_diff small, large;   /* checks */
    bool check_ok;
    double others;             /* cores other processes kept busy while this level was measured */
    bool skipped;              /* a GL level where no OpenGL 4.3 context can be made */
    char error[512];           /* or why it was skipped */
} level_result;


typedef struct ladder_meta {
    char date[64];
    double load0[3], load1[3];
    double n_at, n_check, seconds;
    double others; /* cores other processes kept busy during the run, on average */
    double ghz0, ghz1; /* clock probe at the start and the end */
    int best;       /* index into res of the CPU level with the largest max N, -1 if none */
    bool target_evaluated, target_met;
    int gl_best;    /* likewise among the GL levels */
    bool gl_ran, gl_is_gpu, gl_target_met; /* a GL level ran; on a GPU (not llvmpipe); 1,000,000 reached */
    bool gl_target_evaluated;              /* 3D, 60 steps/s, a GL level on a GPU */
    char gl_device[256]; /* the GL levels' device, or why none could be made */
    const char *gl_timing; /* how the GL levels' pass times were measured (sph_backend.timing), or NULL */
    bool all_pass;
    bench_machine machine; /* its quick measurement at the start: the peak the GFLOP/s are set against */
} ladder_meta;

/* One run of the ladder: a result per selected level, in o->sel's order. */
typedef struct bench_ladder {
    level_result *res;
    ladder_meta meta;
    bool pass_used[SPH_PASS_COUNT]; /* some level timed the pass at the fixed N */
    int gl_state;                   /* 0: no GL level, 1: a GL 4.3 context was made, -1: none could be */
    int k_at, k_check;              /* block sizes of the per-pass table and of the checks */
    bool all_pass;                  /* every level passed its checks and was measured */
} bench_ladder;

/* Measures every selected level (bench_ladder.c); 0 on success, else the
 * exit status (the message said). Free with bench_ladder_free. */
int bench_ladder_measure(const bench_opts *o, bench_ladder *lad);
void bench_ladder_free(bench_ladder *lad);
/* The ladder's table (bench_report.c). */
void bench_ladder_print(FILE *out, const bench_opts *o, const bench_ladder *lad);
/* DIR/ladder-Nd.{csv,json,png,pdf}; argv: the command line the JSON names. */
bool bench_ladder_write(const bench_opts *o, const bench_ladder *lad, int argc, char **argv);
const char *bench_check_word(const level_result *r); /* PASS, FAIL, SKIP or - */
/* Counted flops and GFLOP/s of a measured level against the machine's peak (bench_ladder.c). */
void bench_level_flops(level_result *r, const bench_machine *m);

/* `sphlab bench scaling` (bench_scaling.c). */
int bench_cmd_scaling(bench_opts *o);
/* `sphlab bench solvers` (bench_solvers.c). */
int bench_cmd_solvers(bench_opts *o);
/* bench_pair.c: two CPU levels stepped in turn on one thread (--levels A,B). */
int bench_cmd_pair(bench_opts *o);

#endif
