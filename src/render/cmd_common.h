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
    float range[2];           /* --range LO:HI */
    int w, h;                 /* --size WxH */
} view_opts;

#define VIEW_OPTS_HELP                                                                          \
    "  --size WxH          image size in pixels (default %dx%d)\n"                                 \
    "  --color FIELD       colour by: density pressure speed key neighbours pressure-acc viscosity-acc\n" \
    "  --range LO:HI       fixed colour range (default: each frame's min and max)\n"               \
    "  --overlay NAME,...  switch overlays on (repeatable; 'all', 'none'); default: hud,legend\n"  \
    "  --no-overlay NAME   switch one off\n"                                                        \
    "  --select ID         the particle the neighbours overlay and the index strip follow\n"       \
    "  --slice Z           3D: the plane z = Z [m] the grid, keys and collisions show on\n"     \
    "  --camera Y:P[:Z]    orbit yaw and pitch [deg] (3D) and zoom (default 30:25:1)\n"         \
    "  --center X:Y[:Z]    the point [m] the view centres on (default: the domain's centre)\n"

void view_opts_init(view_opts *o, int w, int h);
/* Parses argv[*i] if it is one of these options (advancing *i over its
 * value). Returns 1 if taken, 0 if not one of these, -1 on a bad value
 * (message printed). `cmd` names the command in messages. */
int view_opts_parse(view_opts *o, const char *cmd, int argc, char **argv, int *i);
/* The view for a simulation from the options; false (message) on a bad field or particle. */
bool view_opts_apply(const view_opts *o, const char *cmd, const sph_sim *sim, sph_view *v);
/* The index a particle is stored at now (the reorder pass moves particles
 * in memory; their id stays), or -1. */
int32_t sim_index_of_id(const sph_sim *sim, long id);
/* Option helpers in the style of cmd_run.c. */
/* Parses a comma-separated overlay list into bits; false (message) on an unknown name. */
bool overlay_list(const char *cmd, const char *list, unsigned *bits, bool *none);

#endif
