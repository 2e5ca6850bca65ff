/* sphlab bench ladder, the report: the table on stdout, and the CSV, the
 * JSON and the chart in DIR, from what bench_ladder.c measured. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cmd.h"
#include "plot.h"
#include "../io/io_json.h"

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

const char *bench_check_word(const level_result *r)
{
    if (r->skipped) return "SKIP";
    if (!r->small.done && !r->large.done) return "-";
    return r->check_ok ? "PASS" : "FAIL";
}

/* Passes with a counted flop figure (bench_flops.c): the neighbours pass and the pair passes. */
static bool counted_pass(int p)
{
    return p == SPH_PASS_NEIGHBOURS || p == SPH_PASS_DENSITY || p == SPH_PASS_PRESSURE_FORCE ||
           p == SPH_PASS_VISCOSITY;
}

/* The pair passes' counted flops in one step, NAN if none. */
static double force_flops(const level_result *r)
{
    double sum = 0;
    bool any = false;
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (counted_pass(p) && p != SPH_PASS_NEIGHBOURS && isfinite(r->flops[p])) sum += r->flops[p], any = true;
    return any ? sum : NAN;
}

/* A pass's counted flops over its own median time [GFLOP/s]; NAN if none or if it took no time. */
static double pass_gflops(const level_result *r, int p)
{
    double ms = r->at.pass_ms[p];
    return isfinite(r->flops[p]) && ms > 0 && r->flops[p] > 0 ? r->flops[p] / (ms * 1e6) : NAN;
}

void bench_csv_num(FILE *f, double v, const char *fmt)
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
               "max_dx_at_m,max_dv_at_m_s,max_drho_at,others_cores,peak_rss_bytes_per_particle,search_candidates,"
               "search_gflop_per_step,search_gflops,search_peak_share,force_gflop_per_step,force_gflops,"
               "force_peak_share,peak_gflops");
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (pass_used[p]) fprintf(f, ",%s_ms", sph_passes[p]->name);
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (pass_used[p] && counted_pass(p)) fprintf(f, ",%s_gflop_per_step,%s_gflops", sph_passes[p]->name,
                                                     sph_passes[p]->name);
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
        bench_csv_num(f, r->searched ? r->max_n : NAN, "%.0f");
        fprintf(f, ",%d", r->capped ? 1 : 0);
        bench_csv_num(f, r->searched ? r->rate_at_max : NAN, "%.4g");
        bench_csv_num(f, s > 0 && prev > 0 && r->searched ? r->max_n / prev : NAN, "%.4g");
        prev = r->searched ? r->max_n : NAN;
        bench_csv_num(f, r->at_ok ? (double)r->at.n : NAN, "%.0f");
        bench_csv_num(f, r->at_ok ? r->at.ms_step : NAN, "%.6g");
        bench_csv_num(f, r->at_ok ? r->at.pairs : NAN, "%.0f");
        bench_csv_num(f, r->at_ok ? r->search_ms : NAN, "%.6g");
        bench_csv_num(f, r->at_ok ? r->force_ms : NAN, "%.6g");
        bench_csv_num(f, r->at_ok ? r->search_rate : NAN, "%.4g");
        bench_csv_num(f, r->at_ok ? r->force_rate : NAN, "%.4g");
        fprintf(f, ",%s", bench_check_word(r));
        fprintf(f, ",%s", r->small.done ? bench_levels[r->small.ref].name : "");
        bench_csv_num(f, r->small.done ? n_check : NAN, "%.0f");
        bench_csv_num(f, r->small.done ? (double)r->small.sets_differ : NAN, "%.0f");
        bench_csv_num(f, r->small.done ? (double)r->small.edge_pairs : NAN, "%.0f");
        bench_csv_num(f, r->small.done ? r->small.dx : NAN, "%.3g");
        bench_csv_num(f, r->small.done ? r->small.dv : NAN, "%.3g");
        bench_csv_num(f, r->small.done ? r->small.drho : NAN, "%.3g");
        fprintf(f, ",%s", r->large.done ? bench_levels[r->large.ref].name : "");
        bench_csv_num(f, r->large.done ? n_at : NAN, "%.0f");
        bench_csv_num(f, r->large.done ? (double)r->large.sets_differ : NAN, "%.0f");
        bench_csv_num(f, r->large.done ? (double)r->large.edge_pairs : NAN, "%.0f");
        bench_csv_num(f, r->large.done ? r->large.dx : NAN, "%.3g");
        bench_csv_num(f, r->large.done ? r->large.dv : NAN, "%.3g");
        bench_csv_num(f, r->large.done ? r->large.drho : NAN, "%.3g");
        bench_csv_num(f, r->others, "%.3f");
        bench_csv_num(f, r->at_ok && r->at.n ? r->at.peak_rss / r->at.n : NAN, "%.1f");
        bench_csv_num(f, r->at_ok ? r->at.candidates : NAN, "%.0f");
        bench_csv_num(f, r->at_ok ? r->flops[SPH_PASS_NEIGHBOURS] / 1e9 : NAN, "%.6g");
        bench_csv_num(f, r->at_ok ? r->search_gflops : NAN, "%.4g");
        bench_csv_num(f, r->at_ok ? r->search_gflops / r->peak_gflops : NAN, "%.4g");
        bench_csv_num(f, r->at_ok ? force_flops(r) / 1e9 : NAN, "%.6g");
        bench_csv_num(f, r->at_ok ? r->force_gflops : NAN, "%.4g");
        bench_csv_num(f, r->at_ok ? r->force_gflops / r->peak_gflops : NAN, "%.4g");
        bench_csv_num(f, r->at_ok ? r->peak_gflops : NAN, "%.4g");
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (pass_used[p]) bench_csv_num(f, r->at_ok ? r->at.pass_ms[p] : NAN, "%.6g");
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (pass_used[p] && counted_pass(p)) {
                bench_csv_num(f, r->at_ok ? r->flops[p] / 1e9 : NAN, "%.6g");
                bench_csv_num(f, r->at_ok ? pass_gflops(r, p) : NAN, "%.4g");
            }
        fputc('\n', f);
    }
}

