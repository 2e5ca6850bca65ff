/* What a simulation says about itself, beside its stepping (sph_sim.c): the
 * passes' timings, the statistics (energy, momentum, the fluid's density range),
 * the pressure a particle has under the pressure model in use and the density
 * that model holds. */
#include "sph_sim.h"
#include "sph_walls.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sph_sim_reset_timings(sph_sim *sim)
{
    memset(sim->timing, 0, sizeof sim->timing);
    sim->step_ms_acc = 0;
    sim->step_ms_count = 0;
}

void sph_sim_record_step_times(sph_sim *sim, const double ms[SPH_PASS_COUNT])
{
    double sum = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (!(ms[p] >= 0)) continue;
        sim->timing[p].total_ms += ms[p];
        sim->timing[p].last_ms = ms[p];
        sum += ms[p];
    }
    sim->step_ms[sim->step_ms_count++ % SPH_STEP_WINDOW] = sum;
}

void sph_sim_collect_times(sph_sim *sim)
{
    if (sim->backend && sim->backend->collect_times) sim->backend->collect_times(sim->backend, sim, true);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median, not the mean: one stalled step (the machine busy for a moment) moved the window's live speed-ups
 * by a factor of 2 between identical runs (x3.03, x2.67, x5.97 for L7 over L6 in lesson 7). */
double sph_sim_step_ms(const sph_sim *sim, int *steps)
{
    int k = sim->step_ms_count < SPH_STEP_WINDOW ? (int)sim->step_ms_count : SPH_STEP_WINDOW;
    if (steps) *steps = k;
    if (!k) return NAN;
    double v[SPH_STEP_WINDOW];
    memcpy(v, sim->step_ms, (size_t)k * sizeof *v);
    qsort(v, (size_t)k, sizeof *v, cmp_double);
    return k % 2 ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
}

/* Internal energy per unit mass that the equation of state stores at density
 * rho: e = integral from rho0 to rho of p / rho'^2. With it, kinetic +
 * gravitational + internal energy is what the pressure force conserves. */
static double eos_energy(const sph_scene_def *def, double r0, double rho)
{
    double k = def->stiffness;
    if (def->negative_pressure == SPH_NEGP_CLAMP && rho < r0) return 0.0;
    if (def->eos == SPH_EOS_TAIT) {
        double g = def->tait_gamma, B = k * r0 / g;
        return B * ((pow(rho, g - 1) - pow(r0, g - 1)) / ((g - 1) * pow(r0, g)) + 1.0 / rho - 1.0 / r0);
    }
    return k * (log(rho / r0) + r0 / rho - 1.0);
}

double sph_stats_energy(const sph_stats *s)
{
    return s->ekin + s->epot + s->eint;
}

float sph_sim_pressure(const sph_sim *sim, uint32_t i)
{
    const sph_particles *P = &sim->P;
    switch (sim->def.pressure_solver) {
    case SPH_PSOLVER_PCISPH: return P->p_pci ? P->p_pci[i] : 0.0f;
    case SPH_PSOLVER_DFSPH:
        return P->kappa && P->kappa_v && P->rho ? P->rho[i] * (P->kappa[i] + P->kappa_v[i]) : 0.0f;
    default: return P->p ? P->p[i] : 0.0f;
    }
}

double sph_density_held(const sph_sim *sim, const char **name)
{
    const bool solver = sim->def.pressure_solver != SPH_PSOLVER_EOS && sim->solver.rho_rest > 0;
    if (name) *name = solver ? "rho_rest" : "rho0";
    return solver ? sim->solver.rho_rest : sim->eos_rho0;
}

double sph_sim_energy_drift(const sph_sim *sim)
{
    if (sim->step < 1) return NAN;
    sph_stats s;
    sph_sim_stats(sim, &s);
    double scale = fmax(fabs(sim->energy_ref), s.ekin);
    return scale > 0 ? (sph_stats_energy(&s) - sim->energy_ref) / scale : 0.0;
}

void sph_sim_stats(const sph_sim *sim, sph_stats *out)
{
    const sph_particles *P = &sim->P;
    const sph_mask reads = SPH_SYNC_FIELD(SPH_FIELD_POS) | SPH_SYNC_FIELD(SPH_FIELD_VEL) |
                           SPH_SYNC_FIELD(SPH_FIELD_MASS) | SPH_SYNC_FIELD(SPH_FIELD_RHO) |
                           SPH_SYNC_FIELD(SPH_FIELD_P) | SPH_SYNC_FIELD(SPH_FIELD_FIXED);
    /* a backend reduces on the device rather than download five fields;
     * a fresh host copy is summed here (in double) as on the CPU */
    if (sim->backend && sim->backend->stats && (sim->backend->stale & reads) &&
        sim->backend->stats(sim->backend, sim, out))
        return;
    sph_sim_sync(sim, reads);
    memset(out, 0, sizeof *out);
    out->n = sim->n;
    double rmin = INFINITY, rmax = -INFINITY, rsum = 0;
    uint32_t n_fluid = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(P, i)) continue; /* wall particles are no part of the fluid's energy or density */
        n_fluid++;
        double v2 = 0;
        for (int d = 0; d < sim->dim; d++) {
            double v = P->vel[d][i];
            v2 += v * v;
            out->momentum[d] += P->mass[i] * v;
        }
        out->ekin += 0.5 * P->mass[i] * v2;
        if (sim->def.effects & SPH_EFFECT(GRAVITY))
            for (int d = 0; d < sim->dim; d++)
                out->epot -= P->mass[i] * sim->def.gravity[d] * ((double)P->pos[d][i] - sim->def.domain_min[d]);
        if (P->p && P->rho[i] > 0) out->eint += P->mass[i] * eos_energy(&sim->def, sim->eos_rho0, P->rho[i]);
        if (v2 > out->max_speed) out->max_speed = v2;
        if (P->rho) {
            double r = P->rho[i];
            rsum += r;
            if (r < rmin) rmin = r;
            if (r > rmax) rmax = r;
        }
    }
    out->max_speed = sqrt(out->max_speed);
    if (P->rho)
        for (uint32_t i = 0; i < sim->n; i++)
            if (P->rho[i] > out->rho_max_all) out->rho_max_all = P->rho[i];
    if (P->rho && n_fluid) {
        out->rho_min = rmin;
        out->rho_max = rmax;
        out->rho_mean = rsum / n_fluid;
    }
}
