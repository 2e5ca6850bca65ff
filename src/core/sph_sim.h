/* The simulation: particle data (one array per field), the spatial index,
 * the pipeline of passes and its timings. No GL header below this line. */
#ifndef SPH_SIM_H
#define SPH_SIM_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "sph_fields.h"
#include "sph_kernel.h"
#include "sph_pass.h"
#include "sph_scene.h"

/* Particle data, one array per field ("structure of arrays") so a pass reads
 * only the fields it uses and its loops vectorise. The members are made from
 * the registry (sph_fields.h): a vector field is one array per axis (the z
 * array is NULL in 2D), a scalar field one array. Fields whose pass is not
 * in the pipeline are not allocated (NULL). `field[f][d]` is the same
 * storage by number, for the loops over the registry. */
#define SPH_MEMBER_1(name) float *name; float *name##_unused_[2];
#define SPH_MEMBER_V(name) float *name[3];
typedef struct sph_particles {
    uint32_t n;
    uint32_t *id; /* [1] index at creation; stays with the particle if data are reordered */
    union {
        float *field[SPH_FIELD_COUNT][3]; /* [field][axis]; a scalar uses [f][0] */
        struct {
#define SPH_FIELD_MEMBER(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about) SPH_MEMBER_##comps(name)
            SPH_FIELDS(SPH_FIELD_MEMBER)
#undef SPH_FIELD_MEMBER
        };
    };
} sph_particles;
#undef SPH_MEMBER_1
#undef SPH_MEMBER_V

/* One entry of the spatial index: the seed's (index, hash, key) triple. */
typedef struct sph_entry {
    uint32_t key;   /* hash % table_size: the slot in the start table */
    uint32_t hash;  /* hash of the cell; tells apart cells that share a key */
    uint32_t index; /* particle */
} sph_entry;

#define SPH_MAX_THREADS 256
/* Below this many items a parallel region costs more than it saves (thread
 * wake-up is microseconds, more on a loaded machine). */
#define SPH_PARALLEL_MIN 4096
#define SPH_EMPTY UINT32_MAX /* start-table value of a key no particle has */

/* The seed's primes; the hash is computed in unsigned 32-bit arithmetic,
 * where overflow wraps (signed overflow, as in the seed's shader, is
 * undefined behaviour in C). */
#define SPH_HASH_P1 15823u
#define SPH_HASH_P2 9737333u
#define SPH_HASH_P3 440817757u

/* How positions map to search cells, per axis (set up by sph_sim_create).
 * Cells are a hair larger than the support, h (1 + 2^-10): then two particles
 * closer than h, as float arithmetic measures it, always fall in the same or
 * adjacent cells, however the products x / size round (with cells of exactly
 * h, x = 0.0599999949 and x = -1e-9 at h = 0.06 land two cells apart). */
typedef struct sph_cells {
    int dim;
    bool dense;        /* grid variant: a cell's key is its number in the grid */
    float origin[3];   /* [m] where cell 0 starts: 0 for the hash (as the seed), the domain's min otherwise */
    float size[3];     /* [m] cell size: h (1 + 2^-10), or L / floor(L / that) on a periodic axis */
    float inv_size[3]; /* [1/m] */
    int32_t count[3];  /* cells over the domain; 0: unbounded (the hash along a non-periodic axis) */
    bool wrap[3];      /* periodic axis: cell count wraps to 0 */
} sph_cells;

