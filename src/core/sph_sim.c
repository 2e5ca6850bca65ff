/* Simulation set-up and the time step as a list of passes; its timings and statistics are in sph_sim_measures.c. */
#include "sph_sim.h"
#include "sph_walls.h"
#include "sph_obstacles.h"
#include "sph_memory.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

const sph_pass *const sph_passes[SPH_PASS_COUNT] = {
#define SPH_PASS_PTR(id, name) &sph_pass_##name,
    SPH_PASSES(SPH_PASS_PTR)
#undef SPH_PASS_PTR
};

bool sph_scene_needs_density(const sph_scene_def *def)
{
    /* surface tension and XSPH weigh neighbours by m_j / rho_j */
    return (def->effects & SPH_EFFECTS_NEEDING_DENSITY) != 0 || def->surface_tension != SPH_STENSION_NONE ||
           def->xsph > 0;
}

bool sph_scene_pressure_solver(const sph_scene_def *def)
{
    return def->pressure_solver != SPH_PSOLVER_EOS && (def->effects & SPH_EFFECT(PRESSURE));
}

bool sph_scene_wall_volume(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(WALLS)) && def->wall_model == SPH_WALL_VOLUME;
}

bool sph_scene_needs_neighbours(const sph_scene_def *def)
{
    return sph_scene_needs_density(def);
}

double sph_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* ---- backends ----------------------------------------------------------- */

static sph_backend_factory backend_factories[SPH_BACKEND_COUNT];

void sph_backend_register(sph_backend_kind kind, sph_backend_factory make)
{
    if ((int)kind >= 0 && kind < SPH_BACKEND_COUNT) backend_factories[kind] = make;
}

void sph_sim_sync(const sph_sim *sim, sph_mask what)
{
    sph_backend *b = sim->backend;
    if (!b) return;
    /* the lists are built on the host from the index and predicted positions */
    if (what & SPH_SYNC_LISTS) what |= SPH_SYNC_INDEX | SPH_SYNC_FIELD(SPH_FIELD_PRED) | SPH_SYNC_ID;
    sph_mask need = what & b->stale;
    if (!need) return;
    /* The host arrays are a cache of the device's state: refreshing them
     * changes no state of the simulation, so a const sim may be refreshed
     * (sim points to an object allocated non-const by sph_sim_create). */
    b->download(b, (sph_sim *)sim, need);
    b->stale &= ~need;
}

void sph_sim_upload(sph_sim *sim)
{
    if (!sim->backend) return;
    sim->backend->upload(sim->backend, sim);
    /* the particles are current on both sides now; the index and lists are
     * still the device's to make */
    sim->backend->stale &= SPH_SYNC_INDEX | SPH_SYNC_LISTS;
}

/* What a backend's pass makes stale in the host copy: what it writes, and
 * the lists when the positions they were built from move. */
static sph_mask pass_stale_bits(int p)
{
    sph_mask w = sph_passes[p]->writes;
    if (w & (SPH_BIT(PRED) | SPH_RES_ENTRIES | SPH_RES_START)) w |= SPH_RES_LISTS;
    return w;
}

/* ---- creation ----------------------------------------------------------- */

static void *alloc_zero(size_t count, size_t size, bool *ok)
{
    if (count == 0) count = 1;
    void *p = calloc(count, size);
    if (!p) *ok = false;
    return p;
}

/* The registry's fields that the pipeline needs: those always there, and
 * those whose pass runs (sph_field_allocated). */
static void alloc_fields(sph_sim *sim, bool *ok)
{
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        const sph_field_info *info = &sph_field_infos[f];
        if (!sph_field_allocated(f, &sim->def, sim->in_pipeline)) continue;
        for (int d = 0; d < (info->vector ? sim->dim : 1); d++)
            sim->P.field[f][d] = alloc_zero(sim->n, sizeof(float), ok);
    }
}

/* splitmix64: a tiny, well-mixed generator, so a seed gives the same jitter everywhere. */
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static float rng_symmetric(uint64_t *s) /* uniform in [-1, 1) */
{
    return (float)((double)(rng_next(s) >> 11) * (2.0 / 9007199254740992.0) - 1.0);
}

/* The density the equation of state gives for pressure p [Pa]: its inverse,
 * so a block started with a pressure field has it from the first density sum.
 * rho0: the equation of state's reference, sim->eos_rho0 [kg/m^dim]. */
static double rest_density_at(const sph_scene_def *def, double rho0, double p)
{
    const double k = def->stiffness;
    if (!(def->effects & SPH_EFFECT(PRESSURE)) || k <= 0) return rho0;
    if (def->eos == SPH_EOS_TAIT) return rho0 * pow(1.0 + def->tait_gamma * p / (k * rho0), 1.0 / def->tait_gamma);
    return rho0 + p / k;
}

