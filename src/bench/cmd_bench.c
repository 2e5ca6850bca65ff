/* sphlab bench WHAT: the seed's optimisation ladder on this machine.
 *   ladder    per level: the largest N at F steps/s (bisection over block
 *             sizes), ms per pass at a fixed N, checks against a reference
 *   scaling   time per step against N for each level (log-log)
 *   machine   the machine's limits (memory bandwidth, float peak)
 *   levels    the level table and the scene keys of each level */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "bench.h"
#include "gpu.h"
#include "plot.h"

static const app_cmd_spec spec = {
    .name = "bench",
    .cmd = APP_CMD(bench),
    .synopsis = "usage: sphlab bench WHAT [options]\n"
                "  ladder      for each level of the ladder: the largest N that runs at F steps/s or more\n"
                "              (bisection over block sizes, median of repeats), ms per pass at a fixed N,\n"
                "              and a check against the reference level; table, CSV, JSON, chart\n"
                "  scaling     time per step against N for each level (log-log): O(N^2) against O(N)\n"
                "  machine     the machine's limits: memory bandwidth (streaming loops), float peak (FMA loop)\n"
                "  levels      the levels and the scene keys that make each\n"
                "options:\n",
    .footer = "Files: DIR/ladder-3d.{csv,json,png,pdf}, DIR/scaling-3d.{csv,png,pdf}, DIR/machine.json (2d likewise).\n"
              "Exit status: 0 done; 1 a level failed its check, or an output could not be written; 2 bad command line.\n",
    .max_pos = 1,
};

typedef struct bench_opts {
    const char *what, *out, *levels;
    double fps, at;
    bool quick, quiet, at_given, trace;
    bench_config cfg;
    int sel[BENCH_MAX_LEVELS], nsel;
    bool progress;
} bench_opts;

static bool parse_levels(bench_opts *o)
{
    o->nsel = 0;
    if (!o->levels) {
        for (int i = 0; i < bench_level_count && i < BENCH_MAX_LEVELS; i++) o->sel[o->nsel++] = i;
        return true;
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
        fprintf(stderr, "sphlab bench: --set: %s\n", err.msg);
        return false;
    }
    o->cfg.set_level[o->cfg.n_sets] = level;
    o->cfg.set[o->cfg.n_sets++] = assign;
    return true;
}

static int parse_args(int argc, char **argv, bench_opts *o)
{
    app_opts opt;
    app_opts_init(&opt);
    opt.fps = 60;
    opt.dim = 3;
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    o->what = opt.n_pos ? opt.pos[0] : NULL;
    o->fps = opt.fps;
    o->cfg.dim = (int)opt.dim;
    o->at_given = opt.at >= 0;
    o->at = (double)opt.at;
    o->out = opt.out;
    o->levels = opt.levels;
    o->quick = opt.quick;
    o->quiet = opt.quiet;
    o->trace = opt.trace;
    o->cfg.watchdog = opt.watchdog;
    for (int i = 0; i < opt.sets.n; i++)
        if (!add_set(o, opt.sets.v[i])) return 2;
    if (!o->what) {
        app_opts_usage(&spec, stderr);
        return 2;
    }
    if (!parse_levels(o)) return 2;
    if (!o->out) o->out = ".";
    if (!o->at_given) o->at = o->quick ? 6000 : 20000;
    o->progress = !o->quiet && isatty(STDERR_FILENO);
    return -1;
}

static bench_opts *g_opts;

static void progress(const char *fmt, ...)
{
    if (!g_opts || !g_opts->progress) return;
    char line[160];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\r  %-76.76s", line);
    fflush(stderr);
}

static void progress_done(void)
{
    if (g_opts && g_opts->progress) fprintf(stderr, "\r%80s\r", "");
}

static void trace(const bench_level *L, const bench_meas *m, const char *what)
{
    if (!g_opts || !g_opts->trace) return;
    progress_done();
    fprintf(stderr, "trace %s %-6s N %8u  %8.2f steps/s  %8.3f ms/step  repeats %d  attempts %d  others %.2f\n", L->name,
            what, m->n, m->steps_per_s, m->ms_step, m->repeats, m->attempts, m->others);
}

static const char *dim_tag(int dim) { return dim == 2 ? "2d" : "3d"; }

static void write_load(FILE *f, const double l[3])
{
    fprintf(f, "[%.2f, %.2f, %.2f]", l[0], l[1], l[2]);
}

/* Passes that belong to the neighbour search, and those that loop over the neighbour lists. */
static bool is_search_pass(int p)
{
    return p == SPH_PASS_HASH || p == SPH_PASS_SORT || p == SPH_PASS_REORDER || p == SPH_PASS_OFFSETS ||
           p == SPH_PASS_NEIGHBOURS;
}
static bool is_pair_pass(int p)
{
    return p == SPH_PASS_DENSITY || p == SPH_PASS_PRESSURE_FORCE || p == SPH_PASS_VISCOSITY;
}

/* ---- ladder ------------------------------------------------------------------------ */

typedef struct level_result {
    bool searched;
    double max_n, rate_at_max; /* 0 if even the smallest size is too slow */
    bool capped;               /* the largest size tried still ran fast enough */
    int measurements;
    bench_meas at;             /* at the fixed N */
    bool at_ok;
    double search_ms, force_ms, search_rate, force_rate; /* rates: pairs per second per core */
    bench_diff small, large;   /* checks */
    bool check_ok;
    double others;             /* cores other processes kept busy while this level was measured */
    bool skipped;              /* a GL level where no OpenGL 4.3 context can be made */
    char error[512];           /* or why it was skipped */
} level_result;

