/* The pipeline: every pass of a time step, in order, written once.
 *
 * The X-macro below is the only list of passes. The pass enum, the table of
 * pass descriptors, the timing table, the CSV columns, `sphlab check` and the
 * window's toggles all expand from it. To add a pass: add a line here and
 * write src/passes/NAME.c defining `const sph_pass sph_pass_NAME` (the
 * Makefile builds every file of src/passes/; docs/architecture.md, "How to
 * add a pass", lists the other files a pass with a field, an effect and a
 * key touches). */
#ifndef SPH_PASS_H
#define SPH_PASS_H

#include <stdbool.h>
#include <stdint.h>

#include "sph_scene.h"

#define SPH_PASSES(X)      \
    X(EXTERNAL, external)  \
    X(HASH, hash)          \
    X(SORT, sort)          \
    X(REORDER, reorder)    \
    X(OFFSETS, offsets)    \
    X(NEIGHBOURS, neighbours) \
    X(DENSITY_GRADIENT, density_gradient) \
    X(DENSITY_RATE, density_rate) \
    X(DENSITY, density)    \
    X(PRESSURE, pressure)  \
    X(WALL_STATE, wall_state) \
    X(PRESSURE_FORCE, pressure_force) \
    X(VISCOSITY, viscosity) \
    X(COHESION, cohesion)  \
    X(NORMALS, normals)    \
    X(CURVATURE, curvature) \
    X(CSF, csf)            \
    X(SURFACE_STRESS, surface_stress) \
    X(XSPH, xsph)          \
    X(INTERACTION, interaction) \
    X(PCISPH, pcisph)      \
    X(DFSPH, dfsph)        \
    X(INTEGRATE, integrate) \
    X(SHIFTING, shifting) \
    X(TRANSPORT, transport) \
    X(WALLS, walls)

typedef enum sph_pass_id {
#define SPH_PASS_ENUM(id, name) SPH_PASS_##id,
    SPH_PASSES(SPH_PASS_ENUM)
#undef SPH_PASS_ENUM
    SPH_PASS_COUNT
} sph_pass_id;

typedef struct sph_sim sph_sim;

/* A set of particle fields and search data, one bit each (sph_fields.h). */
typedef uint64_t sph_mask;

/* Where a pass sits in the step, for the HUD's and the charts' grouping. */
#define SPH_PASS_GROUPS(X) X(FORCES_EXTERNAL, "external") X(SEARCH, "search") X(DENSITY, "density") \
    X(FORCES, "forces") X(INTEGRATE, "integrate") X(BOUNDARY, "boundary")
typedef enum sph_pass_group {
#define SPH_GROUP_ENUM(id, name) SPH_GROUP_##id,
    SPH_PASS_GROUPS(SPH_GROUP_ENUM)
#undef SPH_GROUP_ENUM
    SPH_GROUP_COUNT
} sph_pass_group;
extern const char *const sph_pass_group_names[SPH_GROUP_COUNT];

/* What every pass provides, written with designated initialisers. A pass
 * reads the fields and search data in `reads` and writes only those in
 * `writes` (SPH_BIT(RHO) | SPH_RES_LISTS ...: a misspelt field is a compile
 * error); none writes a buffer that it also reads for another particle in
 * the same sweep, so thread order cannot change a result. The watchdog checks
 * what a pass writes, and a backend's host copy goes stale by it. */
typedef struct sph_pass {
    const char *name;    /* as in CSV columns and `--set`-like toggles */
    const char *summary; /* one line for `sphlab check` and the HUD */
    sph_mask reads;      /* fields and search data read */
    sph_mask writes;     /* fields and search data written */
    sph_pass_group group;
    const char *highlight; /* the colour-by name to show after this pass (a field's colour, "key",
                              "neighbours"); NULL keeps the colour (a test checks every name exists) */
    /* NULL if the scene needs this pass, else why it is left out. */
    const char *(*skip_reason)(const sph_scene_def *def);
    /* The variant the scene selects, e.g. "bitonic" or "poly6 kernel". */
    void (*describe)(const sph_scene_def *def, char *out, int n);
    void (*run)(sph_sim *sim);
    /* What the watchdog needs of a force from outside the fluid (the mouse; a wind), so that such a pass is
     * one file: */
    /* [m/s] the speed its force can give the fluid, added to the speed bound; NULL: none of its own */
    double (*speed_scale)(const sph_scene_def *def);
    /* whether it does work on the fluid now (the mouse while the button is down): the energy check takes its
     * reference again, and the HUD shows no energy drift; NULL: never */
    bool (*does_work)(const sph_sim *sim);
} sph_pass;

#define SPH_PASS_EXTERN(id, name) extern const sph_pass sph_pass_##name;
SPH_PASSES(SPH_PASS_EXTERN)
#undef SPH_PASS_EXTERN

extern const sph_pass *const sph_passes[SPH_PASS_COUNT];

/* Scene tests the passes share in their skip_reason. */
bool sph_scene_needs_neighbours(const sph_scene_def *def);
bool sph_scene_needs_density(const sph_scene_def *def);
/* Walls listed, with wall_model = volume: they count in density and pressure. */
bool sph_scene_wall_volume(const sph_scene_def *def);
#define sph_sim_wall_volume(sim) sph_scene_wall_volume(&(sim)->def)
/* A pressure solver (pcisph, dfsph) makes the pressure: chosen, with the effect pressure. */
bool sph_scene_pressure_solver(const sph_scene_def *def);
/* Walls listed, with wall_model = particles and pressure computed: layers of
 * fixed wall particles (src/core/sph_wall_particles.c). */
bool sph_scene_wall_particles(const sph_scene_def *def);

#endif