/* [1] rho / rho0 of a block with initial_pressure = hydrostatic at the
 * lattice node x [m]: the equation of state solved for the density at
 * p = rho0 |g| d, d the node's depth below the block's highest point along
 * g (its top face when g is along an axis). The particle's mass carries
 * that density (rho spacing^dim), so the summed density, and the carried
 * one that starts from it, start at the hydrostatic pressure, whichever
 * density_method; the lattice stays as it is. */
static double hydrostatic_share(const sph_scene_def *def, double eos_rho0, const sph_block_def *blk,
                                const double x[3])
{
    double g2 = 0, top = -INFINITY, height = 0;
    for (int d = 0; d < def->dim; d++) g2 += (double)def->gravity[d] * def->gravity[d];
    const double gn = sqrt(g2);
    if (!(gn > 0)) return 1.0;
    for (int c = 0; c < (1 << def->dim); c++) { /* the block's corners: the highest against g */
        double up = 0;
        for (int d = 0; d < def->dim; d++) up -= def->gravity[d] / gn * ((c >> d) & 1 ? blk->max[d] : blk->min[d]);
        top = fmax(top, up);
    }
    for (int d = 0; d < def->dim; d++) height -= def->gravity[d] / gn * x[d];
    const double p = def->rest_density * gn * fmax(top - height, 0.0); /* [Pa] */
    return rest_density_at(def, eos_rho0, p) / eos_rho0; /* of the lattice's own density, whichever eos_rest */
}

static void place_particles(sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    sph_particles *P = &sim->P;
    uint64_t rng = def->seed;
    uint32_t i = 0;
    for (int b = 0; b < def->n_blocks; b++) {
        const sph_block_def *blk = &def->blocks[b];
        int64_t nx = sph_block_nodes(def, b, 0), ny = sph_block_nodes(def, b, 1), nz = sph_block_nodes(def, b, 2);
        float s = blk->spacing;
        float mass = def->rest_density * (sim->dim == 3 ? s * s * s : s * s);
        for (int64_t z = 0; z < nz; z++)
            for (int64_t y = 0; y < ny; y++)
                for (int64_t x = 0; x < nx; x++, i++) {
                    int64_t node[3] = {x, y, z};
                    if (def->n_obstacles) { /* nodes inside an obstacle make no particle */
                        double p[3] = {0, 0, 0};
                        for (int d = 0; d < sim->dim; d++) p[d] = blk->min[d] + ((float)node[d] + 0.5f) * s;
                        if (sph_obstacles_holding(def, def->n_obstacles, p) >= 0) {
                            i--;
                            continue;
                        }
                    }
                    P->id[i] = i;
                    P->mass[i] = mass;
                    if (blk->initial_pressure == SPH_INITP_HYDROSTATIC) {
                        double at[3] = {0, 0, 0};
                        for (int d = 0; d < sim->dim; d++) at[d] = blk->min[d] + ((float)node[d] + 0.5f) * s;
                        P->mass[i] = (float)(mass * hydrostatic_share(def, sim->eos_rho0, blk, at));
                    }
                    for (int d = 0; d < sim->dim; d++) {
                        float jit = def->jitter > 0 ? def->jitter * s * rng_symmetric(&rng) : 0.0f;
                        float v = (float)blk->min[d] + ((float)node[d] + 0.5f) * s + jit;
                        /* jitter must not push a particle out of the domain */
                        if (v < def->domain_min[d]) v = def->domain_min[d];
                        if (v > def->domain_max[d]) v = def->domain_max[d];
                        P->pos[d][i] = v;
                        P->vel[d][i] = blk->velocity[d];
                    }
                    if (blk->field == SPH_VFIELD_TAYLOR_GREEN) {
                        const double two_pi = 6.283185307179586;
                        double k = two_pi / ((double)def->domain_max[0] - def->domain_min[0]), U = blk->velocity[0];
                        double px = (double)P->pos[0][i] - def->domain_min[0];
                        double py = (double)P->pos[1][i] - def->domain_min[1];
                        P->vel[0][i] = (float)(U * sin(k * px) * cos(k * py));
                        P->vel[1][i] = (float)(-U * cos(k * px) * sin(k * py));
                        if (sim->dim == 3) P->vel[2][i] = 0.0f;
                        if (blk->field_pressure == SPH_ON) {
                            double p = -0.25 * def->rest_density * U * U * (cos(2 * k * px) + cos(2 * k * py));
                            /* the lattice sums eos_rho0 / rest_density times mass / volume,
                             * so the particle sums to rest_density_at */
                            const double r0 = sim->eos_rho0, r = rest_density_at(def, r0, p) * (def->rest_density / r0);
                            P->mass[i] = (float)(r * (sim->dim == 3 ? s * s * s : s * s));
                        }
                    }
                    /* density_method = continuity starts from the lattice's density, m / s^dim, not
                     * from the summation, which misses a free surface's outside: the top row of a
                     * column read 16 % light (cubic, h = 2 s), a volume the column then lost
                     * (docs/accuracy.md, "hydrostatic") */
                    if (P->rho_c) P->rho_c[i] = P->mass[i] / (sim->dim == 3 ? s * s * s : s * s);
                }
    }
}