/* Largest size k of level L with steps/s >= fps. */
static bool search_max(const bench_opts *o, const bench_level *L, int Li, const bench_plan *plan, double cap,
                       level_result *r)
{
    const int dim = o->cfg.dim;
    char why[512];
    bench_meas m;
    int lo = -1, hi = -1;
    double lo_rate = 0;
    int k = bench_k_at_least(dim, 128);
    /* up by doublings of N until a size is too slow */
    for (;;) {
        progress("%s %s: N = %.0f ...", L->name, L->about, bench_count(dim, k));
        if (!bench_measure_retry(&o->cfg, L, k, plan, o->fps, o->quick ? 2 : 3, &m, why, sizeof why)) {
            snprintf(r->error, sizeof r->error, "%s", why);
            return false;
        }
        r->measurements += m.attempts;
        trace(L, &m, "grow");
        progress("%s %s: N = %.0f: %.1f steps/s", L->name, L->about, bench_count(dim, k), m.steps_per_s);
        if (m.steps_per_s >= o->fps) {
            lo = k, lo_rate = m.steps_per_s;
            if (bench_count(dim, k) >= cap) {
                r->capped = true;
                break;
            }
            int next = bench_k_at_least(dim, 2 * bench_count(dim, k));
            if (bench_count(dim, next) > cap) next = bench_k_at_least(dim, cap);
            k = next > k ? next : k + 1;
        } else {
            hi = k;
            if (lo >= 0 || k == bench_k_min(dim)) break;
            int next = bench_k_at_least(dim, bench_count(dim, k) / 2);
            if (next >= k) next = k - 1;
            k = next;
        }
    }
    /* bisection between a size fast enough and one too slow */
    while (lo >= 0 && hi >= 0 && hi - lo > 1) {
        int mid = lo + (hi - lo) / 2;
        progress("%s %s: N = %.0f ...", L->name, L->about, bench_count(dim, mid));
        if (!bench_measure_retry(&o->cfg, L, mid, plan, o->fps, o->quick ? 2 : 3, &m, why, sizeof why)) {
            snprintf(r->error, sizeof r->error, "%s", why);
            return false;
        }
        r->measurements += m.attempts;
        trace(L, &m, "bisect");
        if (m.steps_per_s >= o->fps)
            lo = mid, lo_rate = m.steps_per_s;
        else
            hi = mid;
    }
    (void)Li;
    r->searched = true;
    r->max_n = lo >= 0 ? bench_count(dim, lo) : 0;
    r->rate_at_max = lo >= 0 ? lo_rate : 0;
    return true;
}

static void fill_rates(level_result *r)
{
    r->search_ms = r->force_ms = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        double v = r->at.pass_ms[p];
        if (!isfinite(v)) continue;
        if (is_search_pass(p)) r->search_ms += v;
        if (is_pair_pass(p)) r->force_ms += v;
    }
    int t = r->at.threads > 0 ? r->at.threads : 1;
    r->search_rate = r->search_ms > 0 ? r->at.pairs / (r->search_ms / 1e3) / t : 0; /* NaN: no lists (GL) */
    r->force_rate = r->force_ms > 0 ? r->at.pairs / (r->force_ms / 1e3) / t : 0;
}

/* The three passes that take longest at the fixed N, as "name ms  name ms ...". */
static void top_passes(const bench_meas *m, char *out, size_t cap, int count)
{
    bool used[SPH_PASS_COUNT] = {false};
    out[0] = '\0';
    for (int c = 0; c < count; c++) {
        int best = -1;
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (!used[p] && isfinite(m->pass_ms[p]) && (best < 0 || m->pass_ms[p] > m->pass_ms[best])) best = p;
        if (best < 0) break;
        used[best] = true;
        size_t len = strlen(out);
        snprintf(out + len, cap - len, "%s%s %.3g", c ? "  " : "", sph_passes[best]->name, m->pass_ms[best]);
    }
}

static const char *check_word(const level_result *r)
{
    if (r->skipped) return "SKIP";
    if (!r->small.done && !r->large.done) return "-";
    return r->check_ok ? "PASS" : "FAIL";
}

static void csv_num(FILE *f, double v, const char *fmt)
{
    fputc(',', f);
    if (isfinite(v)) fprintf(f, fmt, v);
}

static void write_ladder_csv(FILE *f, const bench_opts *o, const level_result *res, const bool *pass_used, double n_at,
                             double n_check)
{
    fprintf(f, "level,description,backend,threads,max_n,capped,steps_per_s_at_max,speedup,n_at,ms_per_step,pairs_per_step,"
               "search_ms,force_ms,search_pairs_per_s_core,force_pairs_per_s_core,check,check_ref,check_n,sets_differ,"
               "edge_pairs,max_dx_m,max_dv_m_s,max_drho,check_at_ref,check_at_n,sets_differ_at,edge_pairs_at,"
               "max_dx_at_m,max_dv_at_m_s,max_drho_at,others_cores");
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (pass_used[p]) fprintf(f, ",%s_ms", sph_passes[p]->name);
    fputc('\n', f);
    double prev = NAN;
    for (int s = 0; s < o->nsel; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        const level_result *r = &res[s];
        char about[128];
        snprintf(about, sizeof about, "%s", L->about);
        for (char *c = about; *c; c++)
            if (*c == ',' || *c == '"') *c = ';';
        fprintf(f, "%s,%s,%s,%d", L->name, about, bench_level_gl(L) ? "gl" : "cpu",
                r->at.threads ? r->at.threads : L->threads);
        csv_num(f, r->searched ? r->max_n : NAN, "%.0f");
        fprintf(f, ",%d", r->capped ? 1 : 0);
        csv_num(f, r->searched ? r->rate_at_max : NAN, "%.4g");
        csv_num(f, s > 0 && prev > 0 && r->searched ? r->max_n / prev : NAN, "%.4g");
        prev = r->searched ? r->max_n : NAN;
        csv_num(f, r->at_ok ? (double)r->at.n : NAN, "%.0f");
        csv_num(f, r->at_ok ? r->at.ms_step : NAN, "%.6g");
        csv_num(f, r->at_ok ? r->at.pairs : NAN, "%.0f");
        csv_num(f, r->at_ok ? r->search_ms : NAN, "%.6g");
        csv_num(f, r->at_ok ? r->force_ms : NAN, "%.6g");
        csv_num(f, r->at_ok ? r->search_rate : NAN, "%.4g");
        csv_num(f, r->at_ok ? r->force_rate : NAN, "%.4g");
        fprintf(f, ",%s", check_word(r));
        fprintf(f, ",%s", r->small.done ? bench_levels[r->small.ref].name : "");
        csv_num(f, r->small.done ? n_check : NAN, "%.0f");
        csv_num(f, r->small.done ? (double)r->small.sets_differ : NAN, "%.0f");
        csv_num(f, r->small.done ? (double)r->small.edge_pairs : NAN, "%.0f");
        csv_num(f, r->small.done ? r->small.dx : NAN, "%.3g");
        csv_num(f, r->small.done ? r->small.dv : NAN, "%.3g");
        csv_num(f, r->small.done ? r->small.drho : NAN, "%.3g");
        fprintf(f, ",%s", r->large.done ? bench_levels[r->large.ref].name : "");
        csv_num(f, r->large.done ? n_at : NAN, "%.0f");
        csv_num(f, r->large.done ? (double)r->large.sets_differ : NAN, "%.0f");
        csv_num(f, r->large.done ? (double)r->large.edge_pairs : NAN, "%.0f");
        csv_num(f, r->large.done ? r->large.dx : NAN, "%.3g");
        csv_num(f, r->large.done ? r->large.dv : NAN, "%.3g");
        csv_num(f, r->large.done ? r->large.drho : NAN, "%.3g");
        csv_num(f, r->others, "%.3f");
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (pass_used[p]) csv_num(f, r->at_ok ? r->at.pass_ms[p] : NAN, "%.6g");
        fputc('\n', f);
    }
}