typedef struct sph_search_data {
    sph_cells cells;
    uint32_t table_size;  /* number of keys */
    sph_entry *entries;   /* [n] written by hash, sorted in place by sort */
    sph_entry *scratch;   /* [n] counting sort's output buffer */
    uint32_t *start;      /* [table_size] offsets: first sorted entry of each key, or SPH_EMPTY */
    uint32_t *count;      /* [table_size + 1] counting sort's histogram */
    float *spos;          /* [4 n] [m] predicted positions in sorted order (x, y, z, 0), for the scan */
    bool reordered;       /* this step's reorder pass ran: particle e is sorted entry e */
    uint32_t *next;       /* [n] sort = none: next particle of the same key, or SPH_EMPTY */
    uint32_t *cell_hash;  /* [n] hash of each particle's cell, in particle order, after a reorder */
    float *spare_f;       /* [n] the reorder pass gathers into these and swaps */
    uint32_t *spare_u;    /* [n] */
    int32_t grid_dims[3]; /* grid variant: cells per axis over the domain */
    /* Neighbour lists (compressed rows): neighbours of i, itself excluded,
     * are nbr[nbr_start[i] .. nbr_start[i+1]). */
    uint32_t *nbr_start;  /* [n + 1] */
    uint32_t *nbr;        /* [nbr_cap] */
    size_t nbr_cap;
    /* [search] compact_lists: nbr holds 16-bit words (nbr_start counts words):
     * row i is the offsets j - i as int16, or, behind the marker
     * SPH_NBR_WIDE, its indices as 32-bit values (two words each, unaligned).
     * Read rows through sph_nbr_row_of / sph_nbr_at. nbr_cap stays in 32-bit words. */
    bool compact;
    /* One growable buffer per thread while the lists are built (compact: 16-bit words, tcap in words). */
    size_t nbr_first;     /* [B] thread 0's rows at the last build, built in place (lists_in_place) */
    int n_threads;
    uint32_t **tbuf;
    size_t *tcap;
    /* Verlet lists ([search] skin > 0, src/core/sph_skin.c): the predicted
     * positions at the lists' build, and whether this step keeps them. */
    float *skin_ref[3];   /* [n] [m] pred at the last build */
    bool lists_built;     /* lists exist for the particles as they are stored now */
    bool lists_kept;      /* this step keeps them: no hash, sort, reorder, offsets, search */
    uint64_t kept_decided; /* sim->step + 1 of the step that decided lists_kept; 0: none yet */
    uint64_t builds;      /* [1] lists built so far (every step without a skin) */
    float skin_moved;     /* [m] the largest move since the build, as this step's decision saw it; 0 after a
                           * step that rebuilt them */
    /* [compute] packed_records: one record per particle (4 or 8 floats: positions [m], mass [kg] or volume
     * [m^3], velocity [m/s], p/rho^2 [m^5/(kg s^2)] or p [Pa]), rewritten by each pass that reads it. */
    float *rec;           /* [rec_cap], 32-byte aligned */
    size_t rec_cap;       /* [1] floats */
} sph_search_data;

/* The first word of a compact row stored wide: no offset j - i is -32768. */
#define SPH_NBR_WIDE 0x8000u
#define SPH_NBR_NEAR 32767 /* the largest |j - i| a compact row stores as an offset */

/* One row of the neighbour lists, whatever their storage. */
typedef struct sph_nbr_row {
    const uint32_t *w; /* plain lists: the indices */
    const int16_t *o;  /* compact row: the offsets j - i */
    const uint16_t *x; /* compact row stored wide: each index as two words (memcpy) */
    uint32_t n;        /* neighbours */
    uint32_t i;        /* the row's particle */
} sph_nbr_row;

static inline sph_nbr_row sph_nbr_row_of(const sph_search_data *S, uint32_t i)
{
    const uint32_t b = S->nbr_start[i], e = S->nbr_start[i + 1];
    sph_nbr_row r = {NULL, NULL, NULL, e - b, i};
    if (!S->compact) {
        r.w = S->nbr + b;
        return r;
    }
    const uint16_t *h = (const uint16_t *)(const void *)S->nbr + b;
    if (e > b && h[0] == SPH_NBR_WIDE) {
        r.x = h + 1;
        r.n = (e - b - 1) / 2;
    } else {
        r.o = (const int16_t *)(const void *)h;
    }
    return r;
}

