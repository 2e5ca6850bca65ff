/* Pass: reorder. After the sort, the particle data are stored in the sorted
 * order of their cells: particle e becomes the one of sorted entry e. The
 * particles of a cell then sit side by side, a cell's run in the index is a
 * run in the arrays too, and a particle's neighbours are near it in memory,
 * so the search scans contiguous arrays and the force passes stop jumping
 * across memory. Each field is gathered into a spare array and the two are
 * swapped. `id` keeps each particle's creation number for outputs. The
 * fields rewritten later in the step (density, pressure, accelerations) need
 * no moving. */
#include "sph_search.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    const char *why = sph_pass_sort.skip_reason(def);
    if (why) return why;
    return def->reorder == SPH_ON ? NULL : "search.reorder = off: particles keep their creation order";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    (void)def;
    snprintf(out, (size_t)n, "particle data stored in cell order (id keeps creation order)");
}

static void gather_f(float **field, float **spare, const sph_entry *e, int n)
{
    const float *restrict src = *field;
    float *restrict dst = *spare;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int k = 0; k < n; k++) dst[k] = src[e[k].index];
    float *t = *field;
    *field = *spare;
    *spare = t;
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    sph_search_data *S = &sim->S;
    const int n = (int)sim->n;
    sph_entry *e = S->entries;
    if (sph_skin_keep(sim)) return; /* the kept lists index the particles where they are */
    {
        const uint32_t *restrict src = P->id;
        uint32_t *restrict dst = S->spare_u;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int k = 0; k < n; k++) dst[k] = src[e[k].index];
        S->spare_u = P->id;
        P->id = dst;
    }
    gather_f(&P->mass, &S->spare_f, e, n);
    if (P->fixed) gather_f(&P->fixed, &S->spare_f, e, n); /* wall particles stay marked */
    if (P->obstacle) gather_f(&P->obstacle, &S->spare_f, e, n); /* with their obstacle and slip */
    if (P->slip) gather_f(&P->slip, &S->spare_f, e, n);
    if (P->rho_c) gather_f(&P->rho_c, &S->spare_f, e, n); /* the carried density (density_method = continuity) */
    if (P->kappa) gather_f(&P->kappa, &S->spare_f, e, n); /* DFSPH's warm starts */
    if (P->p_pci) gather_f(&P->p_pci, &S->spare_f, e, n); /* PCISPH's warm start */
    if (P->kappa_v) gather_f(&P->kappa_v, &S->spare_f, e, n);
    for (int d = 0; d < sim->dim; d++) {
        gather_f(&P->pos[d], &S->spare_f, e, n);
        gather_f(&P->vel[d], &S->spare_f, e, n);
        gather_f(&P->pred[d], &S->spare_f, e, n);
        if (P->pos_r[d]) gather_f(&P->pos_r[d], &S->spare_f, e, n); /* position_sum = compensated */
    }
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int k = 0; k < n; k++) {
        e[k].index = (uint32_t)k;
        S->cell_hash[k] = e[k].hash;
    }
    S->reordered = true;
}

const sph_pass sph_pass_reorder = {
    .name = "reorder",
    .summary = "store particles in cell order",
    /* and the wall flag `fixed` (with `obstacle` and `slip`) where there are wall particles, the carried
     * density rho_c with density_method = continuity, the position remainder pos_r with position_sum =
     * compensated, the pressure solvers' kept kappa, kappa_v and p_pci (their warm starts; the GL backend
     * gathers what is listed here): written (moved) when present, not listed in reads (a pass's reads exist
     * in every scene that runs it) */
    .reads = SPH_RES_ENTRIES | SPH_RES_ID | SPH_BIT(MASS) | SPH_BIT(POS) | SPH_BIT(VEL) | SPH_BIT(PRED),
    .writes = SPH_RES_ID | SPH_BIT(MASS) | SPH_BIT(POS) | SPH_BIT(VEL) | SPH_BIT(PRED) | SPH_BIT(FIXED) |
              SPH_BIT(RHO_C) | SPH_BIT(OBSTACLE) | SPH_BIT(SLIP) | SPH_BIT(KAPPA) | SPH_BIT(KAPPA_V) |
              SPH_BIT(P_PCI) | SPH_BIT(POS_R) | SPH_RES_ENTRIES,
    .group = SPH_GROUP_SEARCH,
    .highlight = NULL,
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