/* The state at t = 0 as the first time step must see it: the largest speed
 * and acceleration, and the total energy. Without this the first adaptive dt
 * (and the fixed-dt warning) was chosen with |v|max = |a|max = 0. The force
 * passes run once with dt = 0 (so pred = pos and nothing moves), on the host,
 * without reordering, before any backend takes the state. */
static void measure_start(sph_sim *sim)
{
    const sph_particles *P = &sim->P;
    const int dim = sim->dim;
    sim->dt = 0.0f;
    sim->fields_fresh = 0; /* the scene's state, then what these passes write */
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (sph_field_infos[f].kind == SPH_KIND_STATE) sim->fields_fresh |= SPH_FIELD_BIT(f);
    for (int p = 0; p < SPH_PASS_INTEGRATE; p++)
        if (sim->in_pipeline[p] && p != SPH_PASS_REORDER) {
            sph_passes[p]->run(sim);
            sim->fields_fresh |= sph_passes[p]->writes;
        }
    double v2max = 0, a2max = 0, g2 = 0;
    for (int d = 0; d < dim; d++)
        g2 += (sim->def.effects & SPH_EFFECT(GRAVITY)) ? (double)sim->def.gravity[d] * sim->def.gravity[d] : 0.0;
    for (uint32_t i = 0; i < sim->n; i++) {
        double v2 = 0, a2 = 0;
        for (int d = 0; d < dim; d++) {
            double a = 0;
            for (int f = 0; f < SPH_FIELD_COUNT; f++)
                if ((SPH_MASK_ACCELERATIONS & SPH_FIELD_BIT(f)) && P->field[f][0]) a += P->field[f][d][i];
            v2 += (double)P->vel[d][i] * P->vel[d][i];
            a2 += a * a;
        }
        v2max = fmax(v2max, v2);
        a2max = fmax(a2max, a2);
    }
    sim->max_speed = (float)sqrt(v2max);
    sim->max_acc = (float)(sqrt(a2max) + sqrt(g2)); /* as integration measures it */
    sph_stats s;
    sph_sim_stats(sim, &s);
    sim->energy_start = sph_stats_energy(&s);
    sim->energy_scale = fabs(s.ekin) + fabs(s.epot) + fabs(s.eint);
}

/* Bounds beyond which the watchdog calls the state a runaway, from the
 * scene's own speed scales, not from its stiffness: a weakly compressible
 * fluid flows at a small fraction of its sound speed, so a speed far above
 * what gravity (a fall along g across the domain), the blocks, the passes'
 * own forces (sph_pass.speed_scale: the mouse), cohesion and any compression the blocks start with can make is an artefact, however
 * stiff the fluid. The lattice's own summation error (up to 3% above rho0)
 * does not count as compression: at k = 1e6 it launched a column at rest at
 * 28 m/s. Also 100 rho0 for density, and, for total energy, its scale at
 * step 0 (sph_watchdog_energy). Called once the state at t = 0 is measured. */
