/* The window's ladder: levels, live speed-ups, N and pass numbers (view_ladder.h). */
#include "view_ladder.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static int cores(void)
{
#ifdef _OPENMP
    return omp_get_num_procs();
#else
    return 1;
#endif
}

int view_ladder_level(const sph_sim *sim)
{
    return sph_level_of(&sim->def, sim->threads, cores());
}

/* The pipeline's passes switched off in the window (key d), their names in names; their count. */
static int passes_off(const sph_sim *sim, char *names, size_t n)
{
    int off = 0;
    size_t used = 0;
    if (n) names[0] = '\0';
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p] && !sim->enabled[p]) {
            off++;
            if (used < n)
                used += (size_t)snprintf(names + used, n - used, "%s%s", used ? " " : "", sph_passes[p]->name);
        }
    return off;
}

void view_ladder_record(view_ladder *l, const sph_sim *sim)
{
    if (sim->n != l->n) { /* other particles: the times of other levels no longer compare */
        memset(l->ms, 0, sizeof l->ms);
        l->n = sim->n;
    }
    char off[8];
    if (passes_off(sim, off, sizeof off)) return; /* a pass off: not the level's step (its time was credited to it) */
    const int lv = view_ladder_level(sim);
    int window = 0;
    const double ms = sph_sim_step_ms(sim, &window);
    if (lv >= 0 && lv < VIEW_LEVELS_MAX && window >= VIEW_MEASURE_STEPS && ms > 0) l->ms[lv] = ms;
}

/* The level one rung below lv in its family (L or G), or -1. */
static int level_below(int lv)
{
    if (lv <= 0) return -1;
    return sph_levels[lv - 1].name[0] == sph_levels[lv].name[0] ? lv - 1 : -1;
}

bool view_ladder_load_csv(view_ladder *l, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return false;
    char line[4096];
    int c_level = -1, c_n = -1, c_ms = -1;
    double ms[VIEW_LEVELS_MAX] = {0}, at[VIEW_LEVELS_MAX] = {0};
    bool any = false;
    for (int row = 0; fgets(line, sizeof line, f); row++) {
        line[strcspn(line, "\r\n")] = '\0';
        char *lvname = NULL, *next = line;
        double n = NAN, m = NAN;
        int col = 0;
        /* fields split at each comma, empty ones kept (a figure not measured is left empty) */
        for (char *tok = line; next; tok = next, col++) {
            next = strchr(tok, ',');
            if (next) *next++ = '\0';
            if (row == 0) {
                if (strcmp(tok, "level") == 0) c_level = col;
                if (strcmp(tok, "n_at") == 0) c_n = col;
                if (strcmp(tok, "ms_per_step") == 0) c_ms = col;
                continue;
            }
            if (col == c_level) lvname = tok;
            if (col == c_n && *tok) n = strtod(tok, NULL);
            if (col == c_ms && *tok) m = strtod(tok, NULL);
        }
        if (row == 0 && (c_level < 0 || c_n < 0 || c_ms < 0)) break;
        const int lv = lvname ? sph_level_find(lvname) : -1;
        if (row > 0 && lv >= 0 && lv < VIEW_LEVELS_MAX && n > 0 && m > 0) {
            ms[lv] = m, at[lv] = n;
            any = true;
        }
    }
    fclose(f);
    if (!any) return false;
    memcpy(l->csv_ms, ms, sizeof ms);
    memcpy(l->csv_n, at, sizeof at);
    snprintf(l->csv_path, sizeof l->csv_path, "%s", path);
    return true;
}

static void speedup_text(const view_ladder *l, int lv, int ref, double ms, char *out, size_t n)
{
    if (ref >= 0 && ref < VIEW_LEVELS_MAX && !(l->ms[ref] > 0) && l->csv_ms[ref] > 0 && l->csv_ms[lv] > 0 &&
        l->csv_n[ref] == l->csv_n[lv]) {
        /* not visited here: the bench's ratio, at its N */
        snprintf(out, n, "x%.3g vs %.8s (bench CSV, N=%.0f)", l->csv_ms[ref] / l->csv_ms[lv], sph_levels[ref].name,
                 l->csv_n[lv]);
    } else if (ref < 0) {
        snprintf(out, n, "-");
    } else if (ref >= VIEW_LEVELS_MAX || !(l->ms[ref] > 0)) {
        snprintf(out, n, "%.8s not visited", sph_levels[ref].name);
    } else if (ref == lv) {
        snprintf(out, n, "x1 vs %.8s", sph_levels[ref].name);
    } else {
        snprintf(out, n, "x%.3g vs %.8s", l->ms[ref] / ms, sph_levels[ref].name);
    }
}

