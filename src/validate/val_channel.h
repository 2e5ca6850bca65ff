/* The channel problems (poiseuille, couette): the shared run and measurement
 * of val_channel.c, each problem's exact solution its own. */
#ifndef SPH_VAL_CHANNEL_H
#define SPH_VAL_CHANNEL_H

#include "validate_run.h"

typedef struct val_channel {
    const char *scene;      /* scenes/validate/... */
    const char *base;       /* output file names */
    const char *title;
    /* the exact velocity u(y, t) [m/s] of the scene's flow */
    double (*exact)(const sph_scene_def *def, double y, double t);
    /* its scale: the steady centre-line speed (Poiseuille) or the wall's (Couette) [m/s] */
    double (*scale)(const sph_scene_def *def);
    const char *scale_name; /* the scale in the verdict line: "u_max", "U" */
    double startup_tol, steady_tol; /* [1] of the scale: before the last sample, at it */
} val_channel;

/* Sample times [s] in units of L^2 / nu = 1 s: Morris et al. 1997, Fig. 4. */
#define VAL_CHANNEL_TIMES 5
extern const double val_channel_times[VAL_CHANNEL_TIMES];

int val_channel_run(const val_ctx *c, const val_problem *p, const val_channel *ch);

#endif