static void json_num(FILE *f, const char *key, double v, const char *fmt, bool comma)
{
    fprintf(f, "\"%s\": ", key);
    if (isfinite(v))
        fprintf(f, fmt, v);
    else
        fputs("null", f);
    if (comma) fputs(", ", f);
}

static void json_diff(FILE *f, const char *key, const bench_diff *d, double n)
{
    fprintf(f, "      \"%s\": ", key);
    if (!d->done) {
        fputs("null,\n", f);
        return;
    }
    fprintf(f, "{\"reference\": \"%s\", \"n\": %.0f, \"pass\": %s, \"sets_differ\": %u, \"edge_pairs\": %u, ",
            bench_levels[d->ref].name, n, d->pass ? "true" : "false", d->sets_differ, d->edge_pairs);
    json_num(f, "pairs", d->pairs, "%.0f", true);
    json_num(f, "reference_pairs", d->ref_pairs, "%.0f", true);
    json_num(f, "max_dx_m", d->dx, "%.3g", true);
    json_num(f, "max_dv_m_s", d->dv, "%.3g", true);
    json_num(f, "max_drho", d->drho, "%.3g", true);
    fputs("\"why\": ", f);
    bench_json_string(f, d->why);
    fputs("},\n", f);
}

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
    bool all_pass;
} ladder_meta;

static void write_ladder_json(FILE *f, const bench_opts *o, const level_result *res, const ladder_meta *m,
                              int argc, char **argv)
{
    fputs("{\n  \"command\": ", f);
    char cmd[1024] = "sphlab";
    for (int i = 0; i < argc; i++) {
        size_t len = strlen(cmd);
        snprintf(cmd + len, sizeof cmd - len, " %s", argv[i]);
    }
    bench_json_string(f, cmd);
    fputs(",\n  \"date\": ", f);
    bench_json_string(f, m->date);
    fprintf(f, ",\n  \"dim\": %d,\n  \"fps\": %.6g,\n  \"quick\": %s,\n  \"watchdog\": %s,\n", o->cfg.dim, o->fps,
            o->quick ? "true" : "false", o->cfg.watchdog ? "true" : "false");
    fputs("  \"load_start\": ", f);
    write_load(f, m->load0);
    fputs(",\n  \"load_end\": ", f);
    write_load(f, m->load1);
    fprintf(f, ",\n  \"seconds\": %.1f,\n  ", m->seconds);
    json_num(f, "other_processes_cores", m->others, "%.3f", true);
    json_num(f, "clock_ghz_start", m->ghz0, "%.3f", true);
    json_num(f, "clock_ghz_end", m->ghz1, "%.3f", false);
    fputs(",\n", f);
    sph_scene_def def;
    char why[256];
    sph_scene_def cdef;
    if (bench_scene_def(&o->cfg, NULL, bench_k_near(o->cfg.dim, m->n_at), false, &def, why, sizeof why) &&
        bench_scene_def(&o->cfg, NULL, bench_k_near(o->cfg.dim, m->n_at), true, &cdef, why, sizeof why))
        fprintf(f, "  \"scene\": {\"what\": \"a block of water falling in a box twice its size\", \"spacing_m\": %g, "
                   "\"h_m\": %g, \"jitter_spacings\": %g, \"check_jitter_spacings\": %g, \"stiffness\": %g, "
                   "\"viscosity\": %g, \"cfl\": %g},\n",
                def.blocks[0].spacing, def.h, def.jitter, cdef.jitter, def.stiffness, def.viscosity, def.cfl);
    fputs("  \"sets\": [", f);
    for (int i = 0; i < o->cfg.n_sets; i++) {
        char set[300];
        snprintf(set, sizeof set, "%s%s%s", o->cfg.set_level[i] ? o->cfg.set_level[i] : "",
                 o->cfg.set_level[i] ? ":" : "", o->cfg.set[i]);
        fputs(i ? ", " : "", f);
        bench_json_string(f, set);
    }
    fputs("],\n", f);
    fprintf(f, "  \"n_at\": %.0f,\n  \"n_check\": %.0f,\n", m->n_at, m->n_check);
    fprintf(f, "  \"tolerances\": {\"steps\": %d, \"dx_m\": %g, \"dv_m_s\": %g, \"drho\": %g, \"neighbour_sets\": "
               "\"identical after 1 step\", \"edge_pairs_within_h_times\": %g},\n",
            BENCH_CHECK_STEPS, BENCH_TOL_X, BENCH_TOL_V, BENCH_TOL_RHO, BENCH_EDGE);
    fputs("  \"target\": {\"dim\": 3, \"fps\": 60, \"n\": 60000, ", f);
    if (m->best >= 0) {
        fputs("\"best_level\": ", f);
        bench_json_string(f, bench_levels[o->sel[m->best]].name);
        fprintf(f, ", \"best_n\": %.0f, ", res[m->best].max_n);
    }
    fprintf(f, "\"met\": %s},\n", !m->target_evaluated ? "null" : m->target_met ? "true" : "false");
    fputs("  \"gl_device\": ", f);
    if (m->gl_device[0])
        bench_json_string(f, m->gl_device);
    else
        fputs("null", f);
    fputs(",\n  \"gl_target\": {\"dim\": 3, \"fps\": 60, \"n\": 1000000, ", f);
    if (m->gl_best >= 0) {
        fputs("\"best_level\": ", f);
        bench_json_string(f, bench_levels[o->sel[m->gl_best]].name);
        fprintf(f, ", \"best_n\": %.0f, ", res[m->gl_best].max_n);
    }
    fprintf(f, "\"met\": %s},\n",
            !m->gl_target_evaluated ? "null" : m->gl_target_met ? "true" : "false");
    fprintf(f, "  \"all_checks_pass\": %s,\n  \"levels\": [\n", m->all_pass ? "true" : "false");
    double prev = NAN;
    for (int s = 0; s < o->nsel; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        const level_result *r = &res[s];
        fputs("    {\n      \"level\": ", f);
        bench_json_string(f, L->name);
        fputs(", \"description\": ", f);
        bench_json_string(f, L->about);
        fputs(", \"sets\": ", f);
        bench_json_string(f, L->sets);
        fprintf(f, ", \"backend\": \"%s\", \"threads\": %d,\n      ", bench_level_gl(L) ? "gl" : "cpu",
                r->at.threads ? r->at.threads : L->threads);
        json_num(f, "max_n", r->searched ? r->max_n : NAN, "%.0f", true);
        fprintf(f, "\"capped\": %s, ", r->capped ? "true" : "false");
        json_num(f, "steps_per_s_at_max", r->searched ? r->rate_at_max : NAN, "%.4g", true);
        json_num(f, "speedup", s > 0 && prev > 0 && r->searched ? r->max_n / prev : NAN, "%.4g", false);
        prev = r->searched ? r->max_n : NAN;
        fputs(",\n      ", f);
        json_num(f, "n_at", r->at_ok ? (double)r->at.n : NAN, "%.0f", true);
        json_num(f, "ms_per_step", r->at_ok ? r->at.ms_step : NAN, "%.6g", true);
        json_num(f, "pairs_per_step", r->at_ok ? r->at.pairs : NAN, "%.0f", true);
        json_num(f, "search_pairs_per_s_core", r->at_ok ? r->search_rate : NAN, "%.4g", true);
        json_num(f, "force_pairs_per_s_core", r->at_ok ? r->force_rate : NAN, "%.4g", true);
        json_num(f, "other_processes_cores", r->others, "%.3f", true);
        json_num(f, "at_other_processes_cores", r->at_ok ? r->at.others : NAN, "%.3f", true);
        fprintf(f, "\"measurements\": %d", r->measurements);
        fputs(",\n      \"pass_ms\": {", f);
        bool first = true;
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (r->at_ok && isfinite(r->at.pass_ms[p])) {
                fprintf(f, "%s\"%s\": %.6g", first ? "" : ", ", sph_passes[p]->name, r->at.pass_ms[p]);
                first = false;
            }
        fputs("},\n", f);
        fprintf(f, "      \"check\": \"%s\",\n", check_word(r));
        json_diff(f, "check_small", &r->small, m->n_check);
        json_diff(f, "check_at", &r->large, m->n_at);
        fputs("      \"error\": ", f);
        bench_json_string(f, r->error);
        fprintf(f, "\n    }%s\n", s + 1 < o->nsel ? "," : "");
    }
    fputs("  ]\n}\n", f);
}

