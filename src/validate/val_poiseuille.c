/* validate poiseuille: start-up plane Poiseuille flow between no-slip walls,
 * driven by the body force F (scenes/validate/poiseuille.ini, F the scene's
 * gravity along x), against the series solution of Morris, Fox & Zhu 1997,
 * eq. 21 (validate_ref.c). Scale: the steady centre-line speed F L^2 / (8 nu).
 * Targets: 5 % during start-up, 2 % at steady state (t = L^2 / nu). */
#include "val_channel.h"

static double width(const sph_scene_def *def)
{
    return (double)def->domain_max[1] - def->domain_min[1];
}

static double exact(const sph_scene_def *def, double y, double t)
{
    return val_poiseuille(y, t, def->gravity[0], def->viscosity, width(def), 200);
}

static double scale(const sph_scene_def *def)
{
    double L = width(def);
    return def->gravity[0] * L * L / (8.0 * def->viscosity);
}

int val_run_poiseuille(const val_ctx *c, const val_problem *p)
{
    static const val_channel ch = {"poiseuille.ini", "poiseuille", "Start-up Poiseuille flow", exact, scale, "u_max",
                                   0.05, 0.02};
    return val_channel_run(c, p, &ch);
}
