/* Validate mode: two runs of the same state compared (sph_compare.h). */
#include "sph_compare.h"
#include "sph_search.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One run's first-step neighbour sets, by id: the neighbours of id k are
 * nbr[start[k] .. start[k+1]), as sorted ids; and where it found them. */
typedef struct id_sets {
    uint32_t *start, *nbr;
    float *pred[3]; /* [m] by id */
} id_sets;

static int cmp_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static void sets_free(id_sets *s)
{
    free(s->start);
    free(s->nbr);
    for (int d = 0; d < 3; d++) free(s->pred[d]);
}

static bool sets_take(const sph_sim *sim, id_sets *s)
{
    const uint32_t n = sim->n;
    memset(s, 0, sizeof *s);
    sph_sim_sync(sim, SPH_SYNC_ALL);
    const uint32_t *ns = sim->S.nbr_start;
    const size_t total = ns ? ns[n] : 0; /* entries, or compact lists' words: at least the entries */
    uint32_t *inv = malloc((size_t)n * sizeof *inv);
    s->start = calloc((size_t)n + 1, sizeof *s->start);
    s->nbr = malloc((total ? total : 1) * sizeof *s->nbr);
    bool ok = inv && s->start && s->nbr;
    float *const *x = sim->P.pred[0] ? sim->P.pred : sim->P.pos;
    for (int d = 0; d < sim->dim && ok; d++) ok = (s->pred[d] = malloc((size_t)n * sizeof(float))) != NULL;
    if (!ok) {
        free(inv);
        sets_free(s);
        return false;
    }
    for (uint32_t i = 0; i < n; i++) inv[sim->P.id[i]] = i;
    /* only the entries within h count: Verlet lists ([search] skin) hold pairs
     * out to h (1 + skin). The test is the search's own, in float, in its
     * order, so a list built out to h keeps every entry. */
    const float h2 = sim->def.h * sim->def.h;
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t i = inv[k];
        const sph_nbr_row row = ns ? sph_nbr_row_of(&sim->S, i) : (sph_nbr_row){0};
        uint32_t kept = 0;
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float r2 = 0.0f;
            for (int d = 0; d < sim->dim; d++) {
                const float dx = sph_min_image(x[d][j] - x[d][i], sim->period[d], sim->inv_period[d]);
                r2 += dx * dx;
            }
            if (r2 < h2) s->nbr[s->start[k] + kept++] = sim->P.id[j];
        }
        s->start[k + 1] = s->start[k] + kept;
        qsort(s->nbr + s->start[k], kept, sizeof *s->nbr, cmp_u32);
        for (int d = 0; d < sim->dim; d++) s->pred[d][k] = x[d][i];
    }
    free(inv);
    return true;
}

/* [m] distance of ids a and b where the search saw them, across periodic axes by the nearest image */
static double pair_distance(const sph_sim *sim, const id_sets *s, uint32_t a, uint32_t b)
{
    double r2 = 0;
    for (int d = 0; d < sim->dim; d++) {
        double dx = (double)s->pred[d][a] - s->pred[d][b];
        if (sim->period[d] > 0) dx -= sim->period[d] * nearbyint(dx / sim->period[d]);
        r2 += dx * dx;
    }
    return sqrt(r2);
}

static void sets_compare(const sph_sim *sim, const id_sets *a, const id_sets *b, sph_compare_result *r)
{
    const double h = sim->def.h;
    uint32_t worst = 0;
    r->pairs_a = a->start[sim->n];
    r->pairs_b = b->start[sim->n];
    for (uint32_t k = 0; k < sim->n; k++) {
        uint32_t i = a->start[k], j = b->start[k], wrong = 0;
        const uint32_t ie = a->start[k + 1], je = b->start[k + 1];
        while (i < ie || j < je) {
            uint32_t other;
            if (j >= je || (i < ie && a->nbr[i] < b->nbr[j])) {
                other = a->nbr[i++];
            } else if (i >= ie || b->nbr[j] < a->nbr[i]) {
                other = b->nbr[j++];
            } else {
                i++, j++;
                continue;
            }
            if (fabs(pair_distance(sim, a, k, other) - h) <= SPH_COMPARE_EDGE * h)
                r->edge_pairs++;
            else
                wrong++;
        }
        if (!wrong) continue;
        r->sets_differ++;
        r->pairs_differ += wrong;
        if (wrong > worst) worst = wrong, r->worst_id = k;
    }
}

