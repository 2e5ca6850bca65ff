/* sphlab bench ladder, the measurements: per level, the checks against the
 * reference levels first, then the largest N that runs at F steps/s
 * (doublings, then bisection over block sizes), then ms per pass at a fixed
 * N. bench_report.c prints and writes what this measures. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cmd.h"
#include "gpu.h"
#include "plot.h"
#include "../io/io.h"

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
        bench_progress("%s %s: N = %.0f ...", L->name, L->about, bench_count(dim, k));
        if (!bench_measure_retry(&o->cfg, L, k, plan, o->fps, o->quick ? 2 : 3, &m, why, sizeof why)) {
            snprintf(r->error, sizeof r->error, "%s", why);
            return false;
        }
        r->measurements += m.attempts;
        bench_trace(L, &m, "grow");
        bench_progress("%s %s: N = %.0f: %.1f steps/s", L->name, L->about, bench_count(dim, k), m.steps_per_s);
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
        bench_progress("%s %s: N = %.0f ...", L->name, L->about, bench_count(dim, mid));
        if (!bench_measure_retry(&o->cfg, L, mid, plan, o->fps, o->quick ? 2 : 3, &m, why, sizeof why)) {
            snprintf(r->error, sizeof r->error, "%s", why);
            return false;
        }
        r->measurements += m.attempts;
        bench_trace(L, &m, "bisect");
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

void bench_level_flops(level_result *r, const bench_machine *m)
{
    bench_pass_flops(&r->at, r->flops);
    double force = 0;
    bool any = false;
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (is_pair_pass(p) && isfinite(r->flops[p])) force += r->flops[p], any = true;
    double search = r->flops[SPH_PASS_NEIGHBOURS];
    r->search_gflops = r->search_ms > 0 && isfinite(search) ? search / (r->search_ms * 1e6) : NAN;
    r->force_gflops = r->force_ms > 0 && any ? force / (r->force_ms * 1e6) : NAN;
    /* the FMA loop's throughput on as many threads as the level ran */
    int t = r->at.threads > 0 ? r->at.threads : 1;
    r->peak_gflops = t >= m->cores ? m->fma_gflops[1] : t * m->fma_gflops[0];
    if (!(r->peak_gflops > 0)) r->peak_gflops = NAN;
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
        bench_progress("reference %s at N = %.0f: %d steps ...", bench_levels[c->level].name, bench_count(o->cfg.dim, c->k),
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
    bench_progress("%s check against %s at N = %.0f ...", bench_levels[Li].name, bench_levels[ref->level].name,
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

/* Whether level Li takes the --set keys: its scene validates and a
 * simulation of the smallest block is made (a GL level only where a device
 * is, *gl_state as in bench_ladder_measure). Otherwise says why, naming the
 * level, and how to give a key to some levels only. */
static bool level_takes_the_sets(const bench_opts *o, int Li, int *gl_state, char *gl_device, size_t gl_n)
{
    const bench_level *L = &bench_levels[Li];
    char why[sizeof(sph_error){0}.msg] = "";
    sph_scene_def def;
    bool ok = bench_scene_def(&o->cfg, L, bench_k_min(o->cfg.dim), false, &def, why, sizeof why);
    if (ok && bench_level_gl(L)) {
        if (*gl_state == 0) *gl_state = sph_gpu_probe(gl_device, gl_n) ? 1 : -1;
        if (*gl_state < 0) return true; /* no device: the level is skipped and said so */
    }
    if (ok) {
        sph_sim *sim;
        sph_error err;
        const sph_error_code c = sph_sim_create(&def, 1, &sim, &err);
        if (c == SPH_ERR_OK)
            sph_sim_destroy(sim);
        else if (c == SPH_ERR_SCENE) {
            ok = false;
            snprintf(why, sizeof why, "%s", err.msg);
        }
    }
    if (!ok)
        fprintf(stderr,
                "sphlab bench: level %s does not take the --set keys: %s\n(a key for some levels only: --set "
                "LEVEL:SECTION.KEY=VALUE, e.g. --set L10:search.skin=0.1)\n",
                L->name, why);
    return ok;
}

int bench_ladder_measure(const bench_opts *o, bench_ladder *lad)
{
    memset(lad, 0, sizeof *lad);
    const int dim = o->cfg.dim;
    const double fps = o->fps;
    ladder_meta meta = {.best = -1};
    bench_now_iso(meta.date, sizeof meta.date);
    bench_loadavg(meta.load0);
    double t_start = sph_now_ms();
    bench_cpu cpu0, cpu1;
    bench_cpu_now(&cpu0);
    meta.ghz0 = bench_clock_probe();
    /* the float peak the counted GFLOP/s are set against: the quick form, about 2 s */
    bench_progress("the machine's float peak and bandwidth (quick) ...");
    bench_machine_measure(&meta.machine, true);

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
    const double cap = o->quick ? BENCH_MAX_N_QUICK : BENCH_MAX_N;

    /* an unwritable directory fails now, not after the measurements */
    char dir_err[1200];
    if (!sph_output_dir(o->out, dir_err, sizeof dir_err)) {
        fprintf(stderr, "sphlab bench: --out: %s\n", dir_err);
        return 1;
    }

    int gl_state = 0; /* 0: not probed yet, 1: a GL 4.3 context can be made, -1: none */
    /* a --set that a selected level or a reference of the checks cannot take (a
     * CPU ladder key on a GL level) is a bad command line, said before anything is timed */
    if (o->cfg.n_sets > 0) {
        for (int s = -2; s < o->nsel; s++)
            if (!level_takes_the_sets(o, s == -2 ? ref_small : s == -1 ? ref_large : o->sel[s], &gl_state,
                                      meta.gl_device, sizeof meta.gl_device))
                return 2;
    }

    level_result *res = calloc((size_t)o->nsel, sizeof *res);
    if (!res) return 1;
    lad->res = res;
    ref_cache ref_s = {.level = ref_small, .k = k_check}, ref_l = {.level = ref_large, .k = k_at};
    ref_cache ref_l_small = {.level = ref_large, .k = k_check};
    bool all_pass = true;
    meta.gl_best = -1;
    for (int s = 0; s < o->nsel; s++) {
        const int Li = o->sel[s];
        const bench_level *L = &bench_levels[Li];
        level_result *r = &res[s];
        char err[512] = "";
        if (bench_level_gl(L)) {
            if (gl_state == 0) gl_state = sph_gpu_probe(meta.gl_device, sizeof meta.gl_device) ? 1 : -1;
            meta.gl_is_gpu = gl_state > 0 && !strstr(meta.gl_device, "llvmpipe") &&
                             !strstr(meta.gl_device, "softpipe") && !strstr(meta.gl_device, "lavapipe");
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
        bench_progress("%s %s: passes at N = %.0f ...", L->name, L->about, meta.n_at);
        char why[512];
        r->at_ok = bench_measure_retry(&o->cfg, L, k_at, &plan_at, 0, o->quick ? 2 : 3, &r->at, why, sizeof why);
        if (!r->at_ok) {
            snprintf(r->error, sizeof r->error, "%s", why);
            all_pass = false;
            r->check_ok = false;
        } else {
            fill_rates(r);
            bench_level_flops(r, &meta.machine);
            if (bench_level_gl(L) && r->at.timing) meta.gl_timing = r->at.timing;
        }
        bench_cpu_now(&c1);
        r->others = bench_cpu_others(&c0, &c1);
    }
    bench_progress_done();
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
        /* a level that failed its check does not count ("its speed does not count"): it was counted, and its
         * N decided the record's verdict */
        if (res[s].searched && res[s].check_ok && (*best < 0 || res[s].max_n > res[*best].max_n)) *best = s;
    }
    meta.target_evaluated = dim == 3 && fabs(fps - 60) < 1e-9 && meta.best >= 0;
    meta.target_met = meta.target_evaluated && res[meta.best].max_n >= 60000;
    meta.gl_target_met = meta.gl_best >= 0 && res[meta.gl_best].max_n >= 1000000;
    meta.gl_target_evaluated = dim == 3 && fabs(fps - 60) < 1e-9 && meta.gl_best >= 0 && meta.gl_is_gpu;

    bool *pass_used = lad->pass_used;
    for (int s = 0; s < o->nsel; s++)
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (res[s].at_ok && isfinite(res[s].at.pass_ms[p])) pass_used[p] = true;
    lad->meta = meta;
    lad->gl_state = gl_state;
    lad->k_at = k_at;
    lad->k_check = k_check;
    lad->all_pass = all_pass;
    return 0;
}

void bench_ladder_free(bench_ladder *lad)
{
    free(lad->res);
    lad->res = NULL;
}