/* The k-th neighbour of the row. */
static inline uint32_t sph_nbr_at(const sph_nbr_row *r, uint32_t k)
{
    if (r->w) return r->w[k];
    if (r->o) return r->i + (uint32_t)(int32_t)r->o[k];
    uint32_t j;
    memcpy(&j, r->x + 2 * (size_t)k, sizeof j);
    return j;
}

/* A field of one simulation: its registry row's text and its arrays. */
typedef struct sph_field {
    const char *name, *unit, *about;
    int ncomp;   /* components stored (vectors: the scene's dimension) */
    float *c[3]; /* component arrays */
} sph_field;

/* What the watchdog found: a non-finite value, else the worst runaway one (the fastest particle). */
typedef struct sph_alarm {
    bool raised;
    uint64_t step;     /* the step being computed (steps completed before it) */
    int pass;          /* the pass that wrote the value */
    int checked_after; /* the pass after which it was found: pass on the CPU; on a backend, integrate (one scan a
                        * step, sph_sim.c), where pass is only the step's first to write the field */
    uint32_t particle; /* index in the arrays (id: P.id[particle]) */
    int field, comp;
    float value;
    char what[256];    /* e.g. "not finite", "speed 812 m/s above the bound 300 m/s" */
} sph_alarm;

#define SPH_STEP_WINDOW 60 /* steps in the ms-per-step window */

typedef struct sph_pass_timing {
    uint64_t calls;
    double total_ms; /* [ms] monotonic clock, summed over calls */
    double last_ms;  /* [ms] latest call */
} sph_pass_timing;

typedef struct sph_stats {
    uint32_t n;
    double ekin;      /* [J] (3D) or [J/m] (2D) kinetic energy */
    double epot;      /* [J] or [J/m] gravitational energy, from the domain's lower corner */
    double eint;      /* [J] or [J/m] energy stored in compression by the equation of state */
    double momentum[3]; /* [kg m/s] total momentum */
    double rho_min, rho_mean, rho_max; /* [kg/m^dim] 0 if density is not computed */
    double max_speed; /* [m/s] */
    double rho_max_all; /* [kg/m^dim] the largest density of any particle, walls' included (the HUD's
                           density error is the fluid's, rho_max); 0 if density is not computed */
} sph_stats;

/* A compute backend: runs the passes on data kept elsewhere (the GL backend,
 * src/gpu/: compute shaders on one buffer per field). Then sim->P and sim->S
 * are host copies of the device's data, refreshed on demand: sph_sim_sync()
 * downloads what a reader needs (stats, fields, dumps, the window), and
 * sph_sim_upload() sends particles the CPU changed. The core knows only this
 * table; the module that implements it registers a factory, so no GL header
 * reaches the core. */
typedef struct sph_backend sph_backend;
struct sph_hash_health; /* sph_hash_health.h */
struct sph_backend {
    const char *name;    /* "gl" */
    char device[200];    /* what it measures on, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5" */
    sph_mask stale;      /* SPH_SYNC_* bits whose host copy is older than the device's */
    /* Runs one pass on the device; sets sim->max_speed and max_acc after integrate. */
    void (*run)(sph_backend *b, sph_sim *sim, sph_pass_id pass);
    /* Copies the parts named by `what` (SPH_SYNC_* bits) into sim->P and sim->S. */
    void (*download)(sph_backend *b, sph_sim *sim, sph_mask what);
    /* Sends every particle field of sim->P to the device. */
    void (*upload)(sph_backend *b, sph_sim *sim);
    void (*destroy)(sph_backend *b);
    /* How the passes' times are measured, for the timing table, e.g. "timer
     * queries on the device"; NULL: the host clock around run(). */
    const char *timing;
    /* Set by a backend that times the passes on the device (timer queries,
     * read back a step or so later so that nothing waits): run() then only
     * counts calls, and the backend reports each complete step's times
     * through sph_sim_record_step_times. collect_times (NULL: none pending)
     * reports what the device has measured so far; wait: all of it. */
    bool device_times;
    void (*collect_times)(sph_backend *b, sph_sim *sim, bool wait);
    /* Optional: sph_sim_stats reduced on the device, so that only a few
     * numbers are read back; called when the host copy of the fields it
     * reads is stale. false: not done (the fields are downloaded). */
    bool (*stats)(sph_backend *b, const sph_sim *sim, sph_stats *out);
    /* Optional: sph_sim_hash_health's figures without the neighbour count
     * (sph_hash_health.h), computed on the device; called when the host copy
     * of the positions is stale. false: not done (the positions are downloaded). */
    bool (*hash_health)(sph_backend *b, const sph_sim *sim, struct sph_hash_health *out);
};

