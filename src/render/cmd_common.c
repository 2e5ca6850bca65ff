/* Options shared by `sphlab render` and `sphlab view` (see cmd_common.h). */
#include "cmd_common.h"

#include <math.h>
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
            /* render promises the same bytes every run: wall-clock timings
             * only when named (--overlay timings) */
            unsigned clock = strcmp(cmd, "render") == 0 ? SPH_OV_BIT(TIMINGS) : 0;
            *bits |= ((1u << SPH_OV_COUNT) - 1) & ~clock;
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

/* A:B or A:B:C (c may be NULL: two only), each a finite number: a NaN or an
 * infinite centre or angle drew an empty or nonsense frame with exit 0. */
static bool parse_pair(const char *s, float *a, float *b, float *c, char sep)
{
    char *end;
    *a = strtof(s, &end);
    if (end == s || *end != sep || !isfinite(*a)) return false;
    const char *t = end + 1;
    *b = strtof(t, &end);
    if (end == t || !isfinite(*b)) return false;
    if (*end == '\0') return true;
    if (!c || *end != sep) return false;
    t = end + 1;
    *c = strtof(t, &end);
    return end != t && *end == '\0' && isfinite(*c);
}

bool view_opts_take(view_opts *vo, const app_opts *o, const char *cmd)
{
    if (o->size[0]) {
        vo->w = (int)o->size[0];
        vo->h = (int)o->size[1];
    }
    if (o->color) {
        if (sph_color_field_find(o->color) < 0) {
            fprintf(stderr, "sphlab %s: unknown colour field '%s' (accepted:", cmd, o->color);
            for (int k = 0; k < SPH_COLOR_COUNT; k++)
                if (*sph_color_field_names[k]) fprintf(stderr, " %s", sph_color_field_names[k]);
            fprintf(stderr, ")\n");
            return false;
        }
        vo->color = o->color;
    }
    if (o->range) {
        /* 'run' only where the whole run is known before the first frame (render) */
        bool run_ok = strcmp(cmd, "render") == 0;
        if (strcmp(o->range, "frame") == 0) {
            vo->range_frame = true;
        } else if (run_ok && strcmp(o->range, "run") == 0) {
            vo->range_run = true;
        } else {
            float *r = vo->range;
            bool pair = parse_pair(o->range, &r[0], &r[1], NULL, ',') || parse_pair(o->range, &r[0], &r[1], NULL, ':');
            if (!pair || !isfinite(r[0]) || !isfinite(r[1]) || !(r[1] > r[0])) {
                fprintf(stderr, "sphlab %s: --range '%s': want LO,HI (finite numbers, LO < HI), %sor 'frame'\n", cmd,
                        o->range, run_ok ? "'run' " : "");
                return false;
            }
            vo->has_range = true;
        }
    }
    for (int i = 0; i < o->overlay.n; i++)
        if (!overlay_list(cmd, o->overlay.v[i], &vo->ov_on, &vo->ov_none)) return false;
    for (int i = 0; i < o->no_overlay.n; i++)
        if (!overlay_list(cmd, o->no_overlay.v[i], &vo->ov_off, NULL)) return false;
    if (o->select >= 0) vo->select_id = o->select;
    if (!isnan(o->slice)) {
        vo->slice = o->slice;
        vo->has_slice = true;
    }
    if (o->center) {
        vo->center[2] = 0;
        if (!parse_pair(o->center, &vo->center[0], &vo->center[1], &vo->center[2], ':')) {
            fprintf(stderr, "sphlab %s: --center '%s': want X:Y or X:Y:Z in metres, finite numbers\n", cmd, o->center);
            return false;
        }
        vo->n_center = 3;
    }
    if (o->camera) {
        vo->zoom = 1;
        if (!parse_pair(o->camera, &vo->yaw, &vo->pitch, &vo->zoom, ':') || !(vo->zoom > 0) || vo->pitch < -89 ||
            vo->pitch > 89) {
            fprintf(stderr, "sphlab %s: --camera '%s': want YAW:PITCH[:ZOOM] in degrees, finite, pitch within +-89, zoom > 0\n",
                    cmd, o->camera);
            return false;
        }
        vo->has_orbit = true;
    }
    return true;
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
            /* the solver's own pressure has a colour: name it */
            const sph_pressure_solver ps = v->field == SPH_COLOR_PRESSURE ? sim->def.pressure_solver : SPH_PSOLVER_EOS;
            fprintf(stderr, "sphlab %s: cannot colour by %s: %s%s\n", cmd, o->color, why,
                    ps == SPH_PSOLVER_PCISPH  ? " (PCISPH's pressure: --color pcisph-pressure)"
                    : ps == SPH_PSOLVER_DFSPH ? " (DFSPH's pressure rho (kappa + kappa_v): --color dfsph-pressure)"
                                              : "");
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
    /* accepted, but would change nothing or show nothing: said, not refused (a review found them silent) */
    if (o->has_slice && sim->dim == 2)
        fprintf(stderr, "sphlab %s: note: --slice %g: a 2D scene has no slice (it cuts 3D scenes at z)\n", cmd,
                o->slice);
    else if (o->has_slice && (o->slice < sim->def.domain_min[2] || o->slice > sim->def.domain_max[2]))
        fprintf(stderr, "sphlab %s: warning: --slice %g m is outside the domain's z, %g to %g m: no particle is cut\n",
                cmd, o->slice, (double)sim->def.domain_min[2], (double)sim->def.domain_max[2]);
    for (int d = 0; d < o->n_center && d < sim->dim; d++)
        if (o->center[d] < sim->def.domain_min[d] || o->center[d] > sim->def.domain_max[d]) {
            fprintf(stderr, "sphlab %s: warning: --center: %c = %g m is outside the domain's %g to %g m: the view may "
                    "show no particle\n", cmd, "xyz"[d], (double)o->center[d], (double)sim->def.domain_min[d],
                    (double)sim->def.domain_max[d]);
            break;
        }
    if (o->has_orbit) {
        v->orbit.yaw = o->yaw;
        v->orbit.pitch = o->pitch;
        v->orbit.zoom = o->zoom;
    }
    if (o->n_center)
        for (int d = 0; d < 3; d++)
            /* --center is absolute; the camera works in the simulation's frame (sim->origin) */
            v->orbit.pan[d] = d < sim->dim ? (float)(o->center[d] - sim->origin[d]) -
                                                 0.5f * ((float)sim->def.domain_min[d] + (float)sim->def.domain_max[d])
                                           : 0.0f;
    if (o->has_range) {
        v->fixed_range = true;
        v->range[0] = o->range[0];
        v->range[1] = o->range[1];
    }
    return true;
}
