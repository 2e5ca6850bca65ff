/* sphlab lesson: the course in lessons/, one folder per lesson.
 *
 *   sphlab lesson --list              the lessons
 *   sphlab lesson N [VIEW OPTIONS]    opens lesson N in the window (runs this
 *                                     binary's `view` with the lesson's scene
 *                                     and overlays)
 *   sphlab lesson N --export DIR      writes the lesson's figures, DIR/report.md
 *                                     and DIR/report.fr.md, headless
 *
 * The export calls the library: simulations with sph_sim_* (lesson_run.c,
 * with the run command's own stats, dump and report functions), the bench
 * ladder through src/bench (bench_cmd.h), charts through src/plot (plot_run,
 * plot_chart), the kernel estimates and the studies through src/study
 * (study_estimate_write, study_cmd_run), and reads every number from their
 * structs or the CSV files it wrote, never from printed text. Three commands
 * still run as child processes of this binary: render and view (GL and SDL
 * contexts, and the software-rendering environment that makes frames
 * byte-identical, are set up per process), and hardcases, whose printed
 * verdict the report quotes verbatim (nothing is parsed from it).
 *
 * The report's text is a template per lesson and language in its folder
 * (report.md, report.fr.md) with {{placeholders}} (lesson_report.c).
 *
 * Files:
 *   cmd_lesson.c      the command, the table of lessons, the window, the report
 *   lesson_export.c   the export framework: paths, logs, child processes,
 *                     charts and CSV files
 *   lesson_run.c      simulations, checks and charts run in process
 *   lesson_report.c   the templates: values, blocks, filling, checks
 *   lesson_lab.c      the small experiments computed here with the core's
 *                     own functions (the seed's worked example of the hash,
 *                     the bitonic network step by step)
 *   lesson_steps.h    what each lesson exports: lesson_util.c (shared),
 *                     lesson_density.c (1, 2), lesson_forces.c (3, 4),
 *                     lesson_search.c (5, 6), lesson_perf.c (7 to 9), lesson_walls.c (10, 11) */
#ifndef SPH_LESSON_H
#define SPH_LESSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "plot.h"

typedef struct lx lx;

typedef struct lesson {
    int num;
    const char *slug;      /* folder lessons/NN-slug */
    const char *title;
    const char *level;     /* beginner, intermediate, advanced */
    const char *about;     /* one line for --list */
    const char *title_fr;  /* the same in French, for report.fr.md */
    const char *about_fr;
    const char *view_args; /* options for `sphlab view` with the lesson's scene */
    int (*export_fn)(lx *x);
} lesson;

extern const lesson sph_lessons[];
extern const int sph_lesson_count;

/* The result of one simulation run in process (lx_run_sim): what `sphlab run`
 * prints, read from the sim. */
enum { LX_RUN_MAX_PASSES = 24, LX_RUN_MAX_SETS = 32 }; /* sets: the ladder's longest level has 16 keys */
typedef struct lx_run {
    int npass;
    char pass[LX_RUN_MAX_PASSES][24];
    double ms_step[LX_RUN_MAX_PASSES]; /* [ms] per step, per pass */
    double share[LX_RUN_MAX_PASSES];   /* [%] of all passes' time */
    double total_ms_step;              /* [ms] per step, all passes */
    long steps;
    double t_sim;        /* [s] simulated */
    double wall_s;       /* [s] wall-clock time of the steps */
    double steps_per_s;  /* [1/s] */
    double ekin;         /* [J/m] in 2D, [J] in 3D, at the end */
    double rho_min, rho_mean, rho_max; /* [kg/m^dim] at the end */
    int threads;
    long particles;
} lx_run;

/* What to run: the options of `sphlab run` the lessons use. */
typedef struct lx_run_opts {
    const char *scene;
    const char *sets[LX_RUN_MAX_SETS]; /* section.key=value, in order; NULL ends them */
    long steps;                        /* < 0: the scene's duration, or its steps */
    int threads;                       /* 0: one per core */
    const char *stats, *dump;          /* CSV files as `sphlab run --stats/--dump` writes them, or NULL */
} lx_run_opts;