#define SPH_SPEED_FACTOR 4.0   /* the bound, in units of the scene's speed scale */
#define SPH_LATTICE_EXCESS 1.1 /* rho / rho0 a lattice may read at rest (3%), with a margin */
static void set_bounds(sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    const bool pressure = def->effects & SPH_EFFECT(PRESSURE);
    double c = pressure ? sqrt(def->stiffness) : 0.0;
    double g2 = 0, v0 = 0, fall_height = 0;
    for (int d = 0; d < def->dim; d++) g2 += (def->effects & SPH_EFFECT(GRAVITY)) ? (double)def->gravity[d] * def->gravity[d] : 0.0;
    for (int d = 0; d < def->dim && g2 > 0; d++) /* the domain's extent along g */
        fall_height += fabs((double)def->gravity[d]) / sqrt(g2) * ((double)def->domain_max[d] - def->domain_min[d]);
    for (int b = 0; b < def->n_blocks; b++) {
        double s2 = 0;
        for (int d = 0; d < def->dim; d++) s2 += (double)def->blocks[b].velocity[d] * def->blocks[b].velocity[d];
        v0 = fmax(v0, sqrt(s2));
    }
    double fall = sqrt(2.0 * sqrt(g2) * fall_height);
    double forces = 0; /* the passes' own: the mouse's push (sph_pass.speed_scale) */
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p] && sph_passes[p]->speed_scale) forces += sph_passes[p]->speed_scale(def);
    /* compression the blocks start with (overlapping blocks): the speed its
     * internal energy, e = k (ln r + 1/r - 1) at r = rho / rho0, could give */
    double rho_max = 0;
    if (pressure && sim->P.rho)
        for (uint32_t i = 0; i < sim->n; i++) rho_max = fmax(rho_max, sim->P.rho[i]);
    double r = rho_max / (SPH_LATTICE_EXCESS * def->rest_density), squeeze = 0;
    if (r > 1) squeeze = c * sqrt(2.0 * (log(r) + 1.0 / r - 1.0));
    /* cohesion and surface tension pull a surface in: their initial acceleration acting over h (the surface
     * tension's were left out: a still cube under csf had a bound of 1 m/s, "4 times 0 m/s") */
    double pull = 0;
    float *const *surface[] = {sim->P.acc_c, sim->P.acc_k, sim->P.acc_s, sim->P.acc_t};
    for (size_t f = 0; f < sizeof surface / sizeof surface[0]; f++)
        if (surface[f][0])
            for (uint32_t i = 0; i < sim->n; i++) {
                double a2 = 0;
                for (int d = 0; d < sim->dim; d++) a2 += (double)surface[f][d][i] * surface[f][d][i];
                pull = fmax(pull, sqrt(2.0 * sqrt(a2) * def->h));
            }
    /* a moving top wall drags the fluid up to its own speed */
    double lid = 0;
    for (int d = 0; d < def->dim; d++) lid += (double)def->wall_velocity[d] * def->wall_velocity[d];
    sim->speed_scale = (float)(fall + v0 + forces + squeeze + pull + sqrt(lid));
    sim->speed_fall = (float)fall;
    sim->speed_bound = (float)(SPH_SPEED_FACTOR * sim->speed_scale + 1.0);
    sim->density_bound = 100.0f * def->rest_density;
}

/* Moves sim->def into the simulation's frame: coordinates relative to the
 * domain's point nearest 0 (sph_scene_origin), rounded to float as the
 * particles are, so the passes compare float with float as before. A domain
 * that contains 0 is unchanged; one far from 0 keeps the precision of its
 * size, not of its distance from 0 (validation checks the float precision
 * over that size). */
static void to_relative(sph_sim *sim)
{
    sph_scene_def *def = &sim->def;
    for (int d = 0; d < def->dim; d++) {
        double o = sph_scene_origin(def, d);
        sim->origin[d] = o;
        def->domain_min[d] = (float)(def->domain_min[d] - o);
        def->domain_max[d] = (float)(def->domain_max[d] - o);
        for (int b = 0; b < def->n_blocks; b++) {
            def->blocks[b].min[d] = (float)(def->blocks[b].min[d] - o);
            def->blocks[b].max[d] = (float)(def->blocks[b].max[d] - o);
        }
        for (int k = 0; k < def->n_obstacles; k++) {
            sph_obstacle_def *ob = &def->obstacles[k];
            ob->min[d] = (float)(ob->min[d] - o);
            ob->max[d] = (float)(ob->max[d] - o);
            ob->centre[d] = (float)(ob->centre[d] - o);
        }
    }
}

sph_error_code sph_sim_create(const sph_scene_def *def, int threads, sph_sim **out, sph_error *err)
{
    return sph_sim_create_shared(def, threads, NULL, out, err);
}

