/* validate couette: start-up Couette flow, the top wall moving at U from
 * t = 0 ([domain] wall_velocity of scenes/validate/couette.ini), the bottom
 * wall still, against the series solution (validate_ref.c). Scale: U.
 * Target: 2 % at every sampled time. */
#include "val_channel.h"

static double width(const sph_scene_def *def)
{
    return (double)def->domain_max[1] - def->domain_min[1];
}

static double exact(const sph_scene_def *def, double y, double t)
{
    return val_couette(y, t, def->wall_velocity[0], def->viscosity, width(def), 400);
}

static double scale(const sph_scene_def *def)
{
    return def->wall_velocity[0];
}

int val_run_couette(const val_ctx *c, const val_problem *p)
{
    static const val_channel ch = {"couette.ini", "couette", "Start-up Couette flow", exact, scale, "U", 0.02,
                                   0.02};
    return val_channel_run(c, p, &ch);
}