/* A cJSON call's result: a NULL (out of memory) clears *ok. */
static cJSON *json_ok(bool *ok, cJSON *item)
{
    if (!item) *ok = false;
    return item;
}

/* V with DECIMALS decimals, as "%.Nf" printed it (counts: 0), or null. */
static bool json_fixed(cJSON *o, const char *key, double v, int decimals)
{
    return cJSON_AddNumberToObject(o, key, bench_round_fixed(v, decimals)) != NULL;
}

/* A check against a reference: null when it did not run. */
static bool json_diff(cJSON *lv, const char *key, const bench_diff *d, double n)
{
    if (!d->done) return cJSON_AddNullToObject(lv, key) != NULL;
    bool ok = true;
    cJSON *o = json_ok(&ok, cJSON_AddObjectToObject(lv, key));
    json_ok(&ok, cJSON_AddStringToObject(o, "reference", bench_levels[d->ref].name));
    ok &= json_fixed(o, "n", n, 0);
    json_ok(&ok, cJSON_AddBoolToObject(o, "pass", d->pass));
    json_ok(&ok, cJSON_AddNumberToObject(o, "sets_differ", d->sets_differ));
    json_ok(&ok, cJSON_AddNumberToObject(o, "edge_pairs", d->edge_pairs));
    ok &= json_fixed(o, "pairs", d->pairs, 0);
    ok &= json_fixed(o, "reference_pairs", d->ref_pairs, 0);
    ok &= sph_json_add_num(o, "max_dx_m", d->dx, 3);
    ok &= sph_json_add_num(o, "max_dv_m_s", d->dv, 3);
    ok &= sph_json_add_num(o, "max_drho", d->drho, 3);
    json_ok(&ok, cJSON_AddStringToObject(o, "why", d->why));
    return ok;
}