/* The reference states, made when first needed. */
typedef struct ref_cache {
    int level, k;
    bool made, ok;
    bench_state st;
} ref_cache;

static const bench_state *ref_get(const bench_opts *o, ref_cache *c, char *why, size_t n)
{
    if (!c->made) {
        c->made = true;
        progress("reference %s at N = %.0f: %d steps ...", bench_levels[c->level].name, bench_count(o->cfg.dim, c->k),
                 BENCH_CHECK_STEPS);
        c->ok = bench_state_run(&o->cfg, &bench_levels[c->level], c->k, &c->st, why, n);
    } else if (!c->ok) {
        snprintf(why, n, "the reference run failed");
    }
    return c->ok ? &c->st : NULL;
}

static void run_check(const bench_opts *o, int Li, ref_cache *ref, int k, bench_diff *d, char *err, size_t errn)
{
    memset(d, 0, sizeof *d);
    char why[512] = "";
    const bench_state *R = ref_get(o, ref, why, sizeof why);
    d->ref = ref->level;
    if (!R) {
        d->done = true;
        d->pass = false;
        snprintf(d->why, sizeof d->why, "reference %s: %.120s", bench_levels[ref->level].name, why);
        snprintf(err, errn, "%s", d->why);
        return;
    }
    progress("%s check against %s at N = %.0f ...", bench_levels[Li].name, bench_levels[ref->level].name,
             bench_count(o->cfg.dim, k));
    bench_state s;
    if (!bench_state_run(&o->cfg, &bench_levels[Li], k, &s, why, sizeof why)) {
        d->done = true;
        d->pass = false;
        snprintf(d->why, sizeof d->why, "%.150s", why);
        snprintf(err, errn, "%s", why);
        return;
    }
    bench_compare(R, &s, d);
    d->ref = ref->level;
    bench_state_free(&s);
}

