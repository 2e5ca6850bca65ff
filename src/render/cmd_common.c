/* Options shared by `sphlab render` and `sphlab view` (see cmd_common.h). */
#include "cmd_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void view_opts_init(view_opts *o, int w, int h)
{
    memset(o, 0, sizeof *o);
    o->select_id = -1;
    o->w = w;
    o->h = h;
}

bool overlay_list(const char *cmd, const char *list, unsigned *bits, bool *none)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (strcmp(tok, "all") == 0) {
            *bits |= (1u << SPH_OV_COUNT) - 1;
        } else if (strcmp(tok, "none") == 0) {
            if (none) *none = true;
        } else {
            int k = sph_overlay_find(tok);
            if (k < 0) {
                fprintf(stderr, "sphlab %s: unknown overlay '%s' (accepted:", cmd, tok);
                for (int j = 0; j < SPH_OV_COUNT; j++) fprintf(stderr, " %s", sph_overlay_names[j]);
                fprintf(stderr, ", all, none)\n");
                return false;
            }
            *bits |= 1u << k;
        }
    }
    return true;
}

static bool parse_pair(const char *s, float *a, float *b, float *c, char sep)
{
    char *end;
    *a = strtof(s, &end);
    if (end == s || *end != sep) return false;
    const char *t = end + 1;
    *b = strtof(t, &end);
    if (end == t) return false;
    if (*end == '\0') return true;
    if (!c || *end != sep) return false;
    t = end + 1;
    *c = strtof(t, &end);
    return end != t && *end == '\0';
}

int view_opts_parse(view_opts *o, const char *cmd, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *v;
    if (app_opt_is(a, "--size")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--size"))) return -1;
        int w, h;
        char x;
        if (sscanf(v, "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w < 64 || h < 64 || w > 8192 || h > 8192) {
            fprintf(stderr, "sphlab %s: --size '%s': want WxH, 64 to 8192 pixels a side\n", cmd, v);
            return -1;
        }
        o->w = w;
        o->h = h;
    } else if (app_opt_is(a, "--color") || app_opt_is(a, "--colour")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, app_opt_is(a, "--color") ? "--color" : "--colour"))) return -1;
        if (sph_color_field_find(v) < 0) {
            fprintf(stderr, "sphlab %s: unknown colour field '%s' (accepted:", cmd, v);
            for (int k = 0; k < SPH_COLOR_COUNT; k++) fprintf(stderr, " %s", sph_color_field_names[k]);
            fprintf(stderr, ")\n");
            return -1;
        }
        o->color = v;
    } else if (app_opt_is(a, "--range")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--range"))) return -1;
        if (!parse_pair(v, &o->range[0], &o->range[1], NULL, ':') || !(o->range[1] > o->range[0])) {
            fprintf(stderr, "sphlab %s: --range '%s': want LO:HI with LO < HI\n", cmd, v);
            return -1;
        }
        o->has_range = true;
    } else if (app_opt_is(a, "--overlay")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--overlay")) || !overlay_list(cmd, v, &o->ov_on, &o->ov_none)) return -1;
    } else if (app_opt_is(a, "--no-overlay")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--no-overlay")) || !overlay_list(cmd, v, &o->ov_off, NULL)) return -1;
    } else if (app_opt_is(a, "--select")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--select")) || !app_parse_int("--select", v, 0, 2000000000L, &o->select_id))
            return -1;
    } else if (app_opt_is(a, "--slice")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--slice")) || !app_parse_double("--slice", v, -1e6, 1e6, &o->slice))
            return -1;
        o->has_slice = true;
    } else if (app_opt_is(a, "--center")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--center"))) return -1;
        o->center[2] = 0;
        if (!parse_pair(v, &o->center[0], &o->center[1], &o->center[2], ':')) {
            fprintf(stderr, "sphlab %s: --center '%s': want X:Y or X:Y:Z in metres\n", cmd, v);
            return -1;
        }
        o->n_center = 3;
    } else if (app_opt_is(a, "--camera")) {
        if (!(v = app_opt_value(cmd, argc, argv, i, "--camera"))) return -1;
        o->zoom = 1;
        if (!parse_pair(v, &o->yaw, &o->pitch, &o->zoom, ':') || !(o->zoom > 0) || o->pitch < -89 || o->pitch > 89) {
            fprintf(stderr, "sphlab %s: --camera '%s': want YAW:PITCH[:ZOOM] in degrees, pitch within +-89, zoom > 0\n",
                    cmd, v);
            return -1;
        }
        o->has_orbit = true;
    } else {
        return 0;
    }
    return 1;
}

int32_t sim_index_of_id(const sph_sim *sim, long id)
{
    if (id < 0) return -1;
    sph_sim_sync(sim, SPH_SYNC_ID);
    for (uint32_t i = 0; i < sim->n; i++)
        if (sim->P.id[i] == (uint32_t)id) return (int32_t)i;
    return -1;
}

bool view_opts_apply(const view_opts *o, const char *cmd, const sph_sim *sim, sph_view *v)
{
    *v = sph_view_default(sim);
    if (o->color) {
        v->field = (sph_color_field)sph_color_field_find(o->color);
        const char *why = sph_color_field_missing(sim, v->field);
        if (why) {
            fprintf(stderr, "sphlab %s: cannot colour by %s: %s\n", cmd, o->color, why);
            return false;
        }
    }
    if (o->ov_none) v->overlays = 0;
    v->overlays = (v->overlays | o->ov_on) & ~o->ov_off;
    if (o->select_id >= 0) {
        v->selected = sim_index_of_id(sim, o->select_id);
        if (v->selected < 0) {
            fprintf(stderr, "sphlab %s: --select %ld: no such particle (the scene has %u, ids 0 to %u)\n", cmd,
                    o->select_id, sim->n, sim->n ? sim->n - 1 : 0);
            return false;
        }
    }
    if (o->has_slice) v->slice_z = (float)o->slice;
    if (o->has_orbit) {
        v->orbit.yaw = o->yaw;
        v->orbit.pitch = o->pitch;
        v->orbit.zoom = o->zoom;
    }
    if (o->n_center)
        for (int d = 0; d < 3; d++)
            v->orbit.pan[d] = d < sim->dim ? o->center[d] - 0.5f * (sim->def.domain_min[d] + sim->def.domain_max[d]) : 0.0f;
    if (o->has_range) {
        v->fixed_range = true;
        v->range[0] = o->range[0];
        v->range[1] = o->range[1];
    }
    return true;
}
