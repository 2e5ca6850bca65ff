/* Limits a valid scene must also meet, set by number formats and by the
 * machine rather than by any one key: the float precision of positions over
 * the domain, the cell counts of the search, and memory. Checked last by
 * sph_scene_validate, so `sphlab check` refuses such a scene with the reason
 * before anything is allocated. */
#include "sph_memory.h"
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* "file:line" of a key's value ("file" for a default, "--set" for an override). */
static int key_line(const sph_scene_def *def, const char *section, const char *name)
{
    for (int i = 0; i < sph_scene_key_count; i++)
        if (strcmp(sph_scene_keys[i].section, section) == 0 && strcmp(sph_scene_keys[i].name, name) == 0)
            return def->origin[i].line;
    return 0;
}

static const char *key_place(const sph_scene_def *def, const char *section, const char *name, char *buf, size_t n)
{
    int line = key_line(def, section, name);
    if (line > 0)
        snprintf(buf, n, "%s:%d", def->file, line);
    else
        snprintf(buf, n, "%s", line < 0 ? "--set" : def->file);
    return buf;
}

/* key_place, and " and --set" when the limit's other key (h) came from --set: `--set kernels.h=0.0001` was
 * refused naming the file's [domain] line alone */
static const char *key_place_with(const sph_scene_def *def, const char *section, const char *name,
                                  const char *other_section, const char *other, char *buf, size_t n)
{
    key_place(def, section, name, buf, n);
    if (key_line(def, other_section, other) < 0 && key_line(def, section, name) >= 0) {
        size_t len = strlen(buf);
        snprintf(buf + len, n - len, " and --set");
    }
    return buf;
}

/* Distance from x to the next float above it. */
static double float_step(double x)
{
    float f = (float)fabs(x);
    return (double)nextafterf(f, INFINITY) - f;
}

double sph_scene_position_step_bound(const sph_scene_def *def)
{
    return (double)def->h * SPH_POSITION_STEP;
}

double sph_scene_origin(const sph_scene_def *def, int d)
{
    double lo = def->domain_min[d], hi = def->domain_max[d];
    return lo > 0 ? lo : hi < 0 ? hi : 0.0;
}

/* Positions are floats relative to sph_scene_origin (sph_sim_create), so
 * the largest coordinate within the domain is its end furthest from that
 * point, and there a float's step is ulp(x). The search's cells exceed h by
 * 2^-10 h (sph_cells) so that rounding cannot put a pair closer than h two
 * cells apart; a pair's two coordinates each round by up to ulp / 2, so ulp
 * must stay within half that margin: ulp(x) <= 2^-11 h (SPH_POSITION_STEP).
 * The kernels then see r / h to 5e-4. That allows 4096-8192 h from the
 * frame's origin: a domain from 0, or far from 0, 4096 h long at least. */
static sph_error_code check_precision(const sph_scene_def *def, sph_error *err)
{
    const double bound = sph_scene_position_step_bound(def);
    for (int d = 0; d < def->dim; d++) {
        double o = sph_scene_origin(def, d);
        double far = fmax(fabs(def->domain_min[d] - o), fabs(def->domain_max[d] - o));
        double step = float_step(far);
        if (step <= bound) continue;
        /* the furthest reach that keeps the bound: below the power of two where the step doubles past it */
        double reach = ldexp(1.0, (int)floor(log2(bound)) + 24);
        const char axis = sph_axis_names[d][0];
        char loc[300];
        return sph_fail(err, SPH_ERR_RANGE,
                        "%s: [domain] %c from %g to %g m: positions are floats relative to %g m (the domain's "
                        "point nearest 0), and %g m from it a float's step is %.3g m, more than h / 2048 = %.3g m "
                        "that the neighbour search needs with h = %g m (accepted: a domain reaching at most %g m "
                        "from that point along %c at this h, or h of at least %.3g m)",
                        key_place_with(def, "domain", "max", "kernels", "h", loc, sizeof loc), axis, def->domain_min[d],
                        def->domain_max[d], o, far, step, bound, (double)def->h, reach, axis,
                        step / SPH_POSITION_STEP);
    }
    return SPH_ERR_OK;
}

/* Cell counts in double: an int would overflow first (a periodic axis of
 * 2e6 m with h = 0.5 mm has 4e9 cells). */
static sph_error_code check_cells(const sph_scene_def *def, sph_error *err)
{
    const double size = (double)def->h * (1.0 + 1.0 / 1024);
    char loc[300];
    for (int d = 0; d < def->dim; d++) {
        double count = floor((def->domain_max[d] - def->domain_min[d]) / size) + 1;
        if ((def->periodic & (1u << d) || def->search == SPH_SEARCH_GRID) && count > SPH_CELL_LIMIT)
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [domain] along %c the search needs %.3g cells of h, more than %d", 
                            key_place_with(def, "domain", "max", "kernels", "h", loc, sizeof loc), sph_axis_names[d][0], count,
                            SPH_CELL_LIMIT);
    }
    if (def->search == SPH_SEARCH_GRID) {
        double cells = sph_memory_grid_cells(def);
        if (cells > SPH_GRID_CELLS_MAX)
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [search] method = grid needs %.3g cells for this domain and h (at most %d); use "
                            "method = hash",
                            key_place(def, "search", "method", loc, sizeof loc), cells, SPH_GRID_CELLS_MAX);
    }
    return SPH_ERR_OK;
}

/* A particle occupies one key, so at most n keys of the hash table are ever
 * used; at 64 n keys, cells that share a key are already rare (1.5%), so a
 * larger table only costs memory (2^31 keys on 100 particles asked 16 GiB).
 * Small scenes may still try tables up to 2^20 keys (4 MiB). */
static sph_error_code check_table(const sph_scene_def *def, sph_error *err)
{
    if (def->search != SPH_SEARCH_HASH || !def->table_size) return SPH_ERR_OK;
    double n = sph_scene_particle_count(def) + sph_wall_particle_count(def);
    double most = fmax(SPH_TABLE_PER_PARTICLE * n, SPH_TABLE_FLOOR);
    if (def->table_size <= most) return SPH_ERR_OK;
    sph_mem_estimate e;
    sph_memory_estimate(def, &e);
    double bytes = 0;
    for (int i = 0; i < e.n; i++)
        if (strcmp(e.item[i].name, "hash table") == 0) bytes = e.item[i].bytes;
    char loc[300], b[32];
    return sph_fail(err, SPH_ERR_RANGE,
                    "%s: [search] table_size = %u for %.0f particles needs %s of keys; a particle occupies one "
                    "key, so a table above %d keys a particle and above %d keys only costs memory (accepted: 0, "
                    "the particle count, up to %.0f)",
                    key_place(def, "search", "table_size", loc, sizeof loc), def->table_size, n,
                    sph_memory_text(bytes, b, sizeof b), SPH_TABLE_PER_PARTICLE, SPH_TABLE_FLOOR, most);
}

sph_error_code sph_scene_check_limits(const sph_scene_def *def, sph_error *err)
{
    sph_error_code c = check_cells(def, err);
    if (!c) c = check_precision(def, err);
    if (!c) c = check_table(def, err);
    if (!c) {
        sph_mem_limit limit;
        sph_memory_limit(&limit);
        c = sph_memory_check(def, &limit, err);
    }
    return c;
}