/* A target: what it asks, the level that came closest, whether it was met (null: not evaluated). */
static bool json_target(cJSON *root, const char *key, double n, const bench_opts *o, const level_result *res, int best,
                        bool evaluated, bool met)
{
    bool ok = true;
    cJSON *t = json_ok(&ok, cJSON_AddObjectToObject(root, key));
    json_ok(&ok, cJSON_AddNumberToObject(t, "dim", 3));
    json_ok(&ok, cJSON_AddNumberToObject(t, "fps", 60));
    json_ok(&ok, cJSON_AddNumberToObject(t, "n", n));
    if (best >= 0) {
        json_ok(&ok, cJSON_AddStringToObject(t, "best_level", bench_levels[o->sel[best]].name));
        ok &= json_fixed(t, "best_n", res[best].max_n, 0);
    }
    json_ok(&ok, evaluated ? cJSON_AddBoolToObject(t, "met", met) : cJSON_AddNullToObject(t, "met"));
    return ok;
}

/* One level's entry of "levels". */
static bool json_level(cJSON *levels, const bench_opts *o, const level_result *res, const ladder_meta *m, int s,
                       double prev)
{
    const bench_level *L = &bench_levels[o->sel[s]];
    const level_result *r = &res[s];
    bool ok = true;
    cJSON *lv = json_ok(&ok, cJSON_CreateObject());
    if (lv && !cJSON_AddItemToArray(levels, lv)) {
        cJSON_Delete(lv);
        return false;
    }
    json_ok(&ok, cJSON_AddStringToObject(lv, "level", L->name));
    json_ok(&ok, cJSON_AddStringToObject(lv, "description", L->about));
    json_ok(&ok, cJSON_AddStringToObject(lv, "sets", L->sets));
    json_ok(&ok, cJSON_AddStringToObject(lv, "backend", bench_level_gl(L) ? "gl" : "cpu"));
    json_ok(&ok, cJSON_AddNumberToObject(lv, "threads", r->at.threads ? r->at.threads : L->threads));
    ok &= json_fixed(lv, "max_n", r->searched ? r->max_n : NAN, 0);
    json_ok(&ok, cJSON_AddBoolToObject(lv, "capped", r->capped));
    ok &= sph_json_add_num(lv, "steps_per_s_at_max", r->searched ? r->rate_at_max : NAN, 4);
    ok &= sph_json_add_num(lv, "speedup", s > 0 && prev > 0 && r->searched ? r->max_n / prev : NAN, 4);
    ok &= json_fixed(lv, "n_at", r->at_ok ? (double)r->at.n : NAN, 0);
    ok &= sph_json_add_num(lv, "ms_per_step", r->at_ok ? r->at.ms_step : NAN, 6);
    ok &= json_fixed(lv, "pairs_per_step", r->at_ok ? r->at.pairs : NAN, 0);
    ok &= json_fixed(lv, "peak_rss_bytes_per_particle", r->at_ok && r->at.n ? r->at.peak_rss / r->at.n : NAN, 1);
    ok &= sph_json_add_num(lv, "search_pairs_per_s_core", r->at_ok ? r->search_rate : NAN, 4);
    ok &= sph_json_add_num(lv, "force_pairs_per_s_core", r->at_ok ? r->force_rate : NAN, 4);
    ok &= json_fixed(lv, "other_processes_cores", r->others, 3);
    ok &= json_fixed(lv, "at_other_processes_cores", r->at_ok ? r->at.others : NAN, 3);
    json_ok(&ok, cJSON_AddNumberToObject(lv, "measurements", r->measurements));
    cJSON *pass = json_ok(&ok, cJSON_AddObjectToObject(lv, "pass_ms"));
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (r->at_ok && isfinite(r->at.pass_ms[p])) ok &= sph_json_add_num(pass, sph_passes[p]->name, r->at.pass_ms[p], 6);
    ok &= json_fixed(lv, "search_candidates", r->at_ok ? r->at.candidates : NAN, 0);
    ok &= sph_json_add_num(lv, "search_gflops", r->at_ok ? r->search_gflops : NAN, 4);
    ok &= sph_json_add_num(lv, "search_peak_share", r->at_ok ? r->search_gflops / r->peak_gflops : NAN, 4);
    ok &= sph_json_add_num(lv, "force_gflops", r->at_ok ? r->force_gflops : NAN, 4);
    ok &= sph_json_add_num(lv, "force_peak_share", r->at_ok ? r->force_gflops / r->peak_gflops : NAN, 4);
    ok &= sph_json_add_num(lv, "peak_gflops", r->at_ok ? r->peak_gflops : NAN, 4);
    /* per counted pass: flops in one step, flops per list entry or per candidate, GFLOP/s */
    cJSON *pf = json_ok(&ok, cJSON_AddObjectToObject(lv, "pass_flops"));
    for (int p = 0; p < SPH_PASS_COUNT && pf; p++) {
        if (!r->at_ok || !counted_pass(p) || !isfinite(r->at.pass_ms[p])) continue;
        cJSON *e = json_ok(&ok, cJSON_AddObjectToObject(pf, sph_passes[p]->name));
        if (!e) break;
        bool search = p == SPH_PASS_NEIGHBOURS;
        json_ok(&ok, cJSON_AddStringToObject(e, "per", search ? "candidate" : "list entry"));
        ok &= sph_json_add_num(e, "flops_per", search ? bench_flops_per_candidate()
                                                      : bench_flops_per_entry(p, r->at.fused), 4);
        ok &= json_fixed(e, "flops_per_step", r->flops[p], 0);
        ok &= sph_json_add_num(e, "gflops", pass_gflops(r, p), 4);
        ok &= sph_json_add_num(e, "peak_share", pass_gflops(r, p) / r->peak_gflops, 4);
    }
    json_ok(&ok, cJSON_AddStringToObject(lv, "check", bench_check_word(r)));
    ok &= json_diff(lv, "check_small", &r->small, m->n_check);
    ok &= json_diff(lv, "check_at", &r->large, m->n_at);
    json_ok(&ok, cJSON_AddStringToObject(lv, "error", r->error));
    return ok;
}