int view_ladder_lines(const view_ladder *l, const sph_sim *sim, char lines[][128], int max_lines)
{
    int k = 0;
#define LADDER_LINE(...) \
    if (k < max_lines) snprintf(lines[k++], 128, __VA_ARGS__)
    const sph_scene_def *d = &sim->def;
    const int lv = view_ladder_level(sim);
    char ingredients[96];
    /* what runs, not only what the keys say: brute force has no reorder pass (it read "reorder on"), and the GL
     * backend's passes run on the device, not on the CPU's threads (it read "2 threads, gl") */
    char threads[32];
    if (d->backend == SPH_BACKEND_CPU)
        snprintf(threads, sizeof threads, "%d thread%s", sim->threads, sim->threads == 1 ? "" : "s");
    else
        snprintf(threads, sizeof threads, "on the device");
    snprintf(ingredients, sizeof ingredients, "%s%s%s, reorder %s, vector %s, %s, %s", sph_search_names[d->search],
             d->search == SPH_SEARCH_BRUTE ? "" : " + ", d->search == SPH_SEARCH_BRUTE ? "" : sph_sort_names[d->sort],
             !sim->in_pipeline[SPH_PASS_REORDER] ? "-"
             : !sim->enabled[SPH_PASS_REORDER]   ? "off (pass)"
                                                  : sph_onoff_names[d->reorder],
             sph_onoff_names[d->vector],
             threads, sph_backend_names[d->backend]);
    char off[96];
    if (passes_off(sim, off, sizeof off)) {
        LADDER_LINE("level %s with passes off (%.60s): not its pipeline, times not recorded",
                    lv >= 0 ? sph_levels[lv].name : "none", off);
    } else if (lv >= 0) {
        LADDER_LINE("level %s: %s", sph_levels[lv].name, sph_levels[lv].about);
    } else {
        LADDER_LINE("level: none of the ladder's (a mix of ingredients)");
    }
    LADDER_LINE("  %s", ingredients);
    int window = 0;
    const double ms = sph_sim_step_ms(sim, &window);
    if (ms > 0 && lv >= 0 && !passes_off(sim, off, sizeof off)) { /* with passes off: no level's figure */
        char below[48], base[48];
        const int l0 = sph_levels[lv].name[0] == 'G' ? sph_level_find("L0") : 0;
        speedup_text(l, lv, level_below(lv), ms, below, sizeof below);
        speedup_text(l, lv, l0, ms, base, sizeof base);
        if (level_below(lv) == l0) { /* at L1 the level below is the base: said once */
            LADDER_LINE("speed-up (live at N = %u): %.47s", sim->n, below);
        } else {
            LADDER_LINE("speed-up (live at N = %u): %.47s, %.47s", sim->n, below, base);
        }
    }
    if (ms > 0 && sim->n) {
        /* the cost per particle-step taken as constant: N_60 = (1000/60 ms) / (ms / N) */
        const double per = ms / sim->n, n60 = (1000.0 / 60.0) / per;
        LADDER_LINE("N at 60 steps/s ~ %.3g (%.3g us/particle-step)", n60, 1e3 * per); /* one row at 1024 px */
    }
    if (l->validated) {
        const sph_compare_result *r = &l->val;
        LADDER_LINE("validate vs %s at step %llu (%d steps): %u sets differ%s", l->val_ref,
                    (unsigned long long)l->val_step, r->steps, r->sets_differ, r->sets_differ ? "  WRONG" : "");
        LADDER_LINE("  %u pairs + %u at r = h; |dx| %.2g m, |dv| %.2g m/s%s", r->pairs_differ, r->edge_pairs, r->dx,
                    r->dv, r->stopped ? " (stopped)" : "");
    }
#undef LADDER_LINE
    return k;
}

bool view_switch(sph_sim **sim, sph_scene_def *def, int *threads, const sph_scene_def *next, int next_threads,
                 const char *what, char *msg, size_t n)
{
    sph_scene_def d = *next;
    sph_error err;
    sph_sim *fresh = NULL;
    if (sph_scene_validate(&d, &err) != SPH_ERR_OK || sph_sim_clone(*sim, &d, next_threads, &fresh, &err) != SPH_ERR_OK) {
        snprintf(msg, n, "%s: %s", what, err.msg);
        return false;
    }
    sph_sim_destroy(*sim);
    *sim = fresh;
    *def = d;
    *threads = next_threads;
    const int lv = view_ladder_level(fresh);
    char on[32]; /* the GL backend's passes run on the device, whatever the CPU's threads */
    if (d.backend == SPH_BACKEND_CPU)
        snprintf(on, sizeof on, "%d thread%s", fresh->threads, fresh->threads == 1 ? "" : "s");
    else
        snprintf(on, sizeof on, "on the device");
    snprintf(msg, n, "%s: at level %s (%s), %s, %s", what, lv >= 0 ? sph_levels[lv].name : "none",
             lv >= 0 ? sph_levels[lv].about : "a mix of ingredients", on, sph_backend_names[d.backend]);
    return true;
}

