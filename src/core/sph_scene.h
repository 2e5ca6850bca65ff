/* A scene: everything a simulation starts from. sph_default_scene_def() gives
 * every field its documented default; a scene file (INI) and --set overrides
 * change only the keys they name. One table (sph_scene_keys) describes every
 * key: section, name, type, unit, range, default and help. The parser, the
 * validation, `sphlab keys` and docs/scene-format.md all follow from it. */
#ifndef SPH_SCENE_H
#define SPH_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "sph_error.h"
#include "sph_kernel.h"

#define SPH_MAX_BLOCKS 32
#define SPH_MAX_KEYS 96

/* Effects a scene can ask for; each pulls in the passes it needs. The last
 * column says whether it needs each particle's density (and so the
 * neighbour search): DENSITY, or NONE. */
#define SPH_EFFECTS(X)                                                                                 \
    X(GRAVITY, "gravity", "uniform body force g", NONE)                                                \
    X(DENSITY, "density", "density by kernel summation (nothing moves by it)", DENSITY)                \
    X(PRESSURE, "pressure", "equation of state and pressure force", DENSITY)                           \
    X(VISCOSITY, "viscosity", "viscous force", DENSITY)                                                \
    X(COHESION, "cohesion", "attraction between particles that makes a surface contract (surface tension)", DENSITY) \
    X(WALLS, "walls", "the domain box reflects particles", NONE)                                       \
    X(INTERACTION, "interaction", "push or pull the fluid around a point (the mouse)", NONE)

enum {
#define SPH_EFFECT_BIT(id, name, about, needs) SPH_EFFECT_BIT_##id,
    SPH_EFFECTS(SPH_EFFECT_BIT)
#undef SPH_EFFECT_BIT
    SPH_EFFECT_COUNT
};
#define SPH_EFFECT(id) (1u << SPH_EFFECT_BIT_##id)
/* The effects that need density: a constant made from the list's last column. */
#define SPH_EFFECT_NEEDS_DENSITY_ 1
#define SPH_EFFECT_NEEDS_NONE_ 0
#define SPH_EFFECT_DENSITY_BIT_(id, name, about, needs) | (SPH_EFFECT_NEEDS_##needs##_ ? SPH_EFFECT(id) : 0u)
#define SPH_EFFECTS_NEEDING_DENSITY (0u SPH_EFFECTS(SPH_EFFECT_DENSITY_BIT_))
extern const char *const sph_effect_names[SPH_EFFECT_COUNT];
extern const char *const sph_effect_about[SPH_EFFECT_COUNT];

/* The choices of each switchable method, as enums with their names. */
#define SPH_EOS_CHOICES(X) X(LINEAR, "linear") X(TAIT, "tait")
#define SPH_EOS_REST_CHOICES(X) X(REST_DENSITY, "rest_density") X(LATTICE, "lattice")
#define SPH_PFORM_CHOICES(X) X(SYMMETRIC, "symmetric") X(SHARED, "shared")
#define SPH_VFORM_CHOICES(X) X(LAPLACIAN, "laplacian") X(SMOOTHING, "smoothing") X(MORRIS, "morris") X(ARTIFICIAL, "artificial") \
    X(MORRIS_ARTIFICIAL, "morris-artificial")