/* The ladder's JSON (the caller deletes it), NULL if out of memory. */
static cJSON *ladder_json(const bench_opts *o, const level_result *res, const ladder_meta *m, int argc, char **argv)
{
    bool ok = true;
    cJSON *root = json_ok(&ok, cJSON_CreateObject());
    char cmd[1024] = "sphlab";
    for (int i = 0; i < argc; i++) {
        size_t len = strlen(cmd);
        snprintf(cmd + len, sizeof cmd - len, " %s", argv[i]);
    }
    json_ok(&ok, cJSON_AddStringToObject(root, "command", cmd));
    json_ok(&ok, cJSON_AddStringToObject(root, "date", m->date));
    json_ok(&ok, cJSON_AddNumberToObject(root, "dim", o->cfg.dim));
    ok &= sph_json_add_num(root, "fps", o->fps, 6);
    json_ok(&ok, cJSON_AddBoolToObject(root, "quick", o->quick));
    json_ok(&ok, cJSON_AddBoolToObject(root, "watchdog", o->cfg.watchdog));
    ok &= bench_json_add_load(root, "load_start", m->load0);
    ok &= bench_json_add_load(root, "load_end", m->load1);
    ok &= json_fixed(root, "seconds", m->seconds, 1);
    ok &= json_fixed(root, "other_processes_cores", m->others, 3);
    ok &= json_fixed(root, "clock_ghz_start", m->ghz0, 3);
    ok &= json_fixed(root, "clock_ghz_end", m->ghz1, 3);
    cJSON *mj = bench_machine_to_json(&m->machine); /* the quick measurement the peak shares use */
    if (!mj || !cJSON_AddItemToObject(root, "machine", mj)) {
        cJSON_Delete(mj);
        ok = false;
    }
    sph_scene_def def, cdef;
    char why[256];
    if (bench_scene_def(&o->cfg, NULL, bench_k_near(o->cfg.dim, m->n_at), false, &def, why, sizeof why) &&
        bench_scene_def(&o->cfg, NULL, bench_k_near(o->cfg.dim, m->n_at), true, &cdef, why, sizeof why)) {
        cJSON *sc = json_ok(&ok, cJSON_AddObjectToObject(root, "scene"));
        json_ok(&ok, cJSON_AddStringToObject(sc, "what", "a block of water falling in a box twice its size"));
        ok &= sph_json_add_num(sc, "spacing_m", def.blocks[0].spacing, 6);
        ok &= sph_json_add_num(sc, "h_m", def.h, 6);
        ok &= sph_json_add_num(sc, "jitter_spacings", def.jitter, 6);
        ok &= sph_json_add_num(sc, "check_jitter_spacings", cdef.jitter, 6);
        ok &= sph_json_add_num(sc, "stiffness", def.stiffness, 6);
        ok &= sph_json_add_num(sc, "viscosity", def.viscosity, 6);
        ok &= sph_json_add_num(sc, "cfl", def.cfl, 6);
    }
    cJSON *sets = json_ok(&ok, cJSON_AddArrayToObject(root, "sets"));
    for (int i = 0; i < o->cfg.n_sets; i++) {
        char set[300];
        snprintf(set, sizeof set, "%s%s%s", o->cfg.set_level[i] ? o->cfg.set_level[i] : "",
                 o->cfg.set_level[i] ? ":" : "", o->cfg.set[i]);
        cJSON *str = json_ok(&ok, cJSON_CreateString(set));
        if (str && !cJSON_AddItemToArray(sets, str)) {
            cJSON_Delete(str);
            ok = false;
        }
    }
    ok &= json_fixed(root, "n_at", m->n_at, 0);
    ok &= json_fixed(root, "n_check", m->n_check, 0);
    cJSON *tol = json_ok(&ok, cJSON_AddObjectToObject(root, "tolerances"));
    json_ok(&ok, cJSON_AddNumberToObject(tol, "steps", BENCH_CHECK_STEPS));
    ok &= sph_json_add_num(tol, "dx_m", BENCH_TOL_X, 6);
    ok &= sph_json_add_num(tol, "dv_m_s", BENCH_TOL_V, 6);
    ok &= sph_json_add_num(tol, "drho", BENCH_TOL_RHO, 6);
    json_ok(&ok, cJSON_AddStringToObject(tol, "neighbour_sets", "identical after 1 step"));
    ok &= sph_json_add_num(tol, "edge_pairs_within_h_times", BENCH_EDGE, 6);
    ok &= json_target(root, "target", 60000, o, res, m->best, m->target_evaluated, m->target_met);
    json_ok(&ok, m->gl_device[0] ? cJSON_AddStringToObject(root, "gl_device", m->gl_device)
                                 : cJSON_AddNullToObject(root, "gl_device"));
    json_ok(&ok, m->gl_timing ? cJSON_AddStringToObject(root, "gl_pass_timing", m->gl_timing)
                              : cJSON_AddNullToObject(root, "gl_pass_timing"));
    ok &= json_target(root, "gl_target", 1000000, o, res, m->gl_best, m->gl_target_evaluated, m->gl_target_met);
    json_ok(&ok, cJSON_AddBoolToObject(root, "all_checks_pass", m->all_pass));
    cJSON *levels = json_ok(&ok, cJSON_AddArrayToObject(root, "levels"));
    double prev = NAN;
    for (int s = 0; s < o->nsel && ok; s++) {
        ok &= json_level(levels, o, res, m, s, prev);
        prev = res[s].searched ? res[s].max_n : NAN;
    }
    if (ok) return root;
    cJSON_Delete(root);
    return NULL;
}

