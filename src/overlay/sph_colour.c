/* What particles are coloured by (the field registry's colours, the index's
 * keys and neighbour counts) and the colour maps (see sph_overlay.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "overlay_internal.h"
#include "sph_search.h"

/* ---- shared by the overlay's files (overlay_internal.h) ---------------- */

/* The hash pass has filled the index at least once since the simulation was
 * made (before that, entries are zeros). */
/* Built by the start's measurement or by this step's passes, and not since
 * undone (sph_sim.h, fields_fresh): the index from the hash pass on; the
 * lists from the neighbours pass until the counting sort borrows their
 * buffer or a reorder moves the particles under them. */
bool sph_ov_index_built(const sph_sim *sim)
{
    return sim->in_pipeline[SPH_PASS_HASH] && sim->S.entries && (sim->fields_fresh & SPH_RES_ENTRIES);
}

bool sph_ov_lists_built(const sph_sim *sim)
{
    return sim->in_pipeline[SPH_PASS_NEIGHBOURS] && sim->S.nbr_start && (sim->fields_fresh & SPH_RES_LISTS);
}

float sph_ov_vec_norm(float *const v[3], int dim, uint32_t i)
{
    float s = 0;
    for (int d = 0; d < dim; d++) s += v[d][i] * v[d][i];
    return sqrtf(s);
}

/* ---- colour fields ------------------------------------------------------- */

const char *const sph_color_field_names[SPH_COLOR_COUNT] = {
#define SPH_COLOR_NAME(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about) colour,
    SPH_FIELDS(SPH_COLOR_NAME)
#undef SPH_COLOR_NAME
    [SPH_COLOR_KEY] = "key",
    [SPH_COLOR_NEIGHBOURS] = "neighbours",
    [SPH_COLOR_DFSPH_PRESSURE] = "dfsph-pressure",
};

int sph_color_field_find(const char *name)
{
    for (int i = 0; i < SPH_COLOR_COUNT; i++)
        if (*sph_color_field_names[i] && strcmp(name, sph_color_field_names[i]) == 0) return i;
    return -1;
}

const char *sph_color_field_unit(sph_color_field f, int dim)
{
    if (f == SPH_COLOR_DFSPH_PRESSURE) return sph_field_unit(SPH_FIELD_P, dim);
    return (int)f < SPH_FIELD_COUNT ? sph_field_unit((int)f, dim) : "1";
}

bool sph_color_field_categorical(sph_color_field f)
{
    return f == SPH_COLOR_KEY;
}



const char *sph_color_field_missing(const sph_sim *sim, sph_color_field f)
{
    if ((int)f >= 0 && (int)f < SPH_FIELD_COUNT) {
        const sph_field_info *fi = &sph_field_infos[f];
        if (!*fi->colour) return "not a colour";
        if (sim->P.field[f][0]) return NULL;
        /* the reason its pass is left out, e.g. "the scene has no viscosity effect" */
        const char *why = fi->made_by < SPH_PASS_COUNT ? sph_passes[fi->made_by]->skip_reason(&sim->def) : NULL;
        return why ? why : "the scene does not compute it";
    }
    switch (f) {
    case SPH_COLOR_KEY: return sim->in_pipeline[SPH_PASS_HASH] ? NULL : "the scene has no spatial hash (no neighbours, or search = brute)";
    case SPH_COLOR_NEIGHBOURS: return sim->in_pipeline[SPH_PASS_NEIGHBOURS] ? NULL : "no effect of the scene needs neighbours";
    case SPH_COLOR_DFSPH_PRESSURE: {
        const char *why = sph_passes[SPH_PASS_DFSPH]->skip_reason(&sim->def);
        return why ? why : sim->P.kappa && sim->P.kappa_v && sim->P.rho ? NULL : "the scene does not compute it";
    }
    default: return "unknown field";
    }
}

sph_color_field sph_color_field_default(const sph_sim *sim)
{
    return sim->P.rho ? SPH_COLOR_DENSITY : SPH_COLOR_SPEED;
}

int sph_color_field_of_pass(const sph_sim *sim, sph_pass_id p)
{
    const char *name = sph_passes[p]->highlight;
    int f = name ? sph_color_field_find(name) : -1;
    return f >= 0 && !sph_color_field_missing(sim, (sph_color_field)f) ? f : -1;
}