#define SPH_SEARCH_CHOICES(X) X(HASH, "hash") X(GRID, "grid") X(BRUTE, "brute")
#define SPH_SORT_CHOICES(X) X(BITONIC, "bitonic") X(COUNTING, "counting") X(QSORT, "qsort") X(NONE, "none")
#define SPH_NEGP_CHOICES(X) X(KEEP, "keep") X(CLAMP, "clamp")
#define SPH_WALL_CHOICES(X) X(VOLUME, "volume") X(REFLECT, "reflect") X(PARTICLES, "particles")
#define SPH_SLIP_CHOICES(X) X(NO, "no") X(FREE, "free")
#define SPH_WALL_FORCE_CHOICES(X) X(ENERGY, "energy") X(GHOST, "ghost")
#define SPH_SIDE_SLIP_CHOICES(X) X(SAME, "same") X(NO, "no") X(FREE, "free")
#define SPH_SHAPE_CHOICES(X) X(BOX, "box") X(CIRCLE, "circle")
#define SPH_DMETHOD_CHOICES(X) X(SUMMATION, "summation") X(CONTINUITY, "continuity")
#define SPH_DFORM_CHOICES(X) X(MOLTENI, "molteni") X(ANTUONO, "antuono") X(FOURTAKAS, "fourtakas")
#define SPH_SHIFT_CHOICES(X) X(NONE, "none") X(LIND, "lind") X(TVF, "tvf")
#define SPH_FIELD_CHOICES(X) X(UNIFORM, "uniform") X(TAYLOR_GREEN, "taylor-green")
#define SPH_INITP_CHOICES(X) X(NONE, "none") X(HYDROSTATIC, "hydrostatic")
#define SPH_ACC_CHOICES(X) X(FLOAT, "float") X(DOUBLE, "double")
#define SPH_POSSUM_CHOICES(X) X(FLOAT, "float") X(COMPENSATED, "compensated")
#define SPH_ONOFF_CHOICES(X) X(OFF, "off") X(ON, "on")
#define SPH_BACKEND_CHOICES(X) X(CPU, "cpu") X(GL, "gl")
#define SPH_PSOLVER_CHOICES(X) X(EOS, "eos") X(PCISPH, "pcisph") X(DFSPH, "dfsph")
#define SPH_SWALLP_CHOICES(X) X(NONE, "none") X(EXTRAPOLATED, "extrapolated")
#define SPH_STENSION_CHOICES(X) X(NONE, "none") X(AKINCI, "akinci") X(CSF, "csf") X(STRESS, "stress")

