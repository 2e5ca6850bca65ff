/* The statistics on the device (sph_backend.stats): sph_sim_stats's energies,
 * momentum, densities and largest speed reduced by two dispatches
 * (shaders/gpu_stats.comp per work group, gpu_stats_sum.comp over the
 * groups), and 12 floats read back instead of five fields. The core asks
 * for them only when its host copy is stale, so a reader that downloaded
 * the fields anyway gets the host's sums in double, as before. */
#include <math.h>
#include <string.h>

#include "gpu_internal.h"

#define STATS_Q 12 /* floats per row: as in shaders/gpu_stats.comp */

bool gpu_stats(sph_backend *b, const sph_sim *sim, sph_stats *out)
{
    gpu *g = (gpu *)b;
    if (!g->prog[PROG_H(stats)] || !g->prog[PROG_H(stats_sum)] || !g->buf[SPH_FIELD_MASS]) return false;
    gpu_current(g);
    if (g->share) { /* another simulation in the shared context may have rebound them */
        for (int k = 0; k < B_TOTAL; k++)
            if (g->buf[k]) gpu_bind(g, k, g->buf[k]);
    }
    const uint32_t groups = (g->n + WG - 1) / WG;
    if (!groups) return false;
    if (g->stats_at == g->changes + 1) { /* nothing ran since (the HUD asks twice a frame): no read-back */
        *out = g->stats;
        return true;
    }
    if (!g->stats_rows) {
        g->gl.GenBuffers(1, &g->stats_rows);
        g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->stats_rows);
        g->gl.BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)((size_t)groups * STATS_Q * sizeof(float)), NULL,
                         GL_DYNAMIC_COPY);
        g->gl.GenBuffers(1, &g->stats_out);
        g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->stats_out);
        g->gl.BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(STATS_Q * sizeof(float)), NULL, GL_DYNAMIC_COPY);
    }
    gpu_use(g, PROG_H(stats));
    gpu_bind(g, B_DST, g->stats_rows);
    gpu_dispatch(g, g->n);
    gpu_use(g, PROG_H(stats_sum));
    gpu_bind(g, B_SRC, g->stats_rows);
    gpu_bind(g, B_DST, g->stats_out);
    gpu_set_u(g, PROG_H(stats_sum), U_count, groups);
    g->gc.DispatchCompute(1, 1, 1);
    g->gc.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    float q[STATS_Q];
    gpu_get(g, g->stats_out, 0, sizeof q, q);
    memset(out, 0, sizeof *out);
    out->n = sim->n;
    out->ekin = q[0];
    out->epot = q[1];
    out->eint = q[2];
    for (int d = 0; d < sim->dim; d++) out->momentum[d] = q[3 + d];
    out->max_speed = sqrt((double)q[9]);
    const double n_fluid = q[10];
    if (sim->P.rho && n_fluid > 0) {
        out->rho_min = q[7];
        out->rho_max = q[8];
        out->rho_mean = q[6] / n_fluid;
    }
    out->rho_max_all = sim->P.rho && sim->n ? q[11] : 0.0;
    g->stats = *out;
    g->stats_at = g->changes + 1;
    return true;
}

void gpu_stats_free(gpu *g)
{
    if (g->stats_rows) g->gl.DeleteBuffers(1, &g->stats_rows);
    if (g->stats_out) g->gl.DeleteBuffers(1, &g->stats_out);
}
