/* Live accuracy figures: density error and energy drift, updated after each
 * step for a view that shows them beside the timings (study.h). */
#include <math.h>
#include <string.h>

#include "study.h"
#include "sph_walls.h"

void study_live_reset(study_live *l)
{
    memset(l, 0, sizeof *l);
}

void study_live_update(study_live *l, const sph_sim *sim)
{
    sph_stats s;
    sph_sim_stats(sim, &s);
    /* against the density the pressure model holds, as the HUD's: a solver's rho_rest, else the equation of
     * state's reference */
    double e = s.ekin + s.epot + s.eint, held = sph_density_held(sim, NULL);
    if (!l->started) {
        l->started = true;
        l->e0 = e;
        l->scale = fabs(e);
    }
    l->scale = fmax(l->scale, s.ekin);
    l->energy_drift = l->scale > 0 ? (e - l->e0) / l->scale : 0.0;
    l->density_error = 0;
    l->density_rms = 0;
    if (sim->P.rho && sim->n) {
        double sum = 0;
        uint32_t n_fluid = 0;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(&sim->P, i)) continue; /* wall particles (wall_model = particles) */
            double d = sim->P.rho[i] / held - 1.0;
            sum += d * d;
            n_fluid++;
        }
        l->density_rms = n_fluid ? sqrt(sum / n_fluid) : 0.0;
        l->density_error = (s.rho_max - held) / held;
    }
}