static int cmd_ladder(bench_opts *o, int argc, char **argv)
{
    const int dim = o->cfg.dim;
    const double fps = o->fps;
    ladder_meta meta = {.best = -1};
    bench_now_iso(meta.date, sizeof meta.date);
    bench_loadavg(meta.load0);
    double t_start = sph_now_ms();
    bench_cpu cpu0, cpu1;
    bench_cpu_now(&cpu0);
    meta.ghz0 = bench_clock_probe();

    int ref_small = bench_level_find(BENCH_REF_SMALL), ref_large = bench_level_find(BENCH_REF_LARGE);
    if (ref_small < 0 || ref_large < 0) {
        fprintf(stderr, "sphlab bench: the level table has no %s or %s (the references of the checks)\n",
                BENCH_REF_SMALL, BENCH_REF_LARGE);
        return 1;
    }
    /* sizes: the check runs above the size where the passes go parallel */
    const int k_check = bench_k_at_least(dim, o->quick ? SPH_PARALLEL_MIN + 1 : 8000);
    const int k_at = bench_k_near(dim, o->at);
    meta.n_check = bench_count(dim, k_check);
    meta.n_at = bench_count(dim, k_at);
    const bench_plan plan_search = o->quick ? (bench_plan){2, 2, 300, fps, false} : (bench_plan){5, 3, 2500, fps, false};
    const bench_plan plan_at = o->quick ? (bench_plan){3, 2, 600, 0, true} : (bench_plan){7, 3, 5000, 0, true};
    const double cap = o->quick ? 150000 : 4000000;

    if (!plot_out_dir(o->out)) return 1;
    /* an unwritable directory fails now, not after the measurements */
    char probe[1100];
    snprintf(probe, sizeof probe, "%s/.bench-probe-%ld", o->out, (long)getpid());
    FILE *pf = fopen(probe, "w");
    if (!pf) {
        fprintf(stderr, "sphlab bench: --out %s: cannot write there\n", o->out);
        return 1;
    }
    fclose(pf);
    remove(probe);

    level_result *res = calloc((size_t)o->nsel, sizeof *res);
    if (!res) return 1;
    ref_cache ref_s = {.level = ref_small, .k = k_check}, ref_l = {.level = ref_large, .k = k_at};
    ref_cache ref_l_small = {.level = ref_large, .k = k_check};
    bool all_pass = true;
    int gl_state = 0; /* 0: not probed yet, 1: a GL 4.3 context can be made, -1: none */
    meta.gl_best = -1;
    for (int s = 0; s < o->nsel; s++) {
        const int Li = o->sel[s];
        const bench_level *L = &bench_levels[Li];
        level_result *r = &res[s];
        char err[512] = "";
        if (bench_level_gl(L)) {
            if (gl_state == 0) {
                gl_state = sph_gpu_probe(meta.gl_device, sizeof meta.gl_device) ? 1 : -1;
                meta.gl_is_gpu = gl_state > 0 && !strstr(meta.gl_device, "llvmpipe") &&
                                 !strstr(meta.gl_device, "softpipe") && !strstr(meta.gl_device, "lavapipe");
            }
            if (gl_state < 0) { /* no device: said, not failed */
                r->skipped = true;
                snprintf(r->error, sizeof r->error, "no OpenGL 4.3 device: %s", meta.gl_device);
                continue;
            }
            meta.gl_ran = true;
        }
        bench_cpu c0, c1;
        bench_cpu_now(&c0);
        /* checks first: no speedup is reported without them */
        if (Li != ref_small)
            run_check(o, Li, &ref_s, k_check, &r->small, err, sizeof err);
        else
            run_check(o, Li, &ref_l_small, k_check, &r->small, err, sizeof err); /* brute force against the hash */
        if (k_at > k_check && Li != ref_small && Li != ref_large)
            run_check(o, Li, &ref_l, k_at, &r->large, err, sizeof err);
        r->check_ok = (!r->small.done || r->small.pass) && (!r->large.done || r->large.pass);
        all_pass &= r->check_ok;
        if (err[0]) snprintf(r->error, sizeof r->error, "%s", err);
        /* the largest N at the frame rate */
        if (!search_max(o, L, Li, &plan_search, cap, r)) {
            all_pass = false;
            r->check_ok = false;
        }
        /* ms per pass at the fixed N */
        progress("%s %s: passes at N = %.0f ...", L->name, L->about, meta.n_at);
        char why[512];
        r->at_ok = bench_measure_retry(&o->cfg, L, k_at, &plan_at, 0, o->quick ? 2 : 3, &r->at, why, sizeof why);
        if (!r->at_ok) {
            snprintf(r->error, sizeof r->error, "%s", why);
            all_pass = false;
            r->check_ok = false;
        } else {
            fill_rates(r);
        }
        bench_cpu_now(&c1);
        r->others = bench_cpu_others(&c0, &c1);
    }
    progress_done();
    bench_cpu_now(&cpu1);
    meta.others = bench_cpu_others(&cpu0, &cpu1);
    meta.ghz1 = bench_clock_probe();
    bench_state_free(&ref_s.st);
    bench_state_free(&ref_l.st);
    bench_state_free(&ref_l_small.st);
    bench_loadavg(meta.load1);
    meta.seconds = (sph_now_ms() - t_start) / 1e3;
    meta.all_pass = all_pass;
    for (int s = 0; s < o->nsel; s++) {
        int *best = bench_level_gl(&bench_levels[o->sel[s]]) ? &meta.gl_best : &meta.best;
        if (res[s].searched && (*best < 0 || res[s].max_n > res[*best].max_n)) *best = s;
    }
    meta.target_evaluated = dim == 3 && fabs(fps - 60) < 1e-9 && meta.best >= 0;
    meta.target_met = meta.target_evaluated && res[meta.best].max_n >= 60000;
    meta.gl_target_met = meta.gl_best >= 0 && res[meta.gl_best].max_n >= 1000000;
    meta.gl_target_evaluated = dim == 3 && fabs(fps - 60) < 1e-9 && meta.gl_best >= 0 && meta.gl_is_gpu;

    bool pass_used[SPH_PASS_COUNT] = {false};
    for (int s = 0; s < o->nsel; s++)
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (res[s].at_ok && isfinite(res[s].at.pass_ms[p])) pass_used[p] = true;

    /* ---- the table ---- */
    if (!o->quiet) {
        char nat[32], nchk[32];
        bench_fmt_count(nat, sizeof nat, meta.n_at);
        bench_fmt_count(nchk, sizeof nchk, meta.n_check);
        printf("sphlab bench ladder: %dD block of water falling in a box, h = 2 spacings, target %g steps/s%s\n", dim,
               fps, o->quick ? " (--quick)" : "");
        printf("%s, load %.2f at the start, %.2f at the end, %.0f s\n", meta.date, meta.load0[0], meta.load1[0],
               meta.seconds);
        printf("other processes kept %.2f of the %d cores busy on average while it ran; one core's clock %.2f GHz\n"
               "at the start, %.2f at the end (lower when the host is busy)\n",
               meta.others, bench_levels_cores(), meta.ghz0, meta.ghz1);
        if (meta.gl_ran)
            printf("GL levels (G*): %s%s\n", meta.gl_device,
                   meta.gl_is_gpu ? "" : " (software rendering on this CPU: a correctness device, not a GPU)");
        else if (gl_state < 0)
            printf("GL levels (G*) skipped: no OpenGL 4.3 device: %s\n", meta.gl_device);
        double worst = 0;
        for (int s = 0; s < o->nsel; s++) worst = fmax(worst, res[s].others);
        if (worst > 0.2)
            printf("warning: the machine was busy (others: up to %.2f cores during a level, column 'others'): timings\n"
                   "are low and noisy, the threaded levels worst (a parallel region waits for its slowest thread);\n"
                   "re-run when quiet\n",
                   worst);
        printf("\n");
        printf("%-5s %-42s %3s %12s %8s %10s  %-44s %-5s %s\n", "level", "description", "thr", "max N", "speedup",
               "ms/step", "top passes at fixed N (ms)", "check", "others");
        double prev = NAN;
        for (int s = 0; s < o->nsel; s++) {
            const bench_level *L = &bench_levels[o->sel[s]];
            const level_result *r = &res[s];
            char maxn[40] = "-", sp[16] = "-", ms[16] = "-", top[128] = "";
            if (r->searched) {
                if (r->max_n > 0)
                    bench_fmt_count(maxn, sizeof maxn, r->max_n);
                else /* a slow machine or software GL: reported, not a failure */
                    snprintf(maxn, sizeof maxn, "none");
                if (r->capped) strcat(maxn, "+");
                if (s > 0 && prev > 0) snprintf(sp, sizeof sp, "x%.2f", r->max_n / prev);
                prev = r->max_n;
            }
            if (r->at_ok) {
                snprintf(ms, sizeof ms, "%.4g", r->at.ms_step);
                top_passes(&r->at, top, sizeof top, 3);
            }
            printf("%-5s %-42s %3d %12s %8s %10s  %-44s %-5s %.2f\n", L->name, L->about,
                   r->at.threads ? r->at.threads : L->threads, maxn, sp, ms, top, check_word(r), r->others);
        }
        printf("\nmax N: the largest block with %g steps/s or more (bisection over block sizes, median of repeats;\n"
               "none: not even the smallest block reached it on this machine, which is no failure);\n"
               "ms/step and passes: medians at N = %s; others: cores that other processes kept busy meanwhile\n",
               fps, nat);
        printf("\nwhere the time goes at N = %s (pairs: neighbour-list entries per step, i->j and j->i):\n", nat);
        printf("%-5s %12s %10s %16s %10s %16s\n", "level", "pairs", "search ms", "pairs/s/core", "forces ms",
               "pairs/s/core");
        for (int s = 0; s < o->nsel; s++) {
            const level_result *r = &res[s];
            if (!r->at_ok) continue;
            if (r->at.pairs > 0)
                printf("%-5s %12.0f %10.3f %16.3g %10.3f %16.3g\n", bench_levels[o->sel[s]].name, r->at.pairs,
                       r->search_ms, r->search_rate, r->force_ms, r->force_rate);
            else /* a GL level: no lists, its passes walk the cells */
                printf("%-5s %12s %10.3f %16s %10.3f %16s\n", bench_levels[o->sel[s]].name, "-", r->search_ms, "-",
                       r->force_ms, "-");
        }
        printf("search: hash, sort, reorder, offsets, neighbours; forces: density, pressure_force, viscosity\n"
               "(GL levels build no lists: density and the forces walk the cells themselves, so no pair count)\n");
        printf("\nchecks: neighbour sets identical after 1 step (a pair within %g h of r = h is rounding's call and\n"
               "counted apart: edge pairs), and after %d steps positions within %g m, velocities within %g m/s,\n"
               "densities within %g (relative), particles matched by id; against %s at N = %s",
               BENCH_EDGE, BENCH_CHECK_STEPS, BENCH_TOL_X, BENCH_TOL_V, BENCH_TOL_RHO, BENCH_REF_SMALL, nchk);
        if (k_at > k_check) printf(" and against %s at N = %s", BENCH_REF_LARGE, nat);
        printf(" (%s itself against %s).\n", BENCH_REF_SMALL, BENCH_REF_LARGE);
        for (int s = 0; s < o->nsel; s++) {
            const level_result *r = &res[s];
            const bench_diff *d[2] = {&r->small, &r->large};
            for (int j = 0; j < 2; j++)
                if (d[j]->done)
                    printf("  %-4s vs %-3s N = %-7.0f %s  sets differ %u (edge pairs %u), dx %.2g m, dv %.2g m/s, "
                           "drho %.2g%s%s\n",
                           bench_levels[o->sel[s]].name, bench_levels[d[j]->ref].name, j ? meta.n_at : meta.n_check,
                           d[j]->pass ? "PASS" : "FAIL", d[j]->sets_differ, d[j]->edge_pairs, d[j]->dx, d[j]->dv,
                           d[j]->drho, d[j]->why[0] ? ": " : "", d[j]->why);
            if (r->skipped)
                printf("  %-4s skipped: %s\n", bench_levels[o->sel[s]].name, r->error);
            else if (r->error[0] && !r->check_ok)
                printf("  %-4s error: %s\n", bench_levels[o->sel[s]].name, r->error);
        }
        if (meta.target_evaluated) {
            char bn[32];
            bench_fmt_count(bn, sizeof bn, res[meta.best].max_n);
            printf("\ntarget (issue 6): the fastest CPU level reaches 60,000 particles at 60 steps/s in 3D: %s "
                   "(%s: %s)\n",
                   meta.target_met ? "MET" : "NOT MET", bench_levels[o->sel[meta.best]].name, bn);
        } else {
            printf("\ntarget (issue 6: 60,000 particles at 60 steps/s in 3D): not evaluated with these options\n");
        }
        if (meta.gl_best >= 0 && dim == 3 && fabs(fps - 60) < 1e-9) {
            char bn[32];
            bench_fmt_count(bn, sizeof bn, res[meta.gl_best].max_n);
            if (meta.gl_target_evaluated)
                printf("target (issue 7): a GL level reaches 1,000,000 particles at 60 steps/s in 3D on a GPU: %s "
                       "(%s: %s)\n",
                       meta.gl_target_met ? "MET" : "NOT MET", bench_levels[o->sel[meta.gl_best]].name, bn);
            else
                printf("target (issue 7, 1,000,000 at 60 steps/s on a GPU): not evaluated, no GPU here (%s: %s on "
                       "software rendering)\n",
                       bench_levels[o->sel[meta.gl_best]].name, bn);
        }
        if (!all_pass) printf("\nFAIL: a level failed its check; its speed does not count\n");
        printf("\n");
    }

    /* ---- files ---- */
    bool ok = true;
    char name[64];
    snprintf(name, sizeof name, "ladder-%s.csv", dim_tag(dim));
    FILE *f = plot_out_stage_csv(o->out, name);
    if (!f) ok = false;
    if (f) {
        write_ladder_csv(f, o, res, pass_used, meta.n_at, meta.n_check);
        ok &= plot_out_close_csv(f, o->out, name);
    }
    snprintf(name, sizeof name, "ladder-%s.json", dim_tag(dim));
    f = ok ? plot_out_stage_csv(o->out, name) : NULL;
    if (ok && !f) ok = false;
    if (f) {
        write_ladder_json(f, o, res, &meta, argc, argv);
        ok &= plot_out_close_csv(f, o->out, name);
    }
    if (ok) {
        static bench_ladder_chart c;
        memset(&c, 0, sizeof c);
        char nat[32];
        bench_fmt_count(nat, sizeof nat, meta.n_at);
        snprintf(c.title, sizeof c.title, "The optimisation ladder, %dD, on this machine", dim);
        snprintf(c.subtitle, sizeof c.subtitle, "%s   load %.2f   %s", meta.date, meta.load0[0],
                 all_pass ? "every level checked against the reference: PASS" : "a level FAILED its check");
        snprintf(c.bars_title, sizeof c.bars_title, "largest N at %g steps/s (log scale)", fps);
        snprintf(c.stack_title, sizeof c.stack_title, "ms per step at N = %s, by pass", nat);
        if (dim == 3 && fabs(fps - 60) < 1e-9) {
            c.target_n = 60000;
            snprintf(c.target_label, sizeof c.target_label, "60,000: the seed's GPU record");
        }
        c.nl = o->nsel;
        int np = 0;
        for (int p = 0; p < SPH_PASS_COUNT && np < BENCH_CHART_PASSES; p++)
            if (pass_used[p]) snprintf(c.pass[np++], sizeof c.pass[0], "%s", sph_passes[p]->name);
        c.np = np;
        for (int s = 0; s < o->nsel; s++) {
            const level_result *r = &res[s];
            snprintf(c.level[s], sizeof c.level[s], "%s %.42s", bench_levels[o->sel[s]].name,
                     bench_levels[o->sel[s]].about);
            c.max_n[s] = r->searched ? r->max_n : 0;
            char n[32];
            bench_fmt_count(n, sizeof n, c.max_n[s]);
            snprintf(c.note[s], sizeof c.note[s], "%s%s%s", n, r->capped ? "+" : "", r->check_ok ? "" : "  FAIL");
            int q = 0;
            for (int p = 0; p < SPH_PASS_COUNT; p++)
                if (pass_used[p]) c.ms[s][q++] = r->at_ok ? r->at.pass_ms[p] : NAN;
        }
        snprintf(name, sizeof name, "ladder-%s", dim_tag(dim));
        ok &= bench_chart_ladder(&c, o->out, name);
    }
    if (ok)
        ok = plot_out_commit(o->quiet);
    else
        plot_out_abort();
    free(res);
    return !ok || !all_pass ? 1 : 0;
}