/* What sph_sim_sync can refresh: the bits of sph_fields.h, one per particle
 * field, then the ids, the index (entries and start table) and the lists. */
#define SPH_SYNC_FIELD(f) SPH_FIELD_BIT(f)
#define SPH_SYNC_ID SPH_RES_ID
#define SPH_SYNC_INDEX (SPH_RES_ENTRIES | SPH_RES_START)
#define SPH_SYNC_LISTS SPH_RES_LISTS
#define SPH_SYNC_ALL (~(sph_mask)0)

/* Makes a backend for sim (its particles are placed); on failure fills err
 * with a message naming the key, value and reason. share is what the caller
 * of sph_sim_create_shared handed over (the GL backend: an OpenGL context to
 * run in, src/gl/gl_context.h), NULL for a backend on its own. */
typedef sph_error_code (*sph_backend_factory)(sph_sim *sim, void *share, sph_backend **out, sph_error *err);
/* Registers the factory of a backend kind (the app does this at start-up). */
void sph_backend_register(sph_backend_kind kind, sph_backend_factory make);

#define SPH_SOLVER_WALL_SAMPLES 256
/* The pressure solvers' progress in the current step and what the last
 * complete step reached (pressure_solver = pcisph or dfsph). */
typedef struct sph_solver_state {
    int phase;               /* dfsph: 0 divergence-free solve, 1 constant-density solve; pcisph: 0 */
    int iteration;           /* iterations of the current solve so far */
    double error;            /* [1] the current solve's error after its latest iteration (density: max
                                (rho* - rho_rest) / rho_rest over the fluid; divergence: max dt |D rho/Dt| / rho_rest) */
    int iterations;          /* [1] the last complete step: iterations of the constant-density solve */
    int div_iterations;      /* [1] the last complete step: iterations of the divergence-free solve (dfsph) */
    double density_error;    /* [1] the last complete step: the density error reached */
    double divergence_error; /* [1] the last complete step: mean of max(dt D rho/Dt, 0) / rho_rest (dfsph) */
    uint64_t capped;         /* [1] solves that stopped at solver_max_iterations, since the start */
    uint64_t stopped;        /* [1] density solves that stopped because their error rose (see least), since the start */
    double least;            /* [1] the current density solve's least error so far, whose pressure p_pci_best (pcisph)
                                or kappa_best (dfsph) keeps */
    bool held;               /* dfsph: an iterate of the current density solve held the compression within the
                                tolerance; kappa_best then keeps the one of those with the least shortfall */
    double least_over;       /* [1] dfsph: that iterate's largest shortfall of a pushed particle */
    float rho_rest;          /* [kg/m^dim] the density held: the sum a particle of the initial lattice reads */
    float delta;             /* [m^2] pcisph: delta at dt = 1 s (delta(dt) = delta / dt^2, in m^2/s^2) */
    float den_full;          /* [kg^2/m^(2 dim + 2)] dfsph: alpha's least denominator, a full neighbourhood's */
    float den_full_v;        /* [kg^2/m^(2 dim + 2)] dfsph: alpha_v's least denominator, a full neighbourhood's */
    float dt_last;           /* [s] the step the kept pressures were solved for (solver_warm_start); 0: none */
    float chebyshev_w;       /* [1] the weight of the density solve's latest correction (solver_chebyshev; 1: none) */
    int chebyshev_from;      /* the iteration the density solve's plain corrections last started from (0, or after a
                                rise under the acceleration, sph_solver_chebyshev_restart) */
    uint64_t restarts;       /* [1] density solves' restarts after a rise under the acceleration, since the start */
    uint64_t iterations_run; /* [1] the density solves' iterations summed over the steps, since the start */
    float *x_df;             /* [m] dfsph: x* of the density iteration, x y z per particle (scratch) */
    uint32_t x_df_cap;       /* [1] particles x_df has room for */
    /* The walls as the lattice continued behind them (src/passes/solver.h):
     * at distance d = i h / SPH_SOLVER_WALL_SAMPLES from a wall, the share of
     * rho_rest the rows behind it add, and its derivative in d. */
    float wall_share[SPH_SOLVER_WALL_SAMPLES + 1];  /* [1] */
    float wall_slope[SPH_SOLVER_WALL_SAMPLES + 1];  /* [1/m] */
} sph_solver_state;