bool view_go_level(sph_sim **sim, sph_scene_def *def, int *threads, int level, char *msg, size_t n)
{
    const sph_level *L = &sph_levels[level];
    sph_scene_def d = *def;
    sph_error err;
    if (sph_level_apply(L, &d, &err) != SPH_ERR_OK) {
        snprintf(msg, n, "level %s: %s", L->name, err.msg);
        return false;
    }
    return view_switch(sim, def, threads, &d, L->threads, "level", msg, n);
}

bool view_next_level(sph_sim **sim, sph_scene_def *def, int *threads, int dir, char *msg, size_t n)
{
    const int lv = view_ladder_level(*sim);
    char first[256] = "";
    for (int s = 1; s <= sph_level_count; s++) {
        const int l = ((lv < 0 ? (dir > 0 ? -1 : 0) : lv) + dir * s + 2 * sph_level_count) % sph_level_count;
        if (view_go_level(sim, def, threads, l, msg, n)) {
            if (first[0]) { /* say why the GL levels were passed over */
                size_t len = strlen(msg);
                snprintf(msg + len, n - len, " (passed over: %.150s)", first);
            }
            return true;
        }
        if (!sph_level_gl(&sph_levels[l])) return false; /* a CPU level refused: said why */
        if (!first[0]) snprintf(first, sizeof first, "%s", msg);
    }
    return false;
}

bool view_validate(view_ladder *l, const sph_sim *sim, const char *ref, char *msg, size_t n)
{
    const int r = sph_level_find(ref);
    sph_error err;
    const double t0 = sph_now_ms();
    if (r >= 0 && strstr(sph_levels[r].sets, "search.method=brute") && sim->n > VIEW_VALIDATE_BRUTE_MAX) {
        /* brute force on one thread is O(N^2): seconds of a frozen window per step at this N */
        snprintf(msg, n, "validate: %s (brute force) at N = %u would freeze the window; shift+a validates against L2",
                 ref, sim->n);
        return false;
    }
    if (r < 0 || sph_sim_validate(sim, &sph_levels[r], 5, &l->val, &err) != SPH_ERR_OK) {
        snprintf(msg, n, "validate: %s", r < 0 ? "no such reference level" : err.msg);
        return false;
    }
    l->validated = true;
    l->val_step = sim->step;
    snprintf(l->val_ref, sizeof l->val_ref, "%s", ref);
    char text[256];
    sph_compare_text(&l->val, ref, text, sizeof text);
    snprintf(msg, n, "%s (%.0f ms)", text, sph_now_ms() - t0);
    return true;
}

bool view_scene_rescaled(const sph_scene_def *def, float factor, sph_scene_def *out, char *why, size_t n)
{
    *out = *def;
    for (int b = 0; b < out->n_blocks; b++) out->blocks[b].spacing *= factor;
    out->h *= factor;
    if (!(out->cfl > 0)) out->dt *= factor; /* the CFL limit goes with h */
    sph_error err;
    if (sph_scene_validate(out, &err) != SPH_ERR_OK) {
        snprintf(why, n, "%s", err.msg);
        return false;
    }
    return true;
}

int view_pass_number(const sph_sim *sim, int pass)
{
    if (pass < 0 || pass >= SPH_PASS_COUNT || !sim->in_pipeline[pass]) return 0;
    int k = 0;
    for (int p = 0; p <= pass; p++) k += sim->in_pipeline[p];
    return k;
}

int view_pass_of_number(const sph_sim *sim, int number)
{
    for (int p = 0, k = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p] && ++k == number) return p;
    return -1;
}

int view_pass_next(const sph_sim *sim, int pass, int dir)
{
    for (int s = 1; s <= SPH_PASS_COUNT + 1; s++) {
        int p = pass < 0 ? (dir > 0 ? s - 1 : SPH_PASS_COUNT - s) : pass + dir * s;
        p = ((p % SPH_PASS_COUNT) + SPH_PASS_COUNT) % SPH_PASS_COUNT;
        if (sim->in_pipeline[p]) return p;
    }
    return -1;
}