/* A value of the report's template: a number, a name, or a block of Markdown. */
enum { LX_MAX_VALUES = 160 };
typedef struct lx_value {
    char name[48];
    char *text;
    size_t len;
    bool used; /* the template being filled has used it */
} lx_value;

/* The state of one export. */
struct lx {
    const lesson *L;
    char dir[1024];    /* output directory */
    char folder[1024]; /* lessons/NN-slug */
    char exe[1024];    /* this binary */
    bool quick;        /* fewer steps and variants (tests, CI) */
    bool quiet;
    char *md;          /* what was written outside any block (failures): {{notes}} */
    size_t md_len;
    FILE *mdf;         /* where lx_md writes: the open block, or sink */
    FILE *sink;        /* into md */
    FILE *blk;         /* the open block's stream, or NULL */
    lx_value vals[LX_MAX_VALUES];
    int nval;
    char figs[96][512]; /* figures written: "file: what it shows" (both languages, {{@en|fr}}) */
    int nfig;
    char missing[8][256];
    int nmissing;
    int failed;        /* commands that failed */
    int lang;          /* the report being written: 0 English, 1 French (picks {{@en|fr}} in values) */
    char scratch[1100]; /* DIR/.work */
    int nlog;
    char srcs[16][1024]; /* lx_src's paths */
    int nsrc;
};

/* ---- export helpers (lesson_export.c) ------------------------------------- */

/* A path in the lesson's folder (stable during the export) / in the output
 * directory (rotating static buffers). */
const char *lx_src(lx *x, const char *file);
const char *lx_out(lx *x, const char *file);
/* The absolute path of an existing file or directory (rotating static buffers). */
const char *lx_abs(const char *path);
/* Splits a CSV line in place at its commas into at most cap fields; returns
 * how many. No quoting: the study quotes only values with commas or spaces,
 * and the bench and study CSVs read here have none. */