struct sph_sim {
    sph_scene_def def;    /* the scene it was made from; passes read their options here */
    int dim;
    uint32_t n;
    sph_particles P;
    sph_search_data S;
    sph_kernel k_density, k_pressure, k_viscosity;

    double t;             /* [s] simulated time */
    float dt;             /* [s] time step of the current step */
    double t_end;         /* [s] where a run by time ends (0: none): the step that would pass it is
                             shortened to end on it (sph_sim_end_at) */
    uint64_t step;        /* steps completed */
    float max_speed;      /* [m/s] after the latest integration, for the CFL condition */
    float max_acc;        /* [m/s^2] likewise */
    double energy_ref;    /* [J] or [J/m] total energy after the first step (when density, and so the
                             internal energy, first exists): what the HUD's energy drift is measured from */
    bool rho_carried;     /* density_method = continuity: rho_c holds the carried density (set by the
                             density_rate pass's first run); until then the density pass sums */
    float eos_rho0;       /* [kg/m^dim] the density at which the equation of state gives p = 0: rest_density,
                             or the finest lattice's (eos_rest = lattice); its inverse and the energy use it too */
    float period[3];      /* [m] domain length on periodic axes, 0 on others */
    float inv_period[3];  /* [1/m] 1 / period, 0 on non-periodic axes */

    bool in_pipeline[SPH_PASS_COUNT]; /* the scene needs the pass */
    bool enabled[SPH_PASS_COUNT];     /* switched on (a window toggle); only meaningful if in the pipeline */
    sph_pass_timing timing[SPH_PASS_COUNT];
    /* The last SPH_STEP_WINDOW complete steps' times, each the sum of its
     * passes' times (the watchdog's checks left out), in a ring: the HUD's
     * ms per step is their median (sph_sim_step_ms). */
    double step_ms_acc;                  /* [ms] passes of the step under way, so far */
    double step_ms[SPH_STEP_WINDOW];     /* [ms] step k is at k % SPH_STEP_WINDOW */
    uint64_t step_ms_count;              /* steps recorded since creation or sph_sim_reset_timings */
    int next_pass;        /* next pass of the current step, for stepping pass by pass */
    /* Fields whose stored values belong to the particles where they are stored
     * now (the inspector's and the HUD's question between two passes): a
     * reorder moves the fields it writes and leaves the others in the old
     * order until the pass that writes them runs again (sph_sim_step_pass). */
    sph_mask fields_fresh;
    /* Watchdog: after every pass, the fields it wrote are checked. */
    bool watchdog;        /* on by default */
    float speed_bound;    /* [m/s] a speed above this is a runaway: 4 speed_scale + 1 m/s */
    float speed_scale;    /* [m/s] what the scene can make: fall + blocks + mouse + initial compression */
    float speed_fall;     /* [m/s] a fall along g across the domain, sqrt(2 g L) (for the report) */
    double energy_start;  /* [J] or [J/m] total energy at step 0 (NAN: take it at the end of the next step) */
    double energy_scale;  /* [J] or [J/m] |kinetic| + |potential| + |internal| at step 0 */
    float density_bound;  /* [kg/m^dim] likewise for density (100 rho0) */
    sph_alarm alarm;
    /* The interaction effect's point (the mouse), set by the window. */
    bool interaction_active; /* the button is down */
    float interaction_point[3]; /* [m] */
    float interaction_sign;  /* +1 pull, -1 push (times the scene's strength) */
    /* An iterative pass (the pressure solvers) runs one iteration per call
     * and sets pass_again to be called again before the step moves on, so
     * stepping pass by pass shows every iteration (sph_sim_step_pass). */
    bool pass_again;
    sph_solver_state solver;
    int threads;
    sph_backend *backend; /* NULL: the passes run here, on P and S */
    void *backend_share;  /* what the backend was made to share (sph_sim_create_shared); reconfigure keeps it */
    /* Far coordinates: positions (P.pos, P.pred) and sim->def's domain and
     * blocks are relative to the domain's point nearest 0 (0 if it contains
     * 0), so a box at x = 1e4 m runs exactly as one at 0. Output adds this
     * back (sph_sim_abs). */
    double origin[3];     /* [m] absolute position of the simulation frame's zero */
};

