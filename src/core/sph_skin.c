/* Verlet lists ([search] skin > 0): the neighbour lists are built out to
 * h (1 + skin) and kept over the following steps while no particle has moved
 * skin h / 2 since the build. Two particles closer than h now were then closer
 * than h + 2 (skin h / 2) = h (1 + skin), so they are in each other's lists;
 * the passes that walk the lists count only pairs within h (their kernels
 * vanish beyond h), so the results are those of lists built every step.
 * (Verlet 1967; Allen & Tildesley, Computer Simulation of Liquids, 1987,
 * section 5.3.1.)
 *
 * The lists hold particle indices, so the particles must stay where they
 * are stored while the lists are kept: a step that keeps them also skips
 * the hash, sort and reorder (the cells and their order are rebuilt with the
 * lists). The search passes ask sph_skin_keep at their start; the first of
 * them in a step decides for the whole step. */
#include "sph_search.h"

#include <math.h>

/* A rounding margin on the half skin: r^2 < (h (1 + skin))^2 was decided in
 * float, so keep a thousandth of the half skin in hand. */
#define SPH_SKIN_MARGIN 0.999f

float sph_skin_radius(const sph_sim *sim)
{
    const float s = sim->def.skin > 0.0f ? sim->def.skin : 0.0f;
    return sim->def.h * (1.0f + s);
}

/* The largest distance any particle's predicted position moved since the
 * build (the minimum image is not taken: a particle wrapped around a
 * periodic axis counts as far, and the lists are rebuilt). */
static float moved_most(const sph_sim *sim)
{
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    float most2 = 0.0f;
#pragma omp parallel for schedule(static) reduction(max : most2) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        float r2 = 0.0f;
        for (int d = 0; d < dim; d++) {
            const float dx = sim->P.pred[d][i] - S->skin_ref[d][i];
            r2 += dx * dx;
        }
        most2 = r2 > most2 ? r2 : most2;
    }
    return sqrtf(most2);
}

bool sph_skin_keep(sph_sim *sim)
{
    sph_search_data *S = &sim->S;
    if (!(sim->def.skin > 0.0f) || !S->skin_ref[0]) return false;
    if (S->kept_decided == sim->step + 1) return S->lists_kept; /* decided by an earlier pass of this step */
    S->kept_decided = sim->step + 1;
    S->lists_kept = false;
    if (!S->lists_built) return false;
    S->skin_moved = moved_most(sim);
    /* NaN moves (a runaway the watchdog will name) rebuild as well */
    S->lists_kept = S->skin_moved < SPH_SKIN_MARGIN * 0.5f * sim->def.skin * sim->def.h;
    return S->lists_kept;
}

void sph_skin_mark(sph_sim *sim)
{
    sph_search_data *S = &sim->S;
    S->builds++;
    if (!S->skin_ref[0]) return;
    const int n = (int)sim->n, dim = sim->dim;
    for (int d = 0; d < dim; d++) {
        float *restrict ref = S->skin_ref[d];
        const float *restrict pred = sim->P.pred[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) ref[i] = pred[i];
    }
    S->lists_built = true;
    S->skin_moved = 0.0f;
}
