/* sphlab bench WHAT: the seed's optimisation ladder on this machine.
 *   ladder    per level: the largest N at F steps/s (bisection over block
 *             sizes), ms per pass at a fixed N, checks against a reference
 *   scaling   time per step against N for each level (log-log)
 *   solvers   eos, pcisph and dfsph at equal density error (bench_solvers.c)
 *   pair      two levels stepped in turn on one thread (bench_pair.c)
 *   machine   the machine's limits (memory bandwidth, float peak)
 *   levels    the level table and the scene keys of each level */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "bench_cmd.h"
#include "plot.h"
#include "gpu.h"
#include "../io/io.h"
#include "../io/io_json.h"

static const app_cmd_spec spec = {
    .name = "bench",
    .cmd = APP_CMD(bench),
    .synopsis = "usage: sphlab bench WHAT [options]\n"
                "  ladder      for each level of the ladder: the largest N that runs at F steps/s or more\n"
                "              (bisection over block sizes, median of repeats), ms per pass at a fixed N,\n"
                "              counted GFLOP/s against the machine's measured float peak (its quick form),\n"
                "              and a check against the reference level; table, CSV, JSON, chart\n"
                "  scaling     time per step against N for each level (log-log): O(N^2) against O(N)\n"
                "  solvers     3D dam break (--at N, default 50,000): eos at the stiffness that holds a 0.1 %\n"
                "              density error over --time T (the stiffness by bisection on log k), pcisph and\n"
                "              dfsph at tolerance 0.1 %, --repeats R interleaved rounds: error, steps, iterations,\n"
                "              ms per simulated second (medians), the ratios (median, least, largest);\n"
                "              pcisph+ and dfsph+: the same with [physics] solver_warm_start = on\n"
                "              (pcisph+ also pcisph_local_delta = on); pcisph* and dfsph*: the + rows with\n"
                "              solver_chebyshev = 0.9\n"
                "  pair        two CPU levels (--levels A,B) from the same start at --at N, stepped in turn on\n"
                "              one thread for --repeats R rounds (default 15): each step's thread CPU time,\n"
                "              medians and their ratio, mean ms per pass, how far the states end apart;\n"
                "              --threads T: on T threads, wall times\n"
                "  machine     the machine's limits: memory bandwidth (streaming loops), float peak (FMA loop)\n"
                "  levels      the levels and the scene keys that make each\n"
                "options:\n",
    .footer = "Files: DIR/ladder-3d.{csv,json,png,pdf}, DIR/scaling-3d.{csv,png,pdf}, DIR/machine.json (2d likewise).\n"
              "Exit status: 0 done; 1 a level failed its check, or an output could not be written; 2 bad command line\n"
              "(an option the benchmark does not read, a --set a level cannot take, too).\n",
    .max_pos = 1,
};

static bool parse_levels(bench_opts *o)
{
    o->nsel = 0;
    if (!o->levels) {
        for (int i = 0; i < bench_level_count && i < BENCH_MAX_LEVELS; i++) o->sel[o->nsel++] = i;
        return true;
    }
    /* an empty item ("L3,,L6", "L3,"): a typo, said (strtok dropped it unsaid) */
    const size_t len = strlen(o->levels);
    if (len && (o->levels[0] == ',' || o->levels[len - 1] == ',' || strstr(o->levels, ",,"))) {
        fprintf(stderr, "sphlab bench: --levels '%s': an empty item between commas\n", o->levels);
        return false;
    }
    char buf[512];
    snprintf(buf, sizeof buf, "%s", o->levels);
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int i = bench_level_find(t);
        if (i < 0) {
            fprintf(stderr, "sphlab bench: --levels: no level '%s' (`sphlab bench levels` lists them)\n", t);
            return false;
        }
        for (int j = 0; j < o->nsel; j++)
            if (o->sel[j] == i) {
                fprintf(stderr, "sphlab bench: --levels: '%s' given twice\n", t);
                return false;
            }
        if (o->nsel == BENCH_MAX_LEVELS) return false;
        o->sel[o->nsel++] = i;
    }
    if (o->nsel == 0) {
        fprintf(stderr, "sphlab bench: --levels: no level given\n");
        return false;
    }
    /* in ladder order, whatever order they were named in */
    for (int a = 1; a < o->nsel; a++)
        for (int b = a; b > 0 && o->sel[b] < o->sel[b - 1]; b--) {
            int t = o->sel[b];
            o->sel[b] = o->sel[b - 1];
            o->sel[b - 1] = t;
        }
    return true;
}