/* [kg/m^dim] The density a particle of the scene's finest lattice sums to at
 * rest, its whole support in the fluid (sph_kernel.c): rest_density (1 + e). */
float sph_sim_lattice_rest_density(const sph_sim *sim);
/* DFSPH's alpha denominator for a full neighbourhood of that lattice
 * (sum_j m^2 grad W^rho . grad W^p) [kg^2/m^(2 dim + 2)], 0 without blocks. */
float sph_sim_lattice_dots(const sph_sim *sim);
/* The same with the pressure kernel's gradient in both factors (sum_j m^2 |grad W^p|^2): the divergence solve's. */
float sph_sim_lattice_dots_pressure(const sph_sim *sim);
/* The finest spacing of the scene's blocks [m], 0 without blocks. */
float sph_scene_finest_spacing(const sph_scene_def *def);

/* threads <= 0: one per core; at most SPH_MAX_THREADS. */
sph_error_code sph_sim_create(const sph_scene_def *def, int threads, sph_sim **out, sph_error *err);
/* The same, handing share to the backend's factory: the window or the
 * renderer passes its OpenGL context, so that the GL backend runs in it and
 * its buffers can be drawn without a copy. Ignored on the CPU. */
sph_error_code sph_sim_create_shared(const sph_scene_def *def, int threads, void *share, sph_sim **out,
                                     sph_error *err);
void sph_sim_destroy(sph_sim *sim);

/* Runs the rest of the current time step (all of it if none is under way). */
void sph_sim_step(sph_sim *sim);
/* Runs the next pass of the pipeline; returns its id. The step is complete
 * (t and step advanced) after the last one. */
sph_pass_id sph_sim_step_pass(sph_sim *sim);

/* Switches variants or effects at run time: rebuilds the pipeline and its
 * buffers for `def` and carries the particles (positions, velocities, ids,
 * masses), time and step over. `def` must make the same particles (same
 * dimension and blocks); pass toggles are kept. On error sim is unchanged. */
sph_error_code sph_sim_reconfigure(sph_sim *sim, const sph_scene_def *def, sph_error *err);
/* The same as a new simulation beside sim, which is left as it was: the
 * state carried over into one made for `def` on `threads` threads (the
 * window's level switch, which may change the thread count, and the
 * validate mode's reference run). */
sph_error_code sph_sim_clone(const sph_sim *sim, const sph_scene_def *def, int threads, sph_sim **out,
                             sph_error *err);

/* With a backend: downloads the parts of `what` (SPH_SYNC_* bits) whose host
 * copy is stale; nothing to do on the CPU. Only the host copy changes (a cache
 * of the device's state), so it takes a const sim. Costs a copy from the
 * device: about 4 bytes per particle and component. */