/* ---- scaling ----------------------------------------------------------------------- */

static int cmd_scaling(bench_opts *o)
{
    const int dim = o->cfg.dim;
    char date[64];
    double load0[3], load1[3];
    bench_now_iso(date, sizeof date);
    bench_loadavg(load0);
    double t_start = sph_now_ms(), ghz0 = bench_clock_probe();
    /* N = 128, 256, ... : the quick run stops at 8192 */
    const double n_max = o->quick ? 8192 : (dim == 3 ? 262144 : 524288);
    const double max_ms = o->quick ? 150 : 1000; /* a level stops after a size this slow */
    const bench_plan plan = o->quick ? (bench_plan){1, 2, 200, 0, false} : (bench_plan){3, 3, 3000, 0, false};
    int ks[64], nk = 0;
    for (double n = 128; n <= n_max * 1.001 && nk < 64; n *= 2) {
        int k = bench_k_near(dim, n);
        if (nk == 0 || k != ks[nk - 1]) ks[nk++] = k;
    }
    if (!plot_out_dir(o->out)) return 1;
    /* GL levels only where an OpenGL 4.3 context can be made; said either way */
    char gl_device[256] = "";
    bool gl_probed = false, gl_ok = false;
    for (int s = 0; s < o->nsel; s++) {
        if (!bench_level_gl(&bench_levels[o->sel[s]])) continue;
        if (!gl_probed) {
            gl_ok = sph_gpu_probe(gl_device, sizeof gl_device);
            gl_probed = true;
            if (!o->quiet) printf("GL levels (G*): %s%s\n", gl_ok ? "" : "skipped, no OpenGL 4.3 device: ", gl_device);
        }
        if (!gl_ok) {
            memmove(o->sel + s, o->sel + s + 1, (size_t)(o->nsel - s - 1) * sizeof o->sel[0]);
            o->nsel--;
            s--;
        }
    }
    double *N = calloc((size_t)o->nsel * nk, sizeof *N), *MS = calloc((size_t)o->nsel * nk, sizeof *MS);
    double *PR = calloc((size_t)o->nsel * nk, sizeof *PR);
    int *cnt = calloc((size_t)o->nsel, sizeof *cnt), *thr = calloc((size_t)o->nsel, sizeof *thr);
    if (!N || !MS || !PR || !cnt || !thr) {
        fprintf(stderr, "sphlab bench: out of memory\n");
        return 1;
    }
    bool ok = true;
    double others[BENCH_MAX_LEVELS], worst = 0;
    for (int s = 0; s < o->nsel && ok; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        bench_cpu c0, c1;
        bench_cpu_now(&c0);
        for (int j = 0; j < nk; j++) {
            progress("%s %s: N = %.0f ...", L->name, L->about, bench_count(dim, ks[j]));
            bench_meas m;
            char why[512];
            if (!bench_measure_retry(&o->cfg, L, ks[j], &plan, 0, o->quick ? 1 : 3, &m, why, sizeof why)) {
                progress_done();
                fprintf(stderr, "sphlab bench: %s at N = %.0f: %s\n", L->name, bench_count(dim, ks[j]), why);
                ok = false;
                break;
            }
            N[s * nk + cnt[s]] = m.n;
            MS[s * nk + cnt[s]] = m.ms_step;
            PR[s * nk + cnt[s]] = m.pairs;
            thr[s] = m.threads;
            cnt[s]++;
            if (m.ms_step > max_ms) break;
        }
        bench_cpu_now(&c1);
        others[s] = bench_cpu_others(&c0, &c1);
        worst = fmax(worst, others[s]);
    }
    progress_done();
    bench_loadavg(load1);
    double seconds = (sph_now_ms() - t_start) / 1e3, ghz1 = bench_clock_probe();
    /* slope of log(ms) against log(N) over the upper half of each level's sizes */
    double slope[BENCH_MAX_LEVELS];
    for (int s = 0; s < o->nsel; s++) {
        int c = cnt[s], a = c / 2;
        if (c - a < 2) a = c - 2;
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        int m = 0;
        for (int i = a < 0 ? 0 : a; i < c; i++) {
            double x = log(N[s * nk + i]), y = log(MS[s * nk + i]);
            sx += x, sy += y, sxx += x * x, sxy += x * y, m++;
        }
        slope[s] = m >= 2 && m * sxx - sx * sx > 0 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
    }
    if (!o->quiet && ok) {
        printf("sphlab bench scaling: %dD, ms per step (median) against N%s\n%s, load %.2f at the start, %.2f at the "
               "end, %.0f s\n",
               dim, o->quick ? " (--quick)" : "", date, load0[0], load1[0], seconds);
        printf("one core's clock %.2f GHz at the start, %.2f at the end (lower when the host is busy)\n", ghz0, ghz1);
        if (worst > 0.2)
            printf("warning: the machine was busy (others: up to %.2f cores during a level): timings are low and\n"
                   "noisy, the threaded levels worst; re-run when quiet\n",
                   worst);
        printf("\n");
        printf("%9s", "N");
        for (int s = 0; s < o->nsel; s++) printf(" %10s", bench_levels[o->sel[s]].name);
        printf("\n");
        for (int j = 0; j < nk; j++) {
            printf("%9.0f", bench_count(dim, ks[j]));
            for (int s = 0; s < o->nsel; s++)
                if (j < cnt[s])
                    printf(" %10.4g", MS[s * nk + j]);
                else
                    printf(" %10s", "-");
            printf("\n");
        }
        printf("%9s", "slope");
        for (int s = 0; s < o->nsel; s++) printf(" %10.2f", slope[s]);
        printf("\n%9s", "others");
        for (int s = 0; s < o->nsel; s++) printf(" %10.2f", others[s]);
        printf("\n\nslope: of log(ms/step) against log(N) over each level's larger half of sizes (1: O(N), 2: O(N^2));\n"
               "a level stops after the first size above %g ms per step; others: cores that other processes kept\n"
               "busy while the level was measured.\n\n",
               max_ms);
    }
    if (ok) {
        char name[64];
        snprintf(name, sizeof name, "scaling-%s.csv", dim_tag(dim));
        FILE *f = plot_out_stage_csv(o->out, name);
        ok = f != NULL;
        if (f) {
            fprintf(f, "level,description,threads,n,ms_per_step,steps_per_s,pairs_per_step,others_cores\n");
            for (int s = 0; s < o->nsel; s++) {
                char about[128];
                snprintf(about, sizeof about, "%s", bench_levels[o->sel[s]].about);
                for (char *c = about; *c; c++)
                    if (*c == ',' || *c == '"') *c = ';';
                for (int i = 0; i < cnt[s]; i++) {
                    fprintf(f, "%s,%s,%d,%.0f,%.6g,%.6g", bench_levels[o->sel[s]].name, about, thr[s], N[s * nk + i],
                            MS[s * nk + i], 1000.0 / MS[s * nk + i]);
                    csv_num(f, PR[s * nk + i], "%.0f"); /* empty for a GL level: no lists */
                    fprintf(f, ",%.3f\n", others[s]);
                }
            }
            ok &= plot_out_close_csv(f, o->out, name);
        }
    }
    if (ok) {
        static bench_scaling_chart c;
        memset(&c, 0, sizeof c);
        snprintf(c.title, sizeof c.title, "Time per step against N, %dD, each level of the ladder", dim);
        snprintf(c.subtitle, sizeof c.subtitle, "%s   load %.2f   median of repeats", date, load0[0]);
        c.fps = 60;
        c.ns = o->nsel;
        for (int s = 0; s < o->nsel; s++) {
            snprintf(c.s[s].label, sizeof c.s[s].label, "%s %.42s", bench_levels[o->sel[s]].name,
                     bench_levels[o->sel[s]].about);
            c.s[s].n = N + s * nk;
            c.s[s].ms = MS + s * nk;
            c.s[s].count = (size_t)cnt[s];
        }
        char name[64];
        snprintf(name, sizeof name, "scaling-%s", dim_tag(dim));
        ok &= bench_chart_scaling(&c, o->out, name);
    }
    if (ok)
        ok = plot_out_commit(o->quiet);
    else
        plot_out_abort();
    free(N);
    free(MS);
    free(PR);
    free(cnt);
    free(thr);
    return ok ? 0 : 1;
}

