/* Obstacles ([obstacle NAME], wall_model = particles): their validation, the
 * fluid lattice nodes they remove, and their wall particles.
 *
 * An obstacle is a solid filled, from its surface inwards, with layers of
 * fixed wall particles down to the kernel support, ceil(h / s) layers at the
 * finest block's spacing s, as the domain's walls are (Adami, Hu & Adams
 * 2012, section 2.3: the wall particles must fill the support of every fluid
 * particle near the wall). A box's particles sit on a lattice of spacing s
 * centred in the box, the outermost half a spacing inside each face; a
 * circle's (a sphere's) on rings (shells) of radius R - (l + 1/2) s, each with
 * about its circumference (area) over s (s^2) particles, so the surface is
 * round, not stair-stepped; each particle carries rho0 times its share of the
 * ring's (shell's) area (volume).
 *
 * Obstacles may overlap: they form one solid, and a particle of obstacle k
 * that falls inside an earlier obstacle is left out (the earlier one has its
 * own particles within the support's depth of its surface). The part of an
 * obstacle outside the domain box is cut off (the domain's own walls stand
 * there). */
#include "sph_obstacles.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sph_sim.h"
#include "sph_walls.h"

/* Origin slots of the obstacle keys (their order in sph_scene_keys). */
enum { SLOT_SHAPE, SLOT_MIN, SLOT_MAX, SLOT_CENTRE, SLOT_RADIUS, SLOT_SLIP };

#define PI 3.14159265358979323846

static double finest_spacing(const sph_scene_def *def)
{
    double s = INFINITY;
    for (int b = 0; b < def->n_blocks; b++) s = fmin(s, def->blocks[b].spacing);
    return s;
}

static int layer_count(const sph_scene_def *def, double s)
{
    return (int)ceil(def->h / s - 1e-6);
}

bool sph_obstacle_inside(const sph_obstacle_def *o, int dim, const double p[3])
{
    if (o->shape == SPH_SHAPE_BOX) {
        for (int a = 0; a < dim; a++)
            if (!(p[a] >= o->min[a] && p[a] <= o->max[a])) return false;
        return true;
    }
    double r2 = 0;
    for (int a = 0; a < dim; a++) r2 += (p[a] - o->centre[a]) * (p[a] - o->centre[a]);
    return r2 <= (double)o->radius * o->radius;
}

int sph_obstacles_holding(const sph_scene_def *def, int below, const double p[3])
{
    for (int k = 0; k < below && k < def->n_obstacles; k++)
        if (sph_obstacle_inside(&def->obstacles[k], def->dim, p)) return k;
    return -1;
}

/* The box around obstacle o [m]. */
static void bounds(const sph_obstacle_def *o, int dim, double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) {
        bool box = o->shape == SPH_SHAPE_BOX;
        lo[a] = a >= dim ? 0 : box ? o->min[a] : (double)o->centre[a] - o->radius;
        hi[a] = a >= dim ? 0 : box ? o->max[a] : (double)o->centre[a] + o->radius;
    }
}

double sph_obstacles_fluid_dropped(const sph_scene_def *def)
{
    double dropped = 0;
    for (int b = 0; b < def->n_blocks; b++) {
        const sph_block_def *blk = &def->blocks[b];
        const float s = blk->spacing;
        int64_t n[3];
        for (int a = 0; a < 3; a++) n[a] = sph_block_nodes(def, b, a);
        for (int k = 0; k < def->n_obstacles; k++) {
            double lo[3], hi[3];
            bounds(&def->obstacles[k], def->dim, lo, hi);
            int64_t from[3] = {0, 0, 0}, to[3] = {1, 1, 1}; /* node range that may fall inside */
            bool none = false;
            for (int a = 0; a < def->dim; a++) {
                from[a] = (int64_t)fmax(0.0, floor((lo[a] - blk->min[a]) / s - 0.5) - 1);
                to[a] = (int64_t)fmin((double)n[a], ceil((hi[a] - blk->min[a]) / s - 0.5) + 2);
                none |= !(from[a] < to[a]);
            }
            if (none) continue;
            for (int64_t z = from[2]; z < to[2]; z++)
                for (int64_t y = from[1]; y < to[1]; y++)
                    for (int64_t x = from[0]; x < to[0]; x++) {
                        int64_t node[3] = {x, y, z};
                        double p[3] = {0, 0, 0};
                        for (int a = 0; a < def->dim; a++) /* as place_particles computes it, in float */
                            p[a] = (float)(blk->min[a] + ((float)node[a] + 0.5f) * s);
                        if (sph_obstacles_holding(def, def->n_obstacles, p) == k) dropped += 1;
                    }
        }
    }
    return dropped;
}

/* ---- wall particles ------------------------------------------------------ */

