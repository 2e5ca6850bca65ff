/* The hash health on the device (sph_backend.hash_health): the figures of
 * sph_sim_hash_health without the neighbour count, from the positions the
 * hash pass saw, by three dispatches of shaders/gpu_health.comp (the per-key
 * records cleared, the particles counted into their keys, the table and the
 * stencils summed), and 20 bytes read back instead of the positions. The
 * core asks for them only when its host copy of the positions is stale. */
#include <math.h>
#include <string.h>

#include "gpu_internal.h"
#include "sph_hash_health.h"

#define HEALTH_SUMS 5 /* uints: occupied, colliding, longest run, candidates (low, high word) */

bool gpu_hash_health(sph_backend *b, const sph_sim *sim, sph_hash_health *out)
{
    gpu *g = (gpu *)b;
    /* the positions the hash pass saw: the predicted ones once it has run (sph_hash_health.c) */
    const int field = sim->P.pred[0] && sim->timing[SPH_PASS_HASH].calls > 0 ? SPH_FIELD_PRED : SPH_FIELD_POS;
    if (!g->prog[PROG_H(health)] || !g->buf[field]) return false;
    gpu_current(g);
    if (g->share) { /* another simulation in the shared context may have rebound them */
        for (int k = 0; k < B_TOTAL; k++)
            if (g->buf[k]) gpu_bind(g, k, g->buf[k]);
    }
    if (!g->health_keys) {
        g->gl.GenBuffers(1, &g->health_keys);
        g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->health_keys);
        g->gl.BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(3 * (size_t)g->table * sizeof(uint32_t)), NULL,
                         GL_DYNAMIC_COPY);
        g->gl.GenBuffers(1, &g->health_sums);
        g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->health_sums);
        g->gl.BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(HEALTH_SUMS * sizeof(uint32_t)), NULL,
                         GL_DYNAMIC_COPY);
        if (g->gl.GetError() != GL_NO_ERROR) return false; /* out of device memory: the host computes them */
    }
    static const uint32_t zero[HEALTH_SUMS] = {0};
    gpu_send(g, g->health_sums, 0, sizeof zero, zero);
    const int p = PROG_H(health);
    gpu_use(g, p);
    gpu_bind(g, B_SRC, g->buf[field]);
    gpu_bind(g, B_DST, g->health_keys);
    gpu_bind(g, B_SUMS, g->health_sums);
    gpu_set_u(g, p, U_count, 0);
    gpu_dispatch(g, g->table);
    gpu_set_u(g, p, U_count, 1);
    gpu_dispatch(g, g->n);
    gpu_set_u(g, p, U_count, 2);
    gpu_dispatch(g, g->table > g->n ? g->table : g->n);
    uint32_t q[HEALTH_SUMS];
    gpu_get(g, g->health_sums, 0, sizeof q, q);
    const uint64_t cand = (uint64_t)q[4] << 32 | q[3];
    *out = (sph_hash_health){.has_table = true,
                             .table_size = g->table,
                             .particles = g->n,
                             .load_factor = (double)g->n / g->table,
                             .occupied = q[0],
                             .colliding = q[1],
                             .longest_run = q[2],
                             .candidates = g->n ? (double)cand / g->n : 0,
                             .neighbours = NAN,
                             .share = NAN};
    return true;
}

void gpu_health_free(gpu *g)
{
    if (g->health_keys) g->gl.DeleteBuffers(1, &g->health_keys);
    if (g->health_sums) g->gl.DeleteBuffers(1, &g->health_sums);
}

bool sph_gpu_hash_health(const sph_sim *sim, sph_hash_health *out)
{
    if (!sim->backend || sim->backend->hash_health != gpu_hash_health) return false;
    if (!sim->in_pipeline[SPH_PASS_HASH] || sim->S.cells.dense) return false; /* no table: as sph_hash_health.c */
    return gpu_hash_health(sim->backend, sim, out);
}