int lx_split_csv(char *line, char **f, int cap);
/* printf into a rotating static buffer (for numeric arguments). */
const char *lx_fmt(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Runs this binary with the arguments (NULL-terminated) as a child process,
 * stdout and stderr into DIR/logs/NN-LOG.txt. Only for the commands that must
 * run in a process of their own or whose printed table the report quotes as
 * is (render, view, hardcases; see the top of this file):
 * nothing may be parsed from the log. cwd: where to run it (NULL: here); env: one
 * NAME=VALUE to set, or NULL. Returns the exit status (a failure is counted,
 * named in the report and on stderr). The log's path goes to *log_path. */
int lx_sphlab(lx *x, const char *log, const char *cwd, const char *env, const char **log_path, ...);
#define LX_END ((const char *)NULL)
/* The same with the arguments in a NULL-terminated array. */
int lx_sphlab_v(lx *x, const char *log, const char *cwd, const char *env, const char **log_path,
                const char *const *args);
/* Whether this build has a command (its --help exits 0). */
bool lx_has_command(lx *x, const char *cmd);
/* Records a command or figure that this build cannot make. */
void lx_missing(lx *x, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Reads a whole file (NUL-terminated, caller frees); NULL if it cannot. */
char *lx_read_file(const char *path);
/* Writes a command line, quoted as a shell would need it. */
void lx_print_args(FILE *f, const char *const *argv);
/* The command line in the report's open code block, and the block's end. */
void lx_md_args(lx *x, const char *const *argv);
/* Opens DIR/logs/NN-LOG.txt for something done in process, headed by the
 * equivalent command line argv (said on stderr unless quiet); NULL if it cannot. */
FILE *lx_log_open(lx *x, const char *log, const char *const *argv, const char **log_path);

/* ---- simulations in process (lesson_run.c) ---------------------------------- */

/* Runs a scene as `sphlab run` would, with the core's functions; fills r (may
 * be NULL). False (a failure, named in the report) if it cannot. */
bool lx_run_sim(lx *x, const char *log, const lx_run_opts *o, lx_run *r);
/* The same, where a watchdog stop is a result the lesson reports, not a
 * failure: *stopped says whether it stopped the run (the files then hold the
 * steps up to it). */
bool lx_run_sim_stoppable(lx *x, const char *log, const lx_run_opts *o, lx_run *r, bool *stopped);
/* ms per step of a pass in a run, or -1. */
double lx_run_pass(const lx_run *r, const char *pass);
/* `sphlab plot ...` in process (plot_run): the chart's files in o->out, a log;
 * false (a failure, named in the report) if it cannot be drawn. */
bool lx_plot(lx *x, const char *log, const plot_opts *o);
/* The scene as `sphlab check` shows it, into the report; fills the pipeline's
 * pass names in order (at most cap) and returns their count (0 on failure). */
int lx_check(lx *x, const char *scene, char names[][24], int cap);

/* ---- the report (lesson_report.c) -------------------------------------------- */

/* Sets the template's value {{name}} (printf). */
void lx_val(lx *x, const char *name, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* What lx_md writes from now on is the value {{name}} (a block), until the
 * next lx_block or lx_block_end. */
void lx_block(lx *x, const char *name);
void lx_block_end(lx *x);
/* Fills the template at tmpl_path into out; false (with a message on stderr)
 * if a placeholder has no value. Marks the values it uses. */
bool lx_report_write(lx *x, const char *tmpl_path, FILE *out);
/* The report's Markdown (the subset the templates use) as an HTML page (lesson_html.c). */
void lx_html_write(const char *md, const char *title, const char *lang, FILE *out); /* lang: "en", "fr" */
/* Values the template just filled did not use (each named on stderr), then
 * clears the marks for the next template. */
int lx_values_unused(lx *x, const char *what);
void lx_values_reset_use(lx *x);
void lx_values_free(lx *x);

/* Appends to the report (Markdown). */
void lx_md(lx *x, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Appends a text / a file's text to the report as a code block (at most max_lines lines). */
void lx_md_text(lx *x, const char *text, int max_lines);
void lx_md_file(lx *x, const char *path, int max_lines);
/* Registers a figure (a file in DIR) for the report's list. */
void lx_fig(lx *x, const char *file, const char *what);

/* Moves DIR/.work/SUB/FRAME to DIR/NAME; false (and a failure) if it is missing. */
bool lx_take(lx *x, const char *sub, const char *frame, const char *name);
/* Draws a line chart or bar chart into DIR/BASE.png and .pdf. */
bool lx_chart(lx *x, plot_kind kind, const void *chart, const char *base, int w, int h, const char *what);
/* Opens DIR/NAME for a CSV (written to a temporary, renamed by lx_csv_close). */
FILE *lx_csv_open(lx *x, const char *name);
bool lx_csv_close(lx *x, FILE *f, const char *name, const char *what);

/* Reads a CSV (header line, numbers) into t; false (and a failure) if not. */
bool lx_table(lx *x, plot_table *t, const char *path);
/* Column of t by name (the export fails if it is missing). */
const double *lx_col(lx *x, const plot_table *t, const char *name);

/* ---- experiments computed in process (lesson_lab.c) ----------------------- */

/* One particle of the seed's worked example, as the hash pass computes it. */
typedef struct lx_hash_row {
    uint32_t id;
    float x, y;
    int32_t cx, cy;
    uint32_t hash, key;
} lx_hash_row;
/* Loads the scene, runs passes up to and including the hash, and returns the
 * entries in particle-id order (n at most cap); -1 with a message on error.
 * Also counts occupied cells and cells that share a key with another. */
int lx_hash_example(const char *scene, const char **sets, int nsets, lx_hash_row *rows, int cap, int *cells,
                    int *colliding_cells, uint32_t *table_size);

/* The bitonic network on n keys, step by step: calls step_cb after each
 * step with the array of keys (and original indices). Returns steps run. */
typedef void (*lx_bitonic_cb)(void *ctx, int stage, int step, uint32_t w, int flip, const uint32_t *keys,
                              const uint32_t *index, uint32_t n, int swaps);
int lx_bitonic_steps(const uint32_t *keys, uint32_t n, lx_bitonic_cb cb, void *ctx);

#endif