void bench_ladder_print(FILE *out, const bench_opts *o, const bench_ladder *lad)
{
    const int dim = o->cfg.dim, gl_state = lad->gl_state, k_at = lad->k_at, k_check = lad->k_check;
    const double fps = o->fps;
    const level_result *res = lad->res;
    const ladder_meta meta = lad->meta;
    const bool all_pass = lad->all_pass;
    {
        char nat[32], nchk[32];
        bench_fmt_count(nat, sizeof nat, meta.n_at);
        bench_fmt_count(nchk, sizeof nchk, meta.n_check);
        fprintf(out, "sphlab bench ladder: %dD block of water falling in a box, h = 2 spacings, target %g steps/s%s\n", dim,
               fps, o->quick ? " (--quick)" : "");
        fprintf(out, "%s, load %.2f at the start, %.2f at the end, %.0f s\n", meta.date, meta.load0[0], meta.load1[0],
               meta.seconds);
        fprintf(out, "other processes kept %.2f of the %d cores busy on average while it ran; one core's clock %.2f GHz\n"
               "at the start, %.2f at the end (lower when the host is busy)\n",
               meta.others, bench_levels_cores(), meta.ghz0, meta.ghz1);
        if (meta.gl_ran) {
            fprintf(out, "GL levels (G*): %s%s\n", meta.gl_device,
                   meta.gl_is_gpu ? "" : " (software rendering on this CPU: a correctness device, not a GPU)");
            if (meta.gl_timing) fprintf(out, "GL pass times: %s\n", meta.gl_timing);
        }
        else if (gl_state < 0)
            fprintf(out, "GL levels (G*) skipped: no OpenGL 4.3 device: %s\n", meta.gl_device);
        double worst = 0;
        for (int s = 0; s < o->nsel; s++) worst = fmax(worst, res[s].others);
        if (worst > 0.2)
            fprintf(out, "warning: the machine was busy (others: up to %.2f cores during a level, column 'others'): timings\n"
                   "are low and noisy, the threaded levels worst (a parallel region waits for its slowest thread);\n"
                   "re-run when quiet\n",
                   worst);
        fprintf(out, "\n");
        fprintf(out, "%-5s %-42s %3s %12s %8s %10s  %-44s %-5s %s\n", "level", "description", "thr", "max N", "speedup",
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
            fprintf(out, "%-5s %-42s %3d %12s %8s %10s  %-44s %-5s %.2f\n", L->name, L->about,
                   r->at.threads ? r->at.threads : L->threads, maxn, sp, ms, top, bench_check_word(r), r->others);
        }
        char capn[32];
        bench_fmt_count(capn, sizeof capn, o->quick ? BENCH_MAX_N_QUICK : BENCH_MAX_N);
        fprintf(out, "\nmax N: the largest block with %g steps/s or more (bisection over block sizes, median of repeats;\n"
               "none: not even the smallest block reached it on this machine, which is no failure;\n"
               "+: the search stopped at its largest size, %s with %s, which the level reached);\n"
               "ms/step and passes: medians at N = %s (with Verlet lists, L10 on, the median step builds no lists:\n"
               "max N counts every step, builds included); others: cores that other processes kept busy meanwhile\n",
               fps, capn, o->quick ? "--quick" : "the full bench", nat);
        fprintf(out, "\nwhere the time goes at N = %s (pairs: neighbour-list entries per step, i->j and j->i):\n", nat);
        fprintf(out, "%-5s %12s %10s %12s %7s %6s %10s %12s %7s %6s %8s\n", "level", "pairs", "search ms",
                "pairs/s/core", "GFLOP/s", "%peak", "forces ms", "pairs/s/core", "GFLOP/s", "%peak", "peak B/N");
        for (int s = 0; s < o->nsel; s++) {
            const level_result *r = &res[s];
            if (!r->at_ok) continue;
            if (r->at.pairs > 0)
            {
                char sg[16] = "-", sp[16] = "-", fg[16] = "-", fp[16] = "-";
                if (isfinite(r->search_gflops)) snprintf(sg, sizeof sg, "%.3g", r->search_gflops);
                if (isfinite(r->search_gflops / r->peak_gflops))
                    snprintf(sp, sizeof sp, "%.2g", 100 * r->search_gflops / r->peak_gflops);
                if (isfinite(r->force_gflops)) snprintf(fg, sizeof fg, "%.3g", r->force_gflops);
                if (isfinite(r->force_gflops / r->peak_gflops))
                    snprintf(fp, sizeof fp, "%.2g", 100 * r->force_gflops / r->peak_gflops);
                fprintf(out, "%-5s %12.0f %10.3f %12.3g %7s %6s %10.3f %12.3g %7s %6s %8.0f\n",
                        bench_levels[o->sel[s]].name, r->at.pairs, r->search_ms, r->search_rate, sg, sp, r->force_ms,
                        r->force_rate, fg, fp, r->at.peak_rss / r->at.n);
            }
            else /* a GL level: no lists, its passes walk the cells */
                fprintf(out, "%-5s %12s %10.3f %12s %7s %6s %10.3f %12s %7s %6s %8.0f\n", bench_levels[o->sel[s]].name,
                        "-", r->search_ms, "-", "-", "-", r->force_ms, "-", "-", "-", r->at.peak_rss / r->at.n);
        }
        fprintf(out, "search: hash, sort, reorder, offsets, neighbours; forces: density, pressure_force, viscosity\n"
                "GFLOP/s: counted flops over the time (search: %g per candidate of the 3^d cells, not counted with\n"
                "Verlet lists, built on some steps only; forces: %g, %g and %g per list entry, the square root and\n"
                "the division one each: src/bench/bench_flops.c); %%peak: of the FMA loop's measured %.3g GFLOP/s\n"
                "on 1 core, %.3g on %d (`sphlab bench machine --quick`, at the start)\n",
                bench_flops_per_candidate(), bench_flops_per_entry(SPH_PASS_DENSITY, false),
                bench_flops_per_entry(SPH_PASS_PRESSURE_FORCE, false), bench_flops_per_entry(SPH_PASS_VISCOSITY, false),
                meta.machine.fma_gflops[0], meta.machine.fma_gflops[1], meta.machine.cores);
        fprintf(out, "(GL levels build no lists: density and the forces walk the cells themselves, so no pair count)\n"
               "peak B/N: the process's peak resident size (getrusage) over N, after the level's timed steps: a\n"
               "bound on the level's bytes per particle (it includes what earlier levels and checks touched: at a\n"
               "small N it is the process's fixed size over N, the same for every level; run one level at a large\n"
               "--at)\n"
               "ms/step: the median of sph_sim_step's wall time (the passes, the watchdog's checks and what lies\n"
               "between them); the chart stacks each pass's own median, less on a busy machine\n");
        fprintf(out, "\nchecks: neighbour sets identical after 1 step (a pair within %g h of r = h is rounding's call and\n"
               "counted apart: edge pairs), and after %d steps positions within %g m, velocities within %g m/s,\n"
               "densities within %g (relative), particles matched by id; against %s at N = %s",
               BENCH_EDGE, BENCH_CHECK_STEPS, BENCH_TOL_X, BENCH_TOL_V, BENCH_TOL_RHO, BENCH_REF_SMALL, nchk);
        if (k_at > k_check) fprintf(out, " and against %s at N = %s", BENCH_REF_LARGE, nat);
        bool ref_small_run = false; /* said only where it ran (it was said of runs without L0) */
        for (int s = 0; s < o->nsel; s++) ref_small_run |= strcmp(bench_levels[o->sel[s]].name, BENCH_REF_SMALL) == 0;
        if (ref_small_run)
            fprintf(out, " (%s itself against %s).\n", BENCH_REF_SMALL, BENCH_REF_LARGE);
        else
            fprintf(out, ".\n");
        for (int s = 0; s < o->nsel; s++) {
            const level_result *r = &res[s];
            const bench_diff *d[2] = {&r->small, &r->large};
            for (int j = 0; j < 2; j++)
                if (d[j]->done)
                    fprintf(out, "  %-4s vs %-3s N = %-7.0f %s  sets differ %u (edge pairs %u), dx %.2g m, dv %.2g m/s, "
                           "drho %.2g%s%s\n",
                           bench_levels[o->sel[s]].name, bench_levels[d[j]->ref].name, j ? meta.n_at : meta.n_check,
                           d[j]->pass ? "PASS" : "FAIL", d[j]->sets_differ, d[j]->edge_pairs, d[j]->dx, d[j]->dv,
                           d[j]->drho, d[j]->why[0] ? ": " : "", d[j]->why);
            if (r->skipped)
                fprintf(out, "  %-4s skipped: %s\n", bench_levels[o->sel[s]].name, r->error);
            else if (r->error[0] && !r->check_ok)
                fprintf(out, "  %-4s error: %s\n", bench_levels[o->sel[s]].name, r->error);
        }
        if (meta.target_evaluated) {
            char bn[32];
            bench_fmt_count(bn, sizeof bn, res[meta.best].max_n);
            /* the seed's record (a GTX 1060) and the next mark for two CPU cores */
            const bool capped = res[meta.best].capped;
            fprintf(out, "\nthe seed's record, 60,000 particles at 60 steps/s in 3D, on the fastest CPU level: %s "
                   "(%s: %s%s)\n",
                   meta.target_met ? "MET" : "NOT MET", bench_levels[o->sel[meta.best]].name, bn, capped ? "+" : "");
            if (capped && res[meta.best].max_n < 250000) /* the search stopped below the mark: nothing said of it */
                fprintf(out, "the next mark, 250,000 particles at 60 steps/s in 3D: not evaluated (the search stops at "
                        "%s%s, which %s reached)\n", capn, o->quick ? " with --quick" : "",
                        bench_levels[o->sel[meta.best]].name);
            else
                fprintf(out, "the next mark, 250,000 particles at 60 steps/s in 3D: %s\n",
                        res[meta.best].max_n >= 250000 ? "MET" : "NOT MET");
        } else {
            fprintf(out, "\nthe seed's record (60,000 particles at 60 steps/s in 3D): not evaluated with these options\n");
        }
        if (meta.gl_best >= 0 && dim == 3 && fabs(fps - 60) < 1e-9) {
            char bn[32];
            bench_fmt_count(bn, sizeof bn, res[meta.gl_best].max_n);
            if (meta.gl_target_evaluated)
                fprintf(out, "GPU target: a GL level reaches 1,000,000 particles at 60 steps/s in 3D: %s "
                       "(%s: %s)\n",
                       meta.gl_target_met ? "MET" : "NOT MET", bench_levels[o->sel[meta.gl_best]].name, bn);
            else
                fprintf(out, "GPU target (1,000,000 at 60 steps/s): not evaluated, no GPU here (%s: %s on "
                       "software rendering)\n",
                       bench_levels[o->sel[meta.gl_best]].name, bn);
        }
        if (!all_pass) fprintf(out, "\nFAIL: a level failed its check; its speed does not count\n");
        fprintf(out, "\n");
    }
}