void sph_sim_sync(const sph_sim *sim, sph_mask what);
/* With a backend: sends the particles of P to the device after the caller
 * changed them (sync first, change, then upload). */
void sph_sim_upload(sph_sim *sim);

void sph_sim_stats(const sph_sim *sim, sph_stats *out);
/* Total energy: kinetic + gravitational + internal (the equation of state's). */
double sph_stats_energy(const sph_stats *s);
/* (E - E_ref) / scale with scale = max(|E_ref|, E_kin): the energy drift since
 * the first step, as a fraction; NaN before the first step. */
double sph_sim_energy_drift(const sph_sim *sim);

/* After a step: the compression of the positions it reached, rho / rho_held - 1
 * summed there over the step's lists; its largest over the fluid and the
 * mean of its positive part [1] (src/passes/solver_reached.c). */
void sph_sim_compression(const sph_sim *sim, double *largest, double *mean);
/* The same against the lattice's rest density rho_rest with the solvers'
 * walls (src/passes/solver.h) whatever the pressure model: one yardstick
 * for the equation of state and the solvers (`sphlab bench solvers`). */
void sph_sim_compression_lattice(sph_sim *sim, double *largest, double *mean);

/* The pressure [Pa, N/m in 2D] particle i (storage index) felt in the last
 * step, whatever made it: the equation of state's p; PCISPH's p_pci; DFSPH's
 * rho (kappa + kappa_v), its two solves' stiffness as a pressure (Bender &
 * Koschier 2017: kappa = p / rho). 0 where no pass makes one (no pressure
 * effect). --dump's p column and the study's pressure read it: the field p
 * exists only with the equation of state. */
float sph_sim_pressure(const sph_sim *sim, uint32_t i);

/* The density the pressure model holds: the solvers' rho_rest once a solve
 * set it (pcisph, dfsph), else the equation of state's reference eos_rho0
 * (rest_density, or the lattice's with eos_rest = lattice); *name (if not
 * NULL): its name in the HUD, "rho_rest" or "rho0". [kg/m^dim] */
double sph_density_held(const sph_sim *sim, const char **name);
/* A field of the particles; false if the scene does not allocate it. */
bool sph_sim_field(const sph_sim *sim, sph_field_id id, sph_field *out);
/* m less the fields this scene does not allocate (a pass's writes, said to a user: the reorder pass moves
 * every field it may meet, and listed them all in a scene without obstacles or solvers). */
sph_mask sph_sim_mask_present(const sph_sim *sim, sph_mask m);
/* The watchdog's report: step, pass, particle, its values and neighbours. */
void sph_sim_alarm_report(const sph_sim *sim, char *out, size_t n);

/* ---- the time step (sph_time_step.c) ---- */

/* Largest time step the CFL conditions allow now with factor cfl; *which
 * names the condition that binds ("sound and flow", "forces", "viscosity"). */
float sph_time_step_limit(const sph_sim *sim, float cfl, const char **which);
/* With a fixed dt (cfl = 0): a warning if dt breaks a CFL condition with the
 * reference factor 0.4, naming it and the largest stable dt; with the
 * adaptive step: a warning if dt_min holds it above the scene's own CFL
 * limit; NULL if fine. */
const char *sph_sim_dt_warning(const sph_sim *sim, char *buf, size_t n);
/* A run to t = until [s] (< 0: a run by steps) that would take over 1e9 steps
 * at the current dt: a warning naming dt and the step count, said before the
 * run starts rather than found out after hours; NULL if not. */
const char *sph_sim_length_warning(const sph_sim *sim, double until, char *buf, size_t n);
/* The pass whose force does work on the fluid from outside now (sph_pass.does_work: the mouse while its
 * button is down), NULL if none: the energy is not conserved then, by design. */