#define SPH_DECLARE_CHOICES(type, PREFIX, LIST)                          \
    typedef enum type { LIST(SPH_CHOICE_ITEM_##PREFIX) PREFIX##_COUNT } type;
#define SPH_CHOICE_ITEM_SPH_EOS(id, name) SPH_EOS_##id,
#define SPH_CHOICE_ITEM_SPH_EOSREST(id, name) SPH_EOSREST_##id,
#define SPH_CHOICE_ITEM_SPH_PFORM(id, name) SPH_PFORM_##id,
#define SPH_CHOICE_ITEM_SPH_VFORM(id, name) SPH_VFORM_##id,
#define SPH_CHOICE_ITEM_SPH_SEARCH(id, name) SPH_SEARCH_##id,
#define SPH_CHOICE_ITEM_SPH_SORT(id, name) SPH_SORT_##id,
#define SPH_CHOICE_ITEM_SPH_NEGP(id, name) SPH_NEGP_##id,
#define SPH_CHOICE_ITEM_SPH_WALL(id, name) SPH_WALL_##id,
#define SPH_CHOICE_ITEM_SPH_SLIP(id, name) SPH_SLIP_##id,
#define SPH_CHOICE_ITEM_SPH_WFORCE(id, name) SPH_WFORCE_##id,
#define SPH_CHOICE_ITEM_SPH_SIDE_SLIP(id, name) SPH_SIDE_SLIP_##id,
#define SPH_CHOICE_ITEM_SPH_SHAPE(id, name) SPH_SHAPE_##id,
#define SPH_CHOICE_ITEM_SPH_DMETHOD(id, name) SPH_DMETHOD_##id,
#define SPH_CHOICE_ITEM_SPH_DFORM(id, name) SPH_DFORM_##id,
#define SPH_CHOICE_ITEM_SPH_SHIFT(id, name) SPH_SHIFT_##id,
#define SPH_CHOICE_ITEM_SPH_VFIELD(id, name) SPH_VFIELD_##id,
#define SPH_CHOICE_ITEM_SPH_INITP(id, name) SPH_INITP_##id,
#define SPH_CHOICE_ITEM_SPH_ACC(id, name) SPH_ACC_##id,
#define SPH_CHOICE_ITEM_SPH_POSSUM(id, name) SPH_POSSUM_##id,
#define SPH_CHOICE_ITEM_SPH_ONOFF(id, name) SPH_##id,
#define SPH_CHOICE_ITEM_SPH_BACKEND(id, name) SPH_BACKEND_##id,
#define SPH_CHOICE_ITEM_SPH_PSOLVER(id, name) SPH_PSOLVER_##id,
#define SPH_CHOICE_ITEM_SPH_STENSION(id, name) SPH_STENSION_##id,
#define SPH_CHOICE_ITEM_SPH_SWALLP(id, name) SPH_SWALLP_##id,
SPH_DECLARE_CHOICES(sph_eos, SPH_EOS, SPH_EOS_CHOICES)
SPH_DECLARE_CHOICES(sph_eos_rest, SPH_EOSREST, SPH_EOS_REST_CHOICES)
SPH_DECLARE_CHOICES(sph_pressure_form, SPH_PFORM, SPH_PFORM_CHOICES)
SPH_DECLARE_CHOICES(sph_viscosity_form, SPH_VFORM, SPH_VFORM_CHOICES)
SPH_DECLARE_CHOICES(sph_search, SPH_SEARCH, SPH_SEARCH_CHOICES)
SPH_DECLARE_CHOICES(sph_sort, SPH_SORT, SPH_SORT_CHOICES)
SPH_DECLARE_CHOICES(sph_negative_pressure, SPH_NEGP, SPH_NEGP_CHOICES)
SPH_DECLARE_CHOICES(sph_wall_model, SPH_WALL, SPH_WALL_CHOICES)
SPH_DECLARE_CHOICES(sph_wall_slip, SPH_SLIP, SPH_SLIP_CHOICES)
SPH_DECLARE_CHOICES(sph_wall_force, SPH_WFORCE, SPH_WALL_FORCE_CHOICES)
SPH_DECLARE_CHOICES(sph_side_slip, SPH_SIDE_SLIP, SPH_SIDE_SLIP_CHOICES)
SPH_DECLARE_CHOICES(sph_shape, SPH_SHAPE, SPH_SHAPE_CHOICES)
SPH_DECLARE_CHOICES(sph_density_method, SPH_DMETHOD, SPH_DMETHOD_CHOICES)
SPH_DECLARE_CHOICES(sph_delta_form, SPH_DFORM, SPH_DFORM_CHOICES)
SPH_DECLARE_CHOICES(sph_shifting, SPH_SHIFT, SPH_SHIFT_CHOICES)
SPH_DECLARE_CHOICES(sph_velocity_field, SPH_VFIELD, SPH_FIELD_CHOICES)
SPH_DECLARE_CHOICES(sph_initial_pressure, SPH_INITP, SPH_INITP_CHOICES)
SPH_DECLARE_CHOICES(sph_accumulate, SPH_ACC, SPH_ACC_CHOICES)
SPH_DECLARE_CHOICES(sph_position_sum, SPH_POSSUM, SPH_POSSUM_CHOICES)
SPH_DECLARE_CHOICES(sph_onoff, SPH_ONOFF, SPH_ONOFF_CHOICES)
SPH_DECLARE_CHOICES(sph_backend_kind, SPH_BACKEND, SPH_BACKEND_CHOICES)
SPH_DECLARE_CHOICES(sph_pressure_solver, SPH_PSOLVER, SPH_PSOLVER_CHOICES)
SPH_DECLARE_CHOICES(sph_surface_tension, SPH_STENSION, SPH_STENSION_CHOICES)
SPH_DECLARE_CHOICES(sph_solver_wall_pressure, SPH_SWALLP, SPH_SWALLP_CHOICES)

extern const char *const sph_eos_names[SPH_EOS_COUNT];
extern const char *const sph_wall_force_names[SPH_WFORCE_COUNT];
extern const char *const sph_eos_rest_names[SPH_EOSREST_COUNT];
extern const char *const sph_pressure_form_names[SPH_PFORM_COUNT];
extern const char *const sph_viscosity_form_names[SPH_VFORM_COUNT];
extern const char *const sph_search_names[SPH_SEARCH_COUNT];
extern const char *const sph_sort_names[SPH_SORT_COUNT];
extern const char *const sph_negative_pressure_names[SPH_NEGP_COUNT];
extern const char *const sph_wall_model_names[SPH_WALL_COUNT];
extern const char *const sph_wall_slip_names[SPH_SLIP_COUNT];
extern const char *const sph_side_slip_names[SPH_SIDE_SLIP_COUNT];
extern const char *const sph_shape_names[SPH_SHAPE_COUNT];
extern const char *const sph_density_method_names[SPH_DMETHOD_COUNT];
extern const char *const sph_delta_form_names[SPH_DFORM_COUNT];
extern const char *const sph_shifting_names[SPH_SHIFT_COUNT];
extern const char *const sph_axis_names[3];
extern const char *const sph_velocity_field_names[SPH_VFIELD_COUNT];
extern const char *const sph_initial_pressure_names[SPH_INITP_COUNT];
extern const char *const sph_accumulate_names[SPH_ACC_COUNT];
extern const char *const sph_position_sum_names[SPH_POSSUM_COUNT];
extern const char *const sph_onoff_names[SPH_ONOFF_COUNT];
extern const char *const sph_backend_names[SPH_BACKEND_COUNT];
extern const char *const sph_pressure_solver_names[SPH_PSOLVER_COUNT];
extern const char *const sph_surface_tension_names[SPH_STENSION_COUNT];
extern const char *const sph_solver_wall_pressure_names[SPH_SWALLP_COUNT];

/* Where a value came from, for messages: the file's line, or 0 for the default. */
typedef struct sph_origin {
    int line;   /* 1-based line in the scene file; 0: default; -1: --set */
    int ncomp;  /* number of components given, for vectors */
} sph_origin;

/* Keys a [fluid NAME] or [obstacle NAME] section can hold: one origin slot
 * each. tests/test_scene.c counts the key table's keys of each against it. */
#define SPH_GROUP_KEYS_MAX 8

/* Longest fluid block name: the INI parser keeps 49 characters of a section
 * header and "fluid " takes 6; longer names are refused, never cut. */
#define SPH_BLOCK_NAME_MAX 43

/* A box filled with particles on a square/cubic lattice. */
typedef struct sph_block_def {
    char name[48];
    double min[3];     /* [m] lower corner of the box (double: a far box keeps its exact size) */
    double max[3];     /* [m] upper corner of the box */
    float spacing;     /* [m] lattice spacing; each particle carries rest_density * spacing^dim of mass */
    float velocity[3]; /* [m/s] initial velocity (uniform); amplitude U = velocity.x (taylor-green) */
    sph_velocity_field field; /* uniform, or the Taylor-Green vortex of the domain's size */
    sph_onoff field_pressure; /* on: start with the field's pressure (taylor-green), carried by the masses */
    sph_initial_pressure initial_pressure; /* none (rho0 everywhere), or hydrostatic: each particle's mass holds
                                            * the equation of state's density at rho0 g (its depth in the block) */
    int line;          /* line of the [fluid ...] section header, for messages */
    sph_origin origin[SPH_GROUP_KEYS_MAX];
} sph_block_def;

/* Longest obstacle name: "obstacle " takes 9 of inih's 49 characters. */
#define SPH_MAX_OBSTACLES 16
#define SPH_OBSTACLE_NAME_MAX 40

/* A solid obstacle made of wall particles (wall_model = particles,
 * src/core/sph_obstacles.c): a box, or a circle (a sphere in 3D). */
typedef struct sph_obstacle_def {
    char name[48];
    sph_shape shape;
    double min[3];     /* [m] box: lower corner (double, as the domain's: exact far from 0) */
    double max[3];     /* [m] box: upper corner */
    double centre[3];  /* [m] circle: centre */
    float radius;      /* [m] circle: radius */
    sph_wall_slip slip; /* no: no-slip surface (velocity mirrored); free: free-slip */
    int line;          /* line of the [obstacle ...] section header, for messages */
    sph_origin origin[SPH_GROUP_KEYS_MAX];
} sph_obstacle_def;

/* solver_chebyshev: the correction of a density solve the acceleration starts at (src/passes/solver.h); corrections
 * 1 to 9 are plain, so a solve needs solver_max_iterations >= 11 (N iterations make N - 1 corrections) to be
 * accelerated at all (sph_scene_validate.c warns) */
#define SPH_CHEBYSHEV_FIRST 10

typedef struct sph_scene_def {
    char file[256];    /* scene file it was read from, for messages */
    char name[64];     /* title shown in tables and windows */
    int dim;           /* [1] 2 or 3 */
    unsigned effects;  /* SPH_EFFECT(...) bits */
    double domain_min[3], domain_max[3]; /* [m] the box walls bound; double, so a box far from 0 keeps
                                            its exact size (the simulation works relative to domain_min) */
    float wall_damping;                 /* [1] share of the normal speed kept at a wall bounce */
    sph_wall_model wall_model;          /* volume: walls also count in density and pressure; particles:
                                           layers of fixed wall particles (Adami et al. 2012) */
    sph_wall_force wall_force;          /* volume: the walls' pressure force, the energy's gradient or ghosts */
    sph_wall_slip wall_slip;            /* particles: the wall particles' velocity in the viscous term
                                           (no: mirrored, no-slip; free: the fluid's, free-slip) */
    unsigned periodic;                  /* bit d: axis d wraps around (no walls on it) */
    sph_side_slip wall_slip_side[6];    /* per side (xmin, xmax, ymin, ymax, zmin, zmax): same as wall_slip,
                                           or no / free for that side's wall particles */
    float wall_velocity[3];             /* [m/s] particles: velocity of the wall particles beyond the top
                                           wall (y max), tangential; they stay in place (Couette, a lid) */
    int n_blocks;
    sph_block_def blocks[SPH_MAX_BLOCKS];
    int n_obstacles;
    sph_obstacle_def obstacles[SPH_MAX_OBSTACLES]; /* [obstacle NAME] blocks, in file order */

    float h;            /* [m] kernel support radius (= cell size of the search) */
    float rest_density; /* [kg/m^dim] rho0 */
    sph_eos eos;
    sph_eos_rest eos_rest; /* the density the equation of state holds: rest_density, or the finest lattice's */
    float stiffness;    /* [m^2/s^2] k in p = k (rho - rho0); c = sqrt(k) is the speed of sound */
    float tait_gamma;   /* [1] exponent of the Tait equation */
    sph_negative_pressure negative_pressure;
    sph_pressure_form pressure_form;
    float viscosity;    /* [m^2/s] kinematic viscosity nu */
    float cohesion;     /* [m^4/(kg s^2)] Akinci's cohesion coefficient gamma (effect cohesion) */
    sph_viscosity_form viscosity_form;
    sph_accumulate accumulate;  /* sums in float (fast) or double (accurate) */
    float gravity[3];   /* [m/s^2] */
    float alpha;        /* [1] Monaghan's artificial viscosity coefficient (viscosity_form = artificial, morris-artificial) */
    float gravity_ramp; /* [s] gravity grows smoothly from 0 to g over this time; 0: full g from the start */
    float damping_time; /* [s] velocities are damped, less and less, over this time; 0: no damping */
    sph_density_method density_method; /* summation each step, or carried by the continuity equation */
    float delta;        /* [1] delta of the density diffusion term (density_method = continuity) */
    sph_delta_form delta_form; /* the diffusion term: Molteni & Colagrossi 2009, or Antuono et al. 2010 */
    sph_shifting shifting;     /* particle shifting after each step: none, or Lind et al. 2012 */
    float shifting_coefficient; /* [1] A of the shift distance D = A h |v| dt (shifting = lind) */
    sph_pressure_solver pressure_solver; /* eos: pressure from the equation of state; pcisph, dfsph: iterated */
    float solver_tolerance;     /* [1] pcisph, dfsph: largest relative density error a step may end with */
    int solver_max_iterations;  /* [1] pcisph, dfsph: iterations a solve may take at most */
    float divergence_tolerance; /* [1] dfsph: largest dt |D rho/Dt| / rho_rest the divergence solve may leave */
    sph_onoff solver_warm_start; /* pcisph, dfsph: each solve starts from the last step's pressure, not from 0 */
    sph_onoff pcisph_local_delta; /* pcisph: delta from each particle's own neighbourhood, not the full lattice's */
    float solver_chebyshev;     /* [1] pcisph, dfsph: the spectral radius the density solve's Chebyshev acceleration
                                   assumes (Wang 2015); 0: plain Jacobi steps */
    sph_solver_wall_pressure solver_wall_pressure; /* pcisph, dfsph with wall particles: none (they push with the
                                                      fluid particle's own) or extrapolated from the fluid (Adami) */
    sph_surface_tension surface_tension; /* none; akinci: Akinci 2013 (passes cohesion, normals, curvature); csf: a
                                            continuum surface force of stated sigma (passes normals, csf) */
    float surface_tension_coefficient;   /* [m^4/(kg s^2)] gamma of surface_tension = akinci (the cohesion pass's
                                            gamma then; in 2D m^3/(kg s^2)) */
    float xsph;                          /* [1] epsilon of XSPH velocity smoothing (Monaghan 1989); 0: none */
    float sigma;                         /* [N/m] surface tension of surface_tension = csf (2D: N, per metre of depth) */
    sph_kernel_kind kernel_density, kernel_pressure, kernel_viscosity;

    float dt;           /* [s] time step when cfl = 0; the first step's bound otherwise */
    float cfl;          /* [1] Courant factor; > 0 selects the adaptive time step */
    float dt_min;       /* [s] the adaptive step never goes below this */
    sph_position_sum position_sum; /* x += dt v in float, or compensated (a per-particle remainder, pos_r) */
    int steps;          /* [1] default run length in steps (--steps overrides) */
    float duration;     /* [s] default run length in simulated time; 0: use steps */

    sph_search search;
    sph_sort sort;
    uint32_t table_size; /* [1] hash table size; 0: the particle count, as in the seed */
    sph_onoff reorder;   /* store the particles in cell order after the sort (for memory locality) */
    sph_onoff vector;    /* use the CPU's vector instructions (AVX-512) in the inner loops where written */
    sph_onoff vector_avx2; /* the pair passes' vector loops in AVX2, 8 lanes, instead of AVX-512's 16 */
    sph_onoff cell_batch;  /* AVX2 search: a cell's particles tested together against each candidate vector */
    sph_onoff wide_batch;  /* with cell_batch: 16 candidates to a vector (AVX-512) instead of 8 */
    sph_onoff lists_in_place; /* the first thread builds its lists straight into the joined array */
    sph_onoff lists_resident; /* with lists_in_place: the copied lists' pages kept from build to build */
    sph_onoff compact_lists;  /* neighbour lists as 16-bit offsets j - i (a wide row's 32-bit indices as escape) */
    float skin;          /* [1] Verlet skin in units of h: lists reach h (1 + skin) and are kept while every
                            particle has moved less than skin h / 2 since their build; 0: built every step */
    sph_backend_kind backend; /* where the passes run: the CPU, or GL compute shaders (src/gpu/) */
    sph_onoff fuse_forces; /* pressure force and viscosity in one walk of the lists, where the forms allow */
    sph_onoff packed_records; /* AVX2 pair loops read neighbours from one record per particle, not field gathers */
    sph_onoff uniform_mass;   /* with packed_records: one mass for all, a constant of the force walk */
    sph_onoff wide_density;   /* with packed_records: density's record walk 16 neighbours at a time (AVX-512) */
    float jitter;        /* [1] random offset of each particle, in spacings */
    uint32_t seed;       /* [1] random seed of the jitter */
    float interaction_radius;   /* [m] reach of the push/pull around the point */
    float interaction_strength; /* [m/s^2] acceleration at the point; > 0 pulls, < 0 pushes */

    sph_origin origin[SPH_MAX_KEYS]; /* per key of sph_scene_keys */
} sph_scene_def;

sph_scene_def sph_default_scene_def(void);

/* Reads a scene file over *def (normally the defaults). Checks each value
 * against its range; the caller applies any overrides, then calls
 * sph_scene_validate for the checks that involve several keys. */
sph_error_code sph_scene_load(const char *path, sph_scene_def *def, sph_error *err);
/* Same from a string (tests, fuzzing); `name` stands for the file in messages. */
sph_error_code sph_scene_load_string(const char *text, const char *name, sph_scene_def *def,
                                     sph_error *err);
/* Applies one "section.key=value" override (the command line's --set). */
sph_error_code sph_scene_set(sph_scene_def *def, const char *assignment, sph_error *err);
/* Cross-checks the scene: blocks inside the domain, particle count, memory. */
sph_error_code sph_scene_validate(const sph_scene_def *def, sph_error *err);
/* Choices valid alone that do not work together (sph_scene_combos.c); part of
 * sph_scene_validate. */
sph_error_code sph_scene_check_combinations(const sph_scene_def *def, sph_error *err);
/* Where [section] name's value came from, in buf: "file:line", "--set", or the
 * file's name alone for a default (sph_scene_combos.c). */
const char *sph_scene_key_where(const sph_scene_def *def, const char *section, const char *name, char *buf,
                                size_t n);
/* Its first check (sph_scene.c, where the parser records the components):
 * in a 3D scene every vector given has 3 components. */
sph_error_code sph_scene_check_components(const sph_scene_def *def, sph_error *err);
/* In a 2D scene, the first vector the file or --set gave with a non-zero z
 * (which 2D ignores: a 3D scene without dimension = 3, gravity along -z),
 * as "file:line: [section] key has a z component ..." in buf; NULL if none. */
const char *sph_scene_ignored_z(const sph_scene_def *def, char *buf, size_t n);

/* Number of particles the blocks make (a double: counts can be absurd before validation). */
double sph_scene_particle_count(const sph_scene_def *def);
/* Neighbours a particle of the finest block has inside its support:
 * pi (h/s)^2 in 2D, 4/3 pi (h/s)^3 in 3D (about 12 and 33 at h = 2s). */
double sph_scene_neighbour_estimate(const sph_scene_def *def);
/* The warnings for a scene that is valid but not the one written, or will be slow or poor: every one that
 * applies, one per line in buf (NULL if none). */
const char *sph_scene_warning(const sph_scene_def *def, char *buf, size_t n);
/* Each warning on its own line "sphlab: warning: ..." on f. */
void sph_scene_warnings_print(const sph_scene_def *def, FILE *f);

/* Positions of block b's lattice along axis a: count of nodes. */
int64_t sph_block_nodes(const sph_scene_def *def, int b, int axis);

/* The key table, for help text and docs. */
typedef enum sph_key_type {
    SPH_KEY_FLOAT, SPH_KEY_INT, SPH_KEY_UINT, SPH_KEY_VEC, SPH_KEY_CHOICE, SPH_KEY_KERNEL,
    SPH_KEY_FLAGS, SPH_KEY_STRING,
    SPH_KEY_POINT /* a vector stored as double[3]: a position, exact far from the origin */
} sph_key_type;

typedef struct sph_key {
    const char *section;   /* "fluid" stands for every [fluid NAME] block, "obstacle" for every [obstacle NAME] */
    const char *name;
    sph_key_type type;
    int offset;            /* into sph_scene_def, or into sph_block_def (sph_obstacle_def) for fluid (obstacle) keys */
    double min, max;       /* accepted range (inclusive unless min_open/max_open) */
    bool min_open, max_open;
    const char *const *choices; int n_choices;
    const char *unit;
    const char *def;       /* default, as written in a file */
    const char *help;
} sph_key;

extern const sph_key sph_scene_keys[];
extern const int sph_scene_key_count;
/* "physics.viscosity=VALUE" for each section that has a key NAME, joined by ", " and " or "; "" if none
 * (the hint of a --set without its section); value NULL: "physics.viscosity". */
void sph_scene_key_sections(const char *name, const char *value, char *out, size_t n);

/* The value of key k stored at base (the def, or a block for fluid keys) as a
 * scene file writes it (floats with 9 digits, so they read back exactly). */
void sph_scene_value_text(const sph_key *k, const void *base, char *out, size_t n);
/* Set every key of one [fluid] or [obstacle] block (kind "fluid", "obstacle") to its default. */
void sph_scene_block_defaults(void *block, const char *kind);
/* Writes def as a scene file (sph_scene_write.c): name, dimension, every key
 * that differs from its default, each fluid block. Loading the text over the
 * defaults gives the same values. The I/O layer's sph_io_save_scene writes it
 * to a path atomically. */
sph_error_code sph_scene_write(const sph_scene_def *def, FILE *f, sph_error *err);

#endif