/* ---- machine, levels ------------------------------------------------------------------ */

static int cmd_machine(bench_opts *o)
{
    char date[64];
    double load0[3], load1[3];
    bench_now_iso(date, sizeof date);
    bench_loadavg(load0);
    progress("measuring the clock, FMA throughput and memory bandwidth ...");
    bench_machine m;
    bench_machine_measure(&m, o->quick);
    progress_done();
    bench_loadavg(load1);
    if (!o->quiet) {
        printf("sphlab bench machine: %s, load %.2f at the start, %.2f at the end\n\n", date, load0[0], load1[0]);
        bench_machine_print(stdout, &m);
        printf("\n");
    }
    if (!plot_out_dir(o->out)) return 1;
    FILE *f = plot_out_stage_csv(o->out, "machine.json");
    if (!f) return 1;
    fputs("{\n  \"date\": ", f);
    bench_json_string(f, date);
    fputs(",\n  \"load_start\": ", f);
    write_load(f, load0);
    fputs(",\n  \"load_end\": ", f);
    write_load(f, load1);
    fputs(",\n  \"machine\": ", f);
    bench_machine_json(f, &m, "  ");
    fputs("\n}\n", f);
    bool ok = plot_out_close_csv(f, o->out, "machine.json");
    if (ok)
        ok = plot_out_commit(o->quiet);
    else
        plot_out_abort();
    return ok ? 0 : 1;
}