bool sph_color_field_values(const sph_sim *sim, sph_color_field f, float *out, float *lo, float *hi)
{
    if (sph_color_field_missing(sim, f)) return false;
    const sph_particles *P = &sim->P;
    const uint32_t n = sim->n;
    if ((int)f < SPH_FIELD_COUNT) { /* a field: a scalar as it is, a vector by its length */
        if (sph_field_infos[f].vector)
            for (uint32_t i = 0; i < n; i++) out[i] = sph_ov_vec_norm(P->field[f], sim->dim, i);
        else
            memcpy(out, P->field[f][0], n * sizeof *out);
    }
    switch (f) {
    case SPH_COLOR_KEY:
        memset(out, 0, n * sizeof *out);
        if (sph_ov_index_built(sim))
            for (uint32_t s = 0; s < n; s++) {
                uint32_t i = sim->S.entries[s].index;
                if (i < n) out[i] = (float)sim->S.entries[s].key;
            }
        break;
    case SPH_COLOR_NEIGHBOURS:
        memset(out, 0, n * sizeof *out);
        if (sph_ov_lists_built(sim))
            for (uint32_t i = 0; i < n; i++) out[i] = (float)(sim->S.nbr_start[i + 1] - sim->S.nbr_start[i]);
        break;
    case SPH_COLOR_DFSPH_PRESSURE:
        for (uint32_t i = 0; i < n; i++) out[i] = sph_sim_pressure(sim, i);
        break;
    default:
        if ((int)f >= SPH_FIELD_COUNT) return false;
        break;
    }
    float a = INFINITY, b = -INFINITY;
    for (uint32_t i = 0; i < n; i++) {
        if (!isfinite(out[i])) continue;
        if (out[i] < a) a = out[i];
        if (out[i] > b) b = out[i];
    }
    if (a > b) a = b = 0;
    *lo = a;
    *hi = b;
    return true;
}

/* Viridis as a polynomial in t (a least-squares fit of matplotlib's table,
 * within about 1/255 of it), evaluated in double so every machine gets the
 * same bytes. */
uint32_t sph_colormap_viridis(float t)
{
    static const double c[7][3] = {
        {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
        {0.1050930431085774, 1.404613529898575, 1.384590162594685},
        {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
        {-4.634230498983486, -5.799100973351585, -19.33244095627987},
        {6.228269936347081, 14.17993336680509, 56.69055260068105},
        {4.776384997670288, -13.74514537774601, -65.35303263337234},
        {-5.435455855934631, 4.645852612178535, 26.3124352495832},
    };
    if (t != t) return SPH_RGBA(128, 128, 128, 255);
    double x = t < 0 ? 0 : t > 1 ? 1 : t;
    /* quantise first: 256 levels, as a colour-map texture would */
    x = floor(x * 255.0 + 0.5) / 255.0;
    int rgb[3];
    for (int k = 0; k < 3; k++) {
        double v = c[6][k];
        for (int j = 5; j >= 0; j--) v = v * x + c[j][k];
        v = v < 0 ? 0 : v > 1 ? 1 : v;
        rgb[k] = (int)floor(v * 255.0 + 0.5);
    }
    return SPH_RGBA(rgb[0], rgb[1], rgb[2], 255);
}

uint32_t sph_colormap_category(uint32_t key)
{
    static const uint8_t tab10[10][3] = {
        {31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},  {148, 103, 189},
        {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207},
    };
    const uint8_t *c = tab10[key % 10];
    return SPH_RGBA(c[0], c[1], c[2], 255);
}

uint32_t sph_color_of(sph_color_field f, float v, float lo, float hi)
{
    if (sph_color_field_categorical(f)) return sph_colormap_category(v >= 0 && v < 4294967040.0f ? (uint32_t)v : 0);
    /* a range within rounding of one value is one value: the middle colour */
    float t = hi - lo > 1e-6f * fmaxf(fabsf(hi), fabsf(lo)) ? (v - lo) / (hi - lo) : 0.5f;
    return sph_colormap_viridis(t);
}

/* Walls drawn in their field's full colour look like fluid (in 3D the far
 * walls coloured by density are the water's yellow): dimmed more than half
 * way to a mid grey the fluid stands out, and the wall's value (e.g. the
 * extrapolated wall pressure) still reads on the colour bar's hue. */
uint32_t sph_color_dimmed(uint32_t c)
{
    uint32_t out = c & 0xFF000000u;
    for (int k = 0; k < 3; k++) {
        uint32_t v = (c >> (8 * k)) & 255u;
        v = (v * (100 - SPH_WALL_DIM_PERCENT) + SPH_WALL_GREY * SPH_WALL_DIM_PERCENT + 50) / 100;
        out |= v << (8 * k);
    }
    return out;
}