bool bench_ladder_write(const bench_opts *o, const bench_ladder *lad, int argc, char **argv)
{
    const int dim = o->cfg.dim;
    const double fps = o->fps;
    const level_result *res = lad->res;
    const ladder_meta meta = lad->meta;
    const bool all_pass = lad->all_pass, *pass_used = lad->pass_used;
    bool ok = true;
    char name[64];
    snprintf(name, sizeof name, "ladder-%s.csv", bench_dim_tag(dim));
    FILE *f = plot_out_stage_csv(o->out, name);
    if (!f) ok = false;
    if (f) {
        write_ladder_csv(f, o, res, pass_used, meta.n_at, meta.n_check);
        ok &= plot_out_close_csv(f, o->out, name);
    }
    snprintf(name, sizeof name, "ladder-%s.json", bench_dim_tag(dim));
    f = ok ? plot_out_stage_csv(o->out, name) : NULL;
    if (ok && !f) ok = false;
    if (f) {
        cJSON *root = ladder_json(o, res, &meta, argc, argv);
        bool put = root && sph_json_fput(f, root, 0) && fputc('\n', f) != EOF;
        cJSON_Delete(root);
        if (!put) fprintf(stderr, "sphlab bench: %s/%s: cannot write the JSON (out of memory or a write error)\n", o->out, name);
        ok &= plot_out_close_csv(f, o->out, name) && put;
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
        snprintf(c.stack_title, sizeof c.stack_title, "the passes' medians at N = %s, stacked (ms)", nat);
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
        snprintf(name, sizeof name, "ladder-%s", bench_dim_tag(dim));
        ok &= bench_chart_ladder(&c, o->out, name);
    }
    if (ok)
        ok = plot_out_commit(o->quiet);
    else
        plot_out_abort();
    return ok;
}