static void state_compare(const sph_sim *a, const sph_sim *b, sph_compare_result *r)
{
    sph_sim_sync(a, SPH_SYNC_ALL);
    sph_sim_sync(b, SPH_SYNC_ALL);
    const uint32_t n = a->n;
    uint32_t *inv = malloc((size_t)n * sizeof *inv);
    if (!inv) return;
    for (uint32_t i = 0; i < n; i++) inv[b->P.id[i]] = i;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t j = inv[a->P.id[i]];
        double x2 = 0, v2 = 0;
        for (int d = 0; d < a->dim; d++) {
            double dx = (double)a->P.pos[d][i] - b->P.pos[d][j];
            if (a->period[d] > 0) dx -= a->period[d] * nearbyint(dx / a->period[d]);
            const double dv = (double)a->P.vel[d][i] - b->P.vel[d][j];
            x2 += dx * dx;
            v2 += dv * dv;
        }
        if (sqrt(x2) > r->dx) r->dx = sqrt(x2), r->dx_id = a->P.id[i];
        r->dv = fmax(r->dv, sqrt(v2));
    }
    free(inv);
}

sph_error_code sph_sim_compare(const sph_sim *a, const sph_sim *b, int steps, sph_compare_result *out,
                               sph_error *err)
{
    memset(out, 0, sizeof *out);
    out->worst_id = out->dx_id = UINT32_MAX;
    if (a->n != b->n || a->dim != b->dim)
        return sph_fail(err, SPH_ERR_SCENE, "validate: the runs hold other particles (%u and %u)", a->n, b->n);
    if (steps < 1) steps = 1;
    sph_sim *ra = NULL, *rb = NULL;
    sph_error_code c = sph_sim_clone(a, &a->def, a->threads, &ra, err);
    if (c == SPH_ERR_OK) c = sph_sim_clone(b, &b->def, b->threads, &rb, err);
    if (c != SPH_ERR_OK) {
        sph_sim_destroy(ra);
        return c;
    }
    out->n = a->n;
    sph_sim_step(ra);
    sph_sim_step(rb);
    out->steps = 1;
    id_sets sa, sb;
    if (!sets_take(ra, &sa)) {
        c = sph_fail(err, SPH_ERR_MEMORY, "validate: out of memory for the neighbour sets of %u particles", a->n);
    } else if (!sets_take(rb, &sb)) {
        sets_free(&sa);
        c = sph_fail(err, SPH_ERR_MEMORY, "validate: out of memory for the neighbour sets of %u particles", a->n);
    } else {
        sets_compare(ra, &sa, &sb, out);
        sets_free(&sa);
        sets_free(&sb);
        for (; out->steps < steps && !ra->alarm.raised && !rb->alarm.raised; out->steps++) {
            sph_sim_step(ra);
            sph_sim_step(rb);
        }
        out->stopped = ra->alarm.raised || rb->alarm.raised;
        state_compare(ra, rb, out);
    }
    sph_sim_destroy(ra);
    sph_sim_destroy(rb);
    return c;
}

sph_error_code sph_sim_validate(const sph_sim *sim, const sph_level *ref, int steps, sph_compare_result *out,
                                sph_error *err)
{
    sph_scene_def def = sim->def;
    sph_error_code c = sph_level_apply(ref, &def, err);
    if (c != SPH_ERR_OK) return c;
    sph_sim *r = NULL;
    c = sph_sim_clone(sim, &def, ref->threads, &r, err);
    if (c != SPH_ERR_OK) return c;
    c = sph_sim_compare(sim, r, steps, out, err);
    sph_sim_destroy(r);
    return c;
}

void sph_compare_text(const sph_compare_result *r, const char *ref, char *out, size_t n)
{
    snprintf(out, n, "validate vs %s, %d steps: %u sets differ%s (%u pairs, %u at the edge); max |dx| %.3g m, |dv| %.3g m/s%s",
             ref, r->steps, r->sets_differ, r->sets_differ ? " WRONG" : "", r->pairs_differ, r->edge_pairs, r->dx,
             r->dv, r->stopped ? "; the watchdog stopped a run" : "");
}