/* --set [LEVEL:]section.key=value: the level must exist and the assignment must apply. */
static bool add_set(bench_opts *o, const char *v)
{
    if (o->cfg.n_sets == BENCH_MAX_SETS) {
        fprintf(stderr, "sphlab bench: more than %d --set options\n", BENCH_MAX_SETS);
        return false;
    }
    const char *colon = strchr(v, ':'), *eq = strchr(v, '=');
    static char levels[BENCH_MAX_SETS][48];
    const char *level = NULL, *assign = v;
    if (colon && (!eq || colon < eq)) {
        size_t len = (size_t)(colon - v);
        if (len == 0 || len >= sizeof levels[0]) {
            fprintf(stderr, "sphlab bench: --set '%s': want [LEVEL:]section.key=value\n", v);
            return false;
        }
        memcpy(levels[o->cfg.n_sets], v, len);
        levels[o->cfg.n_sets][len] = '\0';
        level = levels[o->cfg.n_sets];
        assign = colon + 1;
        if (bench_level_find(level) < 0) {
            fprintf(stderr, "sphlab bench: --set '%s': no level '%s' (`sphlab bench levels` lists them)\n", v, level);
            return false;
        }
    }
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    if (sph_scene_set(&def, assign, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab bench: %s\n", err.msg); /* the message names --set itself */
        return false;
    }
    o->cfg.set_level[o->cfg.n_sets] = level;
    o->cfg.set[o->cfg.n_sets++] = assign;
    return true;
}

/* Which options each benchmark reads: one given to a benchmark that does not read it is a bad command line,
 * not ignored (a review found --out, --set, --fps, --levels, --solvers, --time and --quiet accepted and
 * silently unused by some of them). */
static bool options_read_by(const char *what, const app_opts *opt)
{
    static const struct {
        const char *what, *reads; /* the options it reads, by name, space-separated */
    } table[] = {
        {"ladder", "--set --dim --fps --at --out --levels --quick --quiet --trace --watchdog"},
        {"scaling", "--set --dim --fps --at --out --levels --quick --quiet --trace --watchdog"},
        {"solvers", "--dim --at --time --repeats --solvers --quick --quiet --trace --watchdog"},
        {"pair", "--set --dim --at --repeats --threads --levels --quick --quiet --watchdog"},
        {"machine", "--out --quick --quiet"},
        {"levels", "--dim --levels"},
    };
    const struct {
        const char *name;
        bool given;
    } given[] = {
        {"--set", opt->sets.n > 0},      {"--dim", opt->dim >= 0},          {"--fps", opt->fps >= 0},
        {"--at", opt->at >= 0},          {"--out", opt->out != NULL},       {"--levels", opt->levels != NULL},
        {"--time", opt->time >= 0},      {"--repeats", opt->repeats >= 0},  {"--solvers", opt->solvers != NULL},
        {"--threads", opt->threads > 0}, {"--quick", opt->quick},           {"--quiet", opt->quiet},
        {"--trace", opt->trace},         {"--watchdog", opt->watchdog},
    };
    for (size_t t = 0; t < sizeof table / sizeof table[0]; t++) {
        if (strcmp(table[t].what, what) != 0) continue;
        for (size_t g = 0; g < sizeof given / sizeof given[0]; g++) {
            if (!given[g].given) continue;
            const char *at = strstr(table[t].reads, given[g].name);
            const size_t len = strlen(given[g].name);
            if (at && (at[len] == ' ' || at[len] == '\0')) continue;
            fprintf(stderr, "sphlab bench %s: %s is not read by bench %s (it reads %s)\n", what, given[g].name, what,
                    table[t].reads);
            return false;
        }
    }
    return true; /* an unknown benchmark is said below */
}

static int parse_args(int argc, char **argv, bench_opts *o)
{
    app_opts opt;
    app_opts_init(&opt); /* -1 or NULL: not given (the defaults follow, once what was given is known) */
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    if (opt.n_pos && !options_read_by(opt.pos[0], &opt)) return 2;
    if (opt.fps < 0) opt.fps = 60;
    if (opt.dim < 0) opt.dim = 3;
    o->what = opt.n_pos ? opt.pos[0] : NULL;
    o->fps = opt.fps;
    o->cfg.dim = (int)opt.dim;
    o->at_given = opt.at >= 0;
    o->at = (double)opt.at;
    o->time = opt.time;
    o->repeats = (int)opt.repeats;
    o->out = opt.out;
    o->levels = opt.levels;
    o->solvers = opt.solvers;
    o->quick = opt.quick;
    o->quiet = opt.quiet;
    o->trace = opt.trace;
    o->threads = (int)opt.threads;
    o->cfg.watchdog = opt.watchdog;
    for (int i = 0; i < opt.sets.n; i++)
        if (!add_set(o, opt.sets.v[i])) return 2;
    if (!o->what) {
        app_opts_usage_error(&spec, "name a benchmark");
        return 2;
    }
    if (o->threads > 0 && strcmp(o->what, "pair") != 0) {
        app_opts_usage_error(&spec, "--threads is for bench pair only (the ladder's levels name their threads)");
        return 2;
    }
    if (!parse_levels(o)) return 2;
    if (!o->out) o->out = ".";
    if (!o->at_given) o->at = o->quick ? 6000 : 20000;
    o->progress = !o->quiet && isatty(STDERR_FILENO);
    return -1;
}

/* ---- ladder ------------------------------------------------------------------------ */

static int cmd_ladder(bench_opts *o, int argc, char **argv)
{
    bench_ladder lad;
    int rc = bench_ladder_measure(o, &lad);
    if (rc) {
        bench_ladder_free(&lad);
        return rc;
    }
    if (!o->quiet) bench_ladder_print(stdout, o, &lad);
    bool ok = bench_ladder_write(o, &lad, argc, argv);
    bool all_pass = lad.all_pass;
    bench_ladder_free(&lad);
    return !ok || !all_pass ? 1 : 0;
}

/* ---- machine, levels ------------------------------------------------------------------ */

static int cmd_machine(bench_opts *o)
{
    char date[64];
    double load0[3], load1[3];
    bench_now_iso(date, sizeof date);
    bench_loadavg(load0);
    bench_progress("measuring the clock, FMA throughput and memory bandwidth ...");
    bench_machine m;
    bench_machine_measure(&m, o->quick);
    bench_progress_done();
    bench_loadavg(load1);
    if (!o->quiet) {
        printf("sphlab bench machine: %s, load %.2f at the start, %.2f at the end\n\n", date, load0[0], load1[0]);
        bench_machine_print(stdout, &m);
        printf("\n");
    }
    char err[1200];
    if (!sph_output_dir(o->out, err, sizeof err)) {
        fprintf(stderr, "sphlab bench: --out: %s\n", err);
        return 1;
    }
    cJSON *root = cJSON_CreateObject();
    bool ok = root && cJSON_AddStringToObject(root, "date", date) && bench_json_add_load(root, "load_start", load0) &&
              bench_json_add_load(root, "load_end", load1);
    cJSON *mj = ok ? bench_machine_to_json(&m) : NULL;
    if (mj && !cJSON_AddItemToObject(root, "machine", mj)) {
        cJSON_Delete(mj);
        mj = NULL;
    }
    ok = ok && mj;
    char path[1100];
    int len = snprintf(path, sizeof path, "%s/machine.json", o->out);
    if (len < 0 || (size_t)len >= sizeof path) {
        snprintf(err, sizeof err, "%s/machine.json: path too long", o->out);
        ok = false;
    } else if (!ok) {
        snprintf(err, sizeof err, "%s: out of memory", path);
    } else {
        ok = sph_json_save(path, root, err, sizeof err);
        if (ok && !o->quiet) printf("wrote %s\n", path);
    }
    if (!ok) fprintf(stderr, "sphlab bench: %s\n", err);
    cJSON_Delete(root);
    return ok ? 0 : 1;
}

static int cmd_levels(const bench_opts *o)
{
    bench_levels_print(stdout, o);
    char ini[2048];
    bench_scene_ini(o->cfg.dim, bench_k_near(o->cfg.dim, 1000), BENCH_JITTER, ini, sizeof ini);
    printf("\nThe scene (here N = %.0f; the benchmark changes the block's size and the box with it; the checks\n"
           "run it with jitter = %g, so that no pair sits exactly at r = h):\n\n%s",
           bench_count(o->cfg.dim, bench_k_near(o->cfg.dim, 1000)), BENCH_CHECK_JITTER, ini);
    return 0;
}

int cmd_bench(int argc, char **argv)
{
    plot_out_command("bench"); /* the charts' messages name this command */
    static bench_opts o;
    memset(&o, 0, sizeof o);
    bench_progress_opts(&o);
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) return rc;
    if (strcmp(o.what, "ladder") == 0) return cmd_ladder(&o, argc, argv);
    if (strcmp(o.what, "scaling") == 0) return bench_cmd_scaling(&o);
    if (strcmp(o.what, "solvers") == 0) return bench_cmd_solvers(&o);
    if (strcmp(o.what, "pair") == 0) return bench_cmd_pair(&o);
    if (strcmp(o.what, "machine") == 0) return cmd_machine(&o);
    if (strcmp(o.what, "levels") == 0) return cmd_levels(&o);
    fprintf(stderr, "sphlab bench: unknown benchmark '%s' (ladder, scaling, solvers, pair, machine, levels)\n",
            o.what);
    return 2;
}