const char *sph_sim_work_done_by(const sph_sim *sim);
/* A run by time ends on t_end [s]: the step that would pass it is shortened
 * to end there, so `--time 0.005` stops at 0.005 s, not at the first step past
 * it; sph_sim_reached says when it has. t_end <= 0: no end. */
void sph_sim_end_at(sph_sim *sim, double t_end);
bool sph_sim_reached(const sph_sim *sim, double t_end);
void sph_sim_reset_timings(sph_sim *sim);
/* [ms] median time per step over the last min(SPH_STEP_WINDOW, steps run)
 * complete steps, NaN before the first; *steps (if not NULL) gets that count. */
double sph_sim_step_ms(const sph_sim *sim, int *steps);
/* A backend's device-measured times of one complete step [ms], per pass
 * (negative: the pass did not run): filed as run() on the host clock files
 * them (total_ms, last_ms, the step window). calls are counted when run. */
void sph_sim_record_step_times(sph_sim *sim, const double ms[SPH_PASS_COUNT]);
/* Waits for the times a backend still owes (sph_backend.device_times), so
 * that a timing table read next counts every step run; nothing otherwise. */
void sph_sim_collect_times(sph_sim *sim);

/* Why the time step has its value now, in words: fixed, the cap [time] dt,
 * the floor dt_min, or the CFL condition that binds. */
const char *sph_time_step_reason(const sph_sim *sim, char *buf, size_t n);
/* Time-step choice: fixed, or the CFL conditions. */
float sph_time_step_choose(const sph_sim *sim);

/* Calls fn(args..., dim, dbl) with the dimension and the accumulation
 * precision as constants, so that an inlined per-particle function is
 * compiled once per combination: loops over axes unrolled, sums in float or
 * double ([physics] accumulate) without a test in the inner loop. */
#define SPH_SPECIALISE(dim, dbl, fn, ...)                                                \
    ((dim) == 2 ? ((dbl) ? fn(__VA_ARGS__, 2, true) : fn(__VA_ARGS__, 2, false))         \
                : ((dbl) ? fn(__VA_ARGS__, 3, true) : fn(__VA_ARGS__, 3, false)))
/* The same with a third constant, fn(args..., dim, dbl, periodic): whether
 * any axis is periodic (the minimum image costs a rounding per axis and pair;
 * most scenes need none). */
#define SPH_SPECIALISE_P(dim, dbl, per, fn, ...)                                               \
    ((per) ? ((dim) == 2 ? ((dbl) ? fn(__VA_ARGS__, 2, true, true) : fn(__VA_ARGS__, 2, false, true))   \
                         : ((dbl) ? fn(__VA_ARGS__, 3, true, true) : fn(__VA_ARGS__, 3, false, true)))  \
           : ((dim) == 2 ? ((dbl) ? fn(__VA_ARGS__, 2, true, false) : fn(__VA_ARGS__, 2, false, false)) \
                         : ((dbl) ? fn(__VA_ARGS__, 3, true, false) : fn(__VA_ARGS__, 3, false, false))))
#define sph_sim_periodic(sim) ((sim)->period[0] > 0 || (sim)->period[1] > 0 || (sim)->period[2] > 0)

/* The watchdog (sph_watchdog.c), run by the pipeline after each pass. */
void sph_watchdog_check(sph_sim *sim, int pass);
/* After a complete step: total energy against its value at step 0 (pass: the
 * step's last pass, named in the report). */
void sph_watchdog_energy(sph_sim *sim, int pass);

/* Absolute coordinate along axis d of a position x of the simulation frame. */
static inline double sph_sim_abs(const sph_sim *sim, int d, float x)
{
    return sim->origin[d] + (double)x;
}
/* Whether the frame is shifted (output then needs more digits than a float). */
#define sph_sim_shifted(sim) ((sim)->origin[0] != 0 || (sim)->origin[1] != 0 || (sim)->origin[2] != 0)

/* Monotonic clock [ms]. */
double sph_now_ms(void);

#endif