sph_error_code sph_sim_create_shared(const sph_scene_def *def, int threads, void *share, sph_sim **out,
                                     sph_error *err)
{
    *out = NULL;
    sph_error_code c = sph_scene_validate(def, err);
    if (c) return c;
    sph_sim *sim = calloc(1, sizeof *sim);
    if (!sim) return sph_fail(err, SPH_ERR_MEMORY, "out of memory");
    sim->def = *def;
    sim->backend_share = share;
    sim->dim = def->dim;
    if (def->dim == 2) { /* a 2D scene has no z: keep stray z values out of every formula */
        sim->def.gravity[2] = 0;
        sim->def.domain_min[2] = sim->def.domain_max[2] = 0;
    }
    to_relative(sim);
    /* the fluid's particles, then the walls' (wall_model = particles) */
    /* counted in the frame the particles are placed in */
    sim->n = (uint32_t)(sph_scene_particle_count(&sim->def) + sph_wall_particle_count(&sim->def));
#ifdef _OPENMP
    sim->threads = threads > 0 ? threads : omp_get_num_procs();
    if (sim->threads > SPH_MAX_THREADS) sim->threads = SPH_MAX_THREADS;
#else
    sim->threads = 1;
    (void)threads;
#endif
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        sim->in_pipeline[p] = sph_passes[p]->skip_reason(&sim->def) == NULL;
        sim->enabled[p] = true;
    }
    sim->interaction_sign = 1.0f;
    sim->watchdog = true;
    sim->k_density = sph_kernel_make(def->kernel_density, def->dim, def->h);
    sim->k_pressure = sph_kernel_make(def->kernel_pressure, def->dim, def->h);
    sim->k_viscosity = sph_kernel_make(def->kernel_viscosity, def->dim, def->h);
    /* the volume walls' hidden lattice: the finest block's, as the wall particles' */
    float wall_s = 0.0f;
    for (int b = 0; b < def->n_blocks; b++)
        if (wall_s == 0.0f || def->blocks[b].spacing < wall_s) wall_s = def->blocks[b].spacing;
    sph_kernel_wall_lattice(&sim->k_density, wall_s);
    sph_kernel_wall_lattice(&sim->k_pressure, wall_s); /* the walls' pressure force (sph_wall_ghost_accel) */
    sim->eos_rho0 = def->eos_rest == SPH_EOSREST_LATTICE ? sph_sim_lattice_rest_density(sim) : def->rest_density;

    /* Only the buffers of passes in the pipeline are allocated. */
    uint32_t n = sim->n;
    int dim = sim->dim;
    bool ok = true;
    sph_particles *P = &sim->P;
    P->n = n;
    P->id = alloc_zero(n, sizeof *P->id, &ok);
    alloc_fields(sim, &ok);

    sph_search_data *S = &sim->S;
    for (int d = 0; d < dim; d++)
        if (def->periodic & (1u << d)) {
            sim->period[d] = sim->def.domain_max[d] - sim->def.domain_min[d];
            sim->inv_period[d] = 1.0f / sim->period[d];
        }
    if (sim->in_pipeline[SPH_PASS_HASH]) {
        sph_cells *g = &S->cells;
        /* cells a hair above the lists' reach: h, or h (1 + skin) for Verlet lists */
        const double size = (double)def->h * (1.0 + (def->skin > 0 ? (double)def->skin : 0.0)) * (1.0 + 1.0 / 1024);
        uint64_t cells = 1;
        g->dim = dim;
        g->dense = def->search == SPH_SEARCH_GRID;
        for (int d = 0; d < 3; d++) {
            double len = (double)sim->def.domain_max[d] - sim->def.domain_min[d];
            g->size[d] = (float)size;
            if (d >= dim) {
                g->count[d] = g->dense ? 1 : 0;
            } else if (sim->period[d] > 0) {
                g->wrap[d] = true;
                g->count[d] = (int32_t)floor(len / size);
                g->size[d] = (float)(len / g->count[d]);
                g->origin[d] = sim->def.domain_min[d];
            } else if (g->dense) {
                g->count[d] = (int32_t)ceil(len / size) + 1;
                g->origin[d] = sim->def.domain_min[d];
            }
            g->inv_size[d] = 1.0f / g->size[d];
            if (g->dense) cells *= (uint64_t)g->count[d];
            S->grid_dims[d] = g->dense ? g->count[d] : 0;
        }
        S->table_size = g->dense ? (uint32_t)cells : def->table_size ? def->table_size : (n ? n : 1);
        S->entries = alloc_zero(n, sizeof *S->entries, &ok);
        S->start = alloc_zero(S->table_size, sizeof *S->start, &ok);
        /* a level that reorders reads positions in place (16 bytes a particle less; the one search
         * before the first reorder, at creation, reads them by index) */
        if (!sim->in_pipeline[SPH_PASS_REORDER]) S->spos = alloc_zero(4 * (size_t)n, sizeof *S->spos, &ok);
        if (def->sort == SPH_SORT_NONE) S->next = alloc_zero(n, sizeof *S->next, &ok);
        if (sim->in_pipeline[SPH_PASS_REORDER]) {
            S->cell_hash = alloc_zero(n, sizeof *S->cell_hash, &ok);
            S->spare_f = alloc_zero(n, sizeof *S->spare_f, &ok);
            S->spare_u = alloc_zero(n, sizeof *S->spare_u, &ok);
        }
        /* the counting sort's scratch: borrowed from the neighbour lists, else made at its first use (sort.c) */
    }
    if (sim->in_pipeline[SPH_PASS_NEIGHBOURS]) {
        S->nbr_start = alloc_zero((size_t)n + 1, sizeof *S->nbr_start, &ok);
        S->compact = def->compact_lists == SPH_ON;
        S->n_threads = sim->threads;
        S->tbuf = alloc_zero((size_t)S->n_threads, sizeof *S->tbuf, &ok);
        S->tcap = alloc_zero((size_t)S->n_threads, sizeof *S->tcap, &ok);
        if (def->skin > 0) /* Verlet lists: where each particle was at their build */
            for (int d = 0; d < dim; d++) S->skin_ref[d] = alloc_zero(n, sizeof *S->skin_ref[d], &ok);
    }
    if (!ok) {
        sph_sim_destroy(sim);
        sph_mem_estimate e;
        sph_mem_limit lim;
        sph_memory_estimate(def, &e);
        sph_memory_limit(&lim);
        char need[32], have[32];
        return sph_fail(err, SPH_ERR_MEMORY,
                        "%s: out of memory making the simulation of %u particles (estimated %s in all, the largest "
                        "item %s; limit %s, %s)",
                        def->file, n, sph_memory_text(e.total, need, sizeof need), e.n ? e.item[e.largest].name : "-",
                        sph_memory_text(lim.bytes, have, sizeof have), lim.source);
    }
    place_particles(sim);
    if (P->fixed) sph_wall_particles_place(sim, (uint32_t)sph_scene_particle_count(&sim->def));
    if (P->rho_c) { /* the carried density exists from the start (place_particles); walls: wall_state's */
        for (uint32_t i = (uint32_t)sph_scene_particle_count(&sim->def); i < sim->n; i++)
            P->rho_c[i] = def->rest_density;
        sim->rho_carried = true;
    }
    measure_start(sim);
    set_bounds(sim);
    sim->dt = sph_time_step_choose(sim);
    if (def->backend != SPH_BACKEND_CPU) {
        sph_backend_factory make = backend_factories[def->backend];
        if (!make) {
            sph_sim_destroy(sim);
            return sph_fail(err, SPH_ERR_SCENE, "%s: [compute] backend = %s: this program was built without it",
                            def->file, sph_backend_names[def->backend]);
        }
        c = make(sim, share, &sim->backend, err);
        if (c) {
            sph_sim_destroy(sim);
            return c;
        }
        sph_sim_upload(sim);
    }
    *out = sim;
    return SPH_ERR_OK;
}