/* Where walk() puts what it finds: P == NULL only counts. */
typedef struct sink {
    const sph_scene_def *def;
    int k;
    sph_particles *P;
    uint32_t next, cap;
    double count;
} sink;

static void emit(sink *o, const double p[3], double mass)
{
    const sph_scene_def *def = o->def;
    for (int a = 0; a < def->dim; a++) /* cut off outside the domain */
        if (!(p[a] >= def->domain_min[a] && p[a] <= def->domain_max[a])) return;
    if (sph_obstacles_holding(def, o->k, p) >= 0) return; /* inside an earlier obstacle */
    o->count += 1;
    if (!o->P || o->next >= o->cap) return;
    sph_particles *P = o->P;
    uint32_t i = o->next++;
    P->id[i] = i;
    P->mass[i] = (float)mass;
    P->fixed[i] = 1.0f;
    P->obstacle[i] = (float)(o->k + 1);
    P->slip[i] = def->obstacles[o->k].slip == SPH_SLIP_FREE ? 1.0f : 0.0f;
    for (int a = 0; a < def->dim; a++) {
        P->pos[a][i] = (float)p[a];
        P->vel[a][i] = 0.0f; /* obstacles stand still */
    }
}

static void walk_box(sink *o, const sph_obstacle_def *ob, double s, int layers, double rho0)
{
    const int dim = o->def->dim;
    int64_t n[3] = {1, 1, 1};
    double c[3] = {0, 0, 0};
    for (int a = 0; a < dim; a++) {
        n[a] = (int64_t)floor(((double)ob->max[a] - ob->min[a]) / s + 0.5);
        if (n[a] < 1) n[a] = 1;
        c[a] = 0.5 * ((double)ob->min[a] + ob->max[a]);
    }
    const double mass = rho0 * (dim == 3 ? s * s * s : s * s);
    for (int64_t z = 0; z < n[2]; z++)
        for (int64_t y = 0; y < n[1]; y++) {
            int64_t depth = INT64_MAX; /* layers between the row and the nearest y or z face */
            for (int a = 1; a < dim; a++) {
                int64_t k = a == 1 ? y : z, d = k < n[a] - 1 - k ? k : n[a] - 1 - k;
                if (d < depth) depth = d;
            }
            for (int64_t x = 0; x < n[0]; x++) {
                int64_t dx = x < n[0] - 1 - x ? x : n[0] - 1 - x;
                if (depth >= layers && dx >= layers) { /* deep inside: jump to the far x layers */
                    if (x < n[0] - layers) x = n[0] - layers - 1;
                    continue;
                }
                int64_t node[3] = {x, y, z};
                double p[3] = {0, 0, 0};
                for (int a = 0; a < dim; a++) p[a] = c[a] + ((double)node[a] - 0.5 * (double)(n[a] - 1)) * s;
                emit(o, p, mass);
            }
        }
}

static void walk_circle(sink *o, const sph_obstacle_def *ob, double s, int layers, double rho0)
{
    const int dim = o->def->dim;
    const double R = ob->radius, golden = PI * (3.0 - sqrt(5.0));
    for (int l = 0; l < layers; l++) {
        double r = R - (l + 0.5) * s, p[3] = {0, 0, 0};
        if (r < 0.5 * s) { /* what is left is one particle at the centre */
            double left = R - l * s;
            if (left <= 0) break;
            for (int a = 0; a < dim; a++) p[a] = ob->centre[a];
            emit(o, p, rho0 * (dim == 3 ? 4.0 / 3.0 * PI * left * left * left : PI * left * left));
            break;
        }
        /* particles on the ring (shell) of radius r, each standing for an
         * equal share of the layer between r - s/2 and r + s/2 */
        double area = dim == 3 ? 4.0 * PI * r * r : 2.0 * PI * r;
        int64_t m = (int64_t)floor(area / (dim == 3 ? s * s : s) + 0.5);
        if (m < 1) m = 1;
        const double mass = rho0 * area * s / (double)m;
        for (int64_t j = 0; j < m; j++) {
            double u[3];
            if (dim == 2) { /* alternate layers are turned by half a step */
                double th = 2.0 * PI * ((double)j + 0.5 * (l & 1)) / (double)m;
                u[0] = cos(th), u[1] = sin(th), u[2] = 0;
            } else { /* a Fibonacci lattice: nearly uniform points on the sphere */
                double zz = 1.0 - (2.0 * (double)j + 1.0) / (double)m, rr = sqrt(fmax(0.0, 1.0 - zz * zz));
                double ph = golden * (double)j + 0.5 * l;
                u[0] = rr * cos(ph), u[1] = rr * sin(ph), u[2] = zz;
            }
            for (int a = 0; a < dim; a++) p[a] = ob->centre[a] + r * u[a];
            emit(o, p, mass);
        }
    }
}