static int cmd_levels(const bench_opts *o)
{
    printf("%-5s %-42s %-8s %s\n", "level", "description", "threads", "scene keys");
    for (int s = 0; s < o->nsel; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        char t[16];
        snprintf(t, sizeof t, "%d", L->threads);
        printf("%-5s %-42s %-8s %s\n", L->name, L->about, bench_level_gl(L) ? "device" : L->threads > 0 ? t : "cores",
               L->sets);
    }
    char ini[2048];
    bench_scene_ini(o->cfg.dim, bench_k_near(o->cfg.dim, 1000), BENCH_JITTER, ini, sizeof ini);
    printf("\nThe scene (here N = %.0f; the benchmark changes the block's size and the box with it; the checks\n"
           "run it with jitter = %g, so that no pair sits exactly at r = h):\n\n%s",
           bench_count(o->cfg.dim, bench_k_near(o->cfg.dim, 1000)), BENCH_CHECK_JITTER, ini);
    return 0;
}

int cmd_bench(int argc, char **argv)
{
    static bench_opts o;
    memset(&o, 0, sizeof o);
    g_opts = &o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) return rc;
    if (strcmp(o.what, "ladder") == 0) return cmd_ladder(&o, argc, argv);
    if (strcmp(o.what, "scaling") == 0) return cmd_scaling(&o);
    if (strcmp(o.what, "machine") == 0) return cmd_machine(&o);
    if (strcmp(o.what, "levels") == 0) return cmd_levels(&o);
    fprintf(stderr, "sphlab bench: unknown benchmark '%s' (ladder, scaling, machine, levels)\n", o.what);
    return 2;
}