void sph_sim_destroy(sph_sim *sim)
{
    if (!sim) return;
    if (sim->backend) sim->backend->destroy(sim->backend);
    sph_particles *P = &sim->P;
    free(P->id);
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        for (int d = 0; d < 3; d++) free(P->field[f][d]);
    sph_search_data *S = &sim->S;
    free(S->entries);
    free(S->scratch);
    free(S->start);
    free(S->spos);
    free(S->cell_hash);
    free(S->next);
    free(S->spare_f);
    free(S->spare_u);
    free(S->count);
    free(S->nbr_start);
    free(S->nbr);
    for (int t = 0; S->tbuf && t < S->n_threads; t++) free(S->tbuf[t]);
    free(S->tbuf);
    free(S->tcap);
    for (int d = 0; d < 3; d++) free(S->skin_ref[d]);
    free(sim->solver.x_df);
    free(S->rec);
    free(sim);
}


/* Do two scenes place the same obstacles (their slip aside)? */
static bool same_obstacles(const sph_scene_def *a, const sph_scene_def *b)
{
    if (a->n_obstacles != b->n_obstacles) return false;
    for (int k = 0; k < a->n_obstacles; k++) {
        const sph_obstacle_def *x = &a->obstacles[k], *y = &b->obstacles[k];
        if (x->shape != y->shape || x->radius != y->radius || memcmp(x->min, y->min, sizeof x->min) ||
            memcmp(x->max, y->max, sizeof x->max) || memcmp(x->centre, y->centre, sizeof x->centre))
            return false;
    }
    return true;
}