static double walk(const sph_scene_def *def, int k, sph_particles *P, uint32_t first, uint32_t cap)
{
    sink o = {def, k, P, first, cap, 0};
    const double s = finest_spacing(def);
    if (!sph_scene_wall_particles(def) || !(s > 0) || !isfinite(s) || k >= def->n_obstacles) return 0;
    const sph_obstacle_def *ob = &def->obstacles[k];
    if (ob->shape == SPH_SHAPE_BOX)
        walk_box(&o, ob, s, layer_count(def, s), def->rest_density);
    else
        walk_circle(&o, ob, s, layer_count(def, s), def->rest_density);
    return o.count;
}

double sph_obstacle_wall_count(const sph_scene_def *def, int k)
{
    return walk(def, k, NULL, 0, 0);
}

uint32_t sph_obstacle_place(sph_sim *sim, int k, uint32_t first)
{
    return (uint32_t)walk(&sim->def, k, &sim->P, first, sim->n);
}

/* ---- validation ----------------------------------------------------------- */

static sph_error_code fail_at(sph_error *err, const sph_scene_def *def, const sph_obstacle_def *o, int slot,
                              const char *what)
{
    int line = slot >= 0 && o->origin[slot].line ? o->origin[slot].line : o->line;
    if (line < 0) return sph_fail(err, SPH_ERR_SCENE, "--set: [obstacle %s] %s", o->name, what);
    /* another of its keys given by --set may be the cause (a radius set there, the centre blamed) */
    bool set = false;
    for (int k = 0; k < SPH_GROUP_KEYS_MAX; k++) set |= o->origin[k].line < 0;
    return sph_fail(err, SPH_ERR_SCENE, "%s:%d%s: [obstacle %s] %s", def->file, line, set ? " and --set" : "",
                    o->name, what);
}

/* Wall particles an obstacle could make at most, before cutting, and the rows
 * its walk visits: refuses an absurd size before any loop over its nodes. */
static double estimate(const sph_obstacle_def *o, int dim, double s, int layers)
{
    /* the nodes the walk visits: its layers under the surface, not the whole inside (a wide floor box reaching
     * far outside the domain, 150 wall particles once cut, was refused as 8e8) */
    if (o->shape == SPH_SHAPE_CIRCLE) {
        double R = o->radius;
        return (dim == 3 ? 4.0 * PI * R * R / (s * s) : 2.0 * PI * R / s) * 1.2 * layers + layers;
    }
    double all = 1, inside = 1, rows = 1;
    for (int a = 0; a < dim; a++) {
        double n = fmax(1.0, floor(((double)o->max[a] - o->min[a]) / s + 0.5));
        all *= n;
        inside *= fmax(0.0, n - 2.0 * layers);
        if (a > 0) rows *= n; /* the walk visits every row along y and z, if only to jump its inside */
    }
    return all - inside + rows;
}

