/* Options shared by `sphlab render` and `sphlab view`: what to draw. */
#ifndef SPH_CMD_COMMON_H
#define SPH_CMD_COMMON_H

#include <stdbool.h>

#include "app.h"
#include "render.h"

typedef struct view_opts {
    const char *color;        /* --color FIELD */
    unsigned ov_on, ov_off;   /* --overlay / --no-overlay */
    bool ov_none;             /* --overlay none */
    long select_id;           /* --select ID, -1 none */
    bool has_slice;
    double slice;             /* --slice Z [m] */
    bool has_orbit;
    float yaw, pitch, zoom;   /* --camera YAW:PITCH[:ZOOM] */
    int n_center;
    float center[3];          /* --center X:Y[:Z] [m] */
    bool has_range;
    float range[2];           /* --range LO,HI (or LO:HI) [the field's unit] */
    bool range_run;           /* --range run: one range over the whole run (render) */
    bool range_frame;         /* --range frame: each frame's own min and max */
    int w, h;                 /* --size WxH */
} view_opts;

void view_opts_init(view_opts *o, int w, int h);
/* Takes the drawing options (--size, --color, --range, --overlay, --no-overlay,
 * --select, --slice, --center, --camera; the option table parsed them) over
 * the defaults; false (message naming `cmd`) on a bad value. */
bool view_opts_take(view_opts *vo, const app_opts *o, const char *cmd);
/* The view for a simulation from the options; false (message) on a bad field or particle. */
bool view_opts_apply(const view_opts *o, const char *cmd, const sph_sim *sim, sph_view *v);
/* The index a particle is stored at now (the reorder pass moves particles
 * in memory; their id stays), or -1. */
int32_t sim_index_of_id(const sph_sim *sim, long id);
/* Parses a comma-separated overlay list into bits; false (message) on an unknown name. */
bool overlay_list(const char *cmd, const char *list, unsigned *bits, bool *none);

#endif