sph_error_code sph_sim_clone(const sph_sim *sim, const sph_scene_def *def, int threads, sph_sim **out,
                             sph_error *err)
{
    static const char *const other = "this change makes other particles: reset the scene instead";
    if (def->dim != sim->def.dim || def->n_blocks != sim->def.n_blocks || !same_obstacles(def, &sim->def))
        return sph_fail(err, SPH_ERR_SCENE, "%s", other);
    sph_sim *next;
    sph_error_code c = sph_sim_create_shared(def, threads, sim->backend_share, &next, err);
    if (c) return c;
    if (next->n != sim->n) { /* counted in the simulation's frame, as the particles were placed */
        sph_sim_destroy(next);
        return sph_fail(err, SPH_ERR_SCENE, "%s", other);
    }
    sph_sim_sync(sim, SPH_SYNC_ALL); /* the particles below are read from the host copy */
    uint32_t n = sim->n;
    memcpy(next->P.id, sim->P.id, (size_t)n * sizeof *next->P.id);
    for (int f = 0; f < SPH_FIELD_COUNT; f++) /* the state; derived fields are made again */
        /* fixed: only with wall particles; rho_c: only with density_method = continuity */
        if (sph_field_infos[f].kind == SPH_KIND_STATE && sim->P.field[f][0] && next->P.field[f][0] &&
            f != SPH_FIELD_SLIP && f != SPH_FIELD_OBSTACLE)
            for (int d = 0; d < (sph_field_infos[f].vector ? sim->dim : 1); d++)
                memcpy(next->P.field[f][d], sim->P.field[f][d], (size_t)n * sizeof(float));
    /* a wall particle's slip and obstacle come from the new scene (a slip may
     * have changed), placed in creation order: put them where its id is now */
    const int wall_fields[2] = {SPH_FIELD_OBSTACLE, SPH_FIELD_SLIP};
    for (int w = 0; w < 2; w++) {
        const int f = wall_fields[w];
        if (next->P.field[f][0] && sim->S.spare_f) {
            float *fresh = next->P.field[f][0], *moved = sim->S.spare_f; /* [n] scratch of the old sim */
            for (uint32_t i = 0; i < n; i++) moved[i] = fresh[next->P.id[i]];
            memcpy(fresh, moved, (size_t)n * sizeof(float));
        }
    }
    /* pred: where the carried particles are (the new one's start-up wrote the
     * placement's), until its first step predicts them; the overlays read it */
    if (next->P.pred[0])
        for (int d = 0; d < sim->dim; d++) memcpy(next->P.pred[d], next->P.pos[d], (size_t)n * sizeof(float));
    next->t = sim->t;
    next->t_end = sim->t_end;
    next->step = sim->step;
    next->rho_carried = sim->rho_carried && sim->P.rho_c && next->P.rho_c; /* else summed again */
    next->max_speed = sim->max_speed;
    next->max_acc = sim->max_acc;
    next->energy_ref = sim->energy_ref;
    next->energy_start = NAN; /* the internal energy may have another law now: taken again after a step */
    next->energy_scale = sim->energy_scale;
    next->interaction_active = sim->interaction_active;
    memcpy(next->interaction_point, sim->interaction_point, sizeof next->interaction_point);
    next->interaction_sign = sim->interaction_sign;
    memcpy(next->enabled, sim->enabled, sizeof next->enabled);
    next->dt = sph_time_step_choose(next);
    sph_sim_upload(next);
    *out = next;
    return SPH_ERR_OK;
}

sph_error_code sph_sim_reconfigure(sph_sim *sim, const sph_scene_def *def, sph_error *err)
{
    sph_sim *next;
    sph_error_code c = sph_sim_clone(sim, def, sim->threads, &next, err);
    if (c) return c;
    /* swap contents so the caller's pointer stays valid */
    sph_sim tmp = *sim;
    *sim = *next;
    *next = tmp;
    sph_sim_destroy(next);
    return SPH_ERR_OK;
}

/* ---- the time step ------------------------------------------------------ */

/* The watchdog on a backend: scanning every field after every pass would
 * download them all each pass. The integrate pass's reduction already reads
 * back the largest speed and acceleration; a non-finite or runaway value
 * there triggers the download and the full scan, which names the field and
 * particle; the report names integrate, where it was found (the scan's pass,
 * the first of the step that writes the field, is no more than that: on an
 * H200 it named 'external' for a particle that integrate had sent out of the
 * box). A density runaway that leaves speeds finite and bounded is caught
 * only on the CPU backend. */
static void watchdog_backend(sph_sim *sim, int p)
{
    if (p != SPH_PASS_INTEGRATE) return;
    if (isfinite(sim->max_speed) && isfinite(sim->max_acc) && sim->max_speed <= sim->speed_bound) return;
    sph_sim_sync(sim, SPH_SYNC_ALL);
    for (int q = 0; q < SPH_PASS_COUNT && !sim->alarm.raised; q++)
        if (sim->in_pipeline[q] && sim->enabled[q]) sph_watchdog_check(sim, q);
    if (sim->alarm.raised) sim->alarm.checked_after = p; /* found here, whichever pass wrote the field */
}