sph_error_code sph_obstacles_validate(const sph_scene_def *def, sph_error *err)
{
    const char *axes = "xyz";
    const double s = finest_spacing(def);
    char what[400];
    for (int k = 0; k < def->n_obstacles; k++) {
        const sph_obstacle_def *o = &def->obstacles[k];
        const bool box = o->shape == SPH_SHAPE_BOX;
        if (def->wall_model != SPH_WALL_PARTICLES || !sph_scene_wall_particles(def)) {
            /* the condition that failed, and where its value came from (the file's line or --set) */
            char at[300];
            if (def->wall_model != SPH_WALL_PARTICLES)
                snprintf(what, sizeof what,
                         "needs wall particles (an obstacle is made of them): [domain] wall_model = %s (%s); accepted: "
                         "wall_model = particles",
                         sph_wall_model_names[def->wall_model],
                         sph_scene_key_where(def, "domain", "wall_model", at, sizeof at));
            else {
                const bool walls = def->effects & SPH_EFFECT(WALLS), pressure = def->effects & SPH_EFFECT(PRESSURE);
                snprintf(what, sizeof what,
                         "needs wall particles (an obstacle is made of them): [scene] effects (%s) do not list %s; "
                         "wall particles need walls and pressure among them",
                         sph_scene_key_where(def, "scene", "effects", at, sizeof at),
                         !walls && !pressure ? "walls or pressure" : !walls ? "walls" : "pressure");
            }
            return fail_at(err, def, o, -1, what);
        }
        int wrong = box ? (o->origin[SLOT_CENTRE].line ? SLOT_CENTRE : o->origin[SLOT_RADIUS].line ? SLOT_RADIUS : -1)
                        : (o->origin[SLOT_MIN].line ? SLOT_MIN : o->origin[SLOT_MAX].line ? SLOT_MAX : -1);
        if (wrong >= 0) {
            snprintf(what, sizeof what, "shape = %s takes %s, not %s (accepted: a box's min and max, a circle's "
                     "centre and radius)", sph_shape_names[o->shape], box ? "min and max" : "centre and radius",
                     wrong == SLOT_CENTRE ? "centre" : wrong == SLOT_RADIUS ? "radius" : wrong == SLOT_MIN ? "min" : "max");
            return fail_at(err, def, o, wrong, what);
        }
        if (box) {
            if (!o->origin[SLOT_MAX].line)
                return fail_at(err, def, o, -1, "shape = box needs max (and min, by default 0 0 0)");
            for (int a = 0; a < def->dim; a++)
                if (!((double)o->max[a] - o->min[a] >= s * (1 - 1e-3))) {
                    snprintf(what, sizeof what, "max.%c = %g: the box is %g m thick along %c, less than one spacing "
                             "(%g m) (accepted: max at least one spacing above min)", axes[a], o->max[a],
                             (double)o->max[a] - o->min[a], axes[a], s);
                    return fail_at(err, def, o, SLOT_MAX, what);
                }
        } else if (!(o->radius >= s * (1 - 1e-3))) {
            snprintf(what, sizeof what, "radius = %g: %s (accepted: at least one spacing, %g m)", o->radius,
                     o->origin[SLOT_RADIUS].line ? "smaller than one spacing" : "shape = circle needs a radius", s);
            return fail_at(err, def, o, SLOT_RADIUS, what);
        }
        double lo[3], hi[3];
        bounds(o, def->dim, lo, hi);
        for (int a = 0; a < def->dim; a++) {
            if ((def->periodic & (1u << a)) && (lo[a] < def->domain_min[a] || hi[a] > def->domain_max[a])) {
                snprintf(what, sizeof what, "%c from %g to %g leaves the domain (%g to %g) along a periodic axis "
                         "(accepted: within the domain there)", axes[a], lo[a], hi[a], def->domain_min[a],
                         def->domain_max[a]);
                return fail_at(err, def, o, box ? SLOT_MAX : SLOT_CENTRE, what);
            }
        }
        if (estimate(o, def->dim, s, layer_count(def, s)) > 2e8) {
            snprintf(what, sizeof what, "would make more than 2e8 wall particles at spacing %g m; make it smaller", s);
            return fail_at(err, def, o, -1, what);
        }
        if (sph_obstacle_wall_count(def, k) == 0) {
            /* two causes: name the earlier obstacle that holds it (the one the user may have grown), or say where
             * it lies against the domain */
            double mid[3] = {0, 0, 0};
            bool meets = true;
            for (int a = 0; a < def->dim; a++) {
                mid[a] = 0.5 * (lo[a] + hi[a]);
                meets &= hi[a] > def->domain_min[a] && lo[a] < def->domain_max[a];
            }
            const int holder = meets ? sph_obstacles_holding(def, k, mid) : -1;
            if (holder >= 0) {
                const sph_obstacle_def *e = &def->obstacles[holder];
                int last = e->line; /* its section: from the header to its last key in the file */
                bool set = false;
                for (int g = 0; g < SPH_GROUP_KEYS_MAX; g++) {
                    set |= e->origin[g].line < 0;
                    if (e->origin[g].line > last) last = e->origin[g].line;
                }
                char where[320] = "--set";
                if (e->line > 0 && last > e->line)
                    snprintf(where, sizeof where, "%s:%d to %d%s", def->file, e->line, last, set ? " and --set" : "");
                else if (e->line > 0)
                    snprintf(where, sizeof where, "%s:%d%s", def->file, e->line, set ? " and --set" : "");
                snprintf(what, sizeof what, "lies inside [obstacle %.47s] (%.200s): it makes no wall particle (accepted: an "
                         "obstacle with some of its surface outside every earlier one)", e->name, where);
            } else {
                int w = 0;
                for (int a = 0; a < def->dim && w < (int)sizeof what; a++)
                    w += snprintf(what + w, sizeof what - (size_t)w, "%s%c from %g to %g", a ? ", " : "", axes[a],
                                  lo[a], hi[a]);
                if (w < (int)sizeof what)
                    snprintf(what + w, sizeof what - (size_t)w, " lies outside the domain: it makes no wall particle "
                             "(accepted: some of it within [domain] min and max)");
            }
            return fail_at(err, def, o, box ? SLOT_MIN : SLOT_CENTRE, what);
        }
    }
    if (def->n_obstacles && sph_scene_particle_count(def) < 1)
        return sph_fail(err, SPH_ERR_SCENE, "%s: no particles: every fluid node lies inside an obstacle", def->file);
    return SPH_ERR_OK;
}