static void run_timed(sph_sim *sim, int p)
{
    if (sim->backend && sim->backend->device_times) { /* its times come later (sph_sim_record_step_times) */
        sim->backend->run(sim->backend, sim, (sph_pass_id)p);
        sim->backend->stale |= pass_stale_bits(p);
        sim->timing[p].calls++;
        if (sim->watchdog) watchdog_backend(sim, p);
        return;
    }
    double t0 = sph_now_ms();
    if (sim->backend) {
        sim->backend->run(sim->backend, sim, (sph_pass_id)p);
        sim->backend->stale |= pass_stale_bits(p);
    } else {
        sph_passes[p]->run(sim);
    }
    double ms = sph_now_ms() - t0;
    sim->timing[p].calls++;
    sim->timing[p].total_ms += ms;
    sim->timing[p].last_ms = ms;
    sim->step_ms_acc += ms;
    if (!sim->watchdog) return; /* its cost is not counted as the pass's */
    if (sim->backend)
        watchdog_backend(sim, p);
    else
        sph_watchdog_check(sim, p);
}

const char *sph_sim_work_done_by(const sph_sim *sim)
{
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p] && sim->enabled[p] && sph_passes[p]->does_work && sph_passes[p]->does_work(sim))
            return sph_passes[p]->name;
    return NULL;
}

/* t after a step; a step shortened to a run's end lands on it, not a float
 * rounding of dt away from it */
static void advance_time(sph_sim *sim)
{
    sim->t += sim->dt;
    if (sim->t_end > 0 && fabs(sim->t - sim->t_end) <= 1e-6 * sim->dt) sim->t = sim->t_end;
}

sph_pass_id sph_sim_step_pass(sph_sim *sim)
{
#ifdef _OPENMP
    omp_set_num_threads(sim->threads);
#endif
    if (sim->alarm.raised) return SPH_PASS_COUNT; /* stopped: the state stays as the watchdog found it */
    if (sim->next_pass == 0) sim->dt = sph_time_step_choose(sim);
    int p = sim->next_pass;
    while (p < SPH_PASS_COUNT && !(sim->in_pipeline[p] && sim->enabled[p])) p++;
    const bool again = sim->pass_again; /* an iteration of the pass before: its time adds up */
    double before = p < SPH_PASS_COUNT ? sim->timing[p].last_ms : 0.0;
    sim->pass_again = false;
    if (p < SPH_PASS_COUNT) {
        run_timed(sim, p);
        if (p != SPH_PASS_REORDER)
            sim->fields_fresh |= sph_passes[p]->writes;
        else if (!sim->S.lists_kept) /* it moved the particles: the fields it did not move are in the old order */
            sim->fields_fresh &= sph_passes[p]->writes;
    }
    const bool device_times = sim->backend && sim->backend->device_times;
    if (again && p < SPH_PASS_COUNT && !device_times) sim->timing[p].last_ms += before;
    int next = sim->pass_again && p < SPH_PASS_COUNT ? p : p + 1; /* an iterative pass asks for another call */
    while (next < SPH_PASS_COUNT && !(sim->in_pipeline[next] && sim->enabled[next])) next++;
    if (next >= SPH_PASS_COUNT) { /* that was the step's last pass */
        advance_time(sim);
        sim->step++;
        if (sph_scene_pressure_solver(&sim->def)) sim->solver.iterations_run += (uint64_t)sim->solver.iterations;
        next = 0;
        if (!device_times) sim->step_ms[sim->step_ms_count++ % SPH_STEP_WINDOW] = sim->step_ms_acc;
        sim->step_ms_acc = 0;
        if (sim->step == 1) {
            sph_stats s;
            sph_sim_stats(sim, &s);
            sim->energy_ref = sph_stats_energy(&s);
        }
        if (sim->watchdog && p < SPH_PASS_COUNT) sph_watchdog_energy(sim, p);
    }
    sim->next_pass = next;
    return (sph_pass_id)(p < SPH_PASS_COUNT ? p : SPH_PASS_COUNT);
}

/* The step reads as its passes: external forces, hash, sort, offsets,
 * neighbours, density, pressure, pressure force, viscosity, integrate, walls
 * (the order of SPH_PASSES); each runs if the scene needs it and it is on. */
void sph_sim_step(sph_sim *sim)
{
    uint64_t step = sim->step;
    while (sim->step == step && !sim->alarm.raised) {
        if (sph_sim_step_pass(sim) == SPH_PASS_COUNT) { /* no pass at all: still advance time */
            if (sim->step == step) {
                advance_time(sim);
                sim->step++;
                sim->next_pass = 0;
            }
        }
    }
}
