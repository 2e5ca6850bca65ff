/* The registry of particle fields: every per-particle array of the
 * simulation, described once.
 *
 * SPH_FIELDS below is the only list. The storage (sph_particles' members),
 * allocation and freeing, the watchdog's checks, CPU<->GPU sync bits,
 * --dump/VTK columns, colour-by-field, force arrows, the inspector and the
 * integration's sum of accelerations are loops over it. A new force adds one
 * row of kind ACCELERATION: it is then allocated when its pass runs,
 * integrated, checked, dumped, coloured and drawn as arrows.
 *
 * A row: X(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about)
 *   ID       the enum suffix (SPH_FIELD_ID) and mask bit (SPH_BIT(ID))
 *   name     the member of sph_particles and the column name in files
 *   comps    1 (a scalar) or V (a vector: one array per axis, the scene's dimension)
 *   unit     SI unit in 3D
 *   unit2    SI unit in 2D (per metre of depth: a mass is kg/m, a pressure N/m)
 *   kind     STATE (carried from step to step), DERIVED (recomputed each step),
 *            ACCELERATION (summed by integration), WALL (a wall model's own data)
 *   made_by  the pass whose presence in the pipeline allocates the field; NONE: always there
 *            (pos_r besides needs position_sum = compensated: sph_field_allocated)
 *   check    what the watchdog checks besides finiteness: NONE, SPEED (|v| under the
 *            scene's bound), DENSITY (in (0, 100 rho0])
 *   colour   the name particles are coloured by (the window's and `render`'s
 *            --color), "" for none; vectors are coloured by their magnitude
 *   label    its row in the window's inspector ("" for none); accelerations are drawn as arrows
 *   about    what it means, for the inspector and `sphlab keys`-like listings */
#ifndef SPH_FIELDS_H
#define SPH_FIELDS_H

#include <stdbool.h>
#include <stdint.h>

#include "sph_pass.h"

#define SPH_FIELDS(X)                                                                                          \
    X(POS, pos, V, "m", "m", STATE, NONE, NONE, "", "x", "position")                                             \
    X(VEL, vel, V, "m/s", "m/s", STATE, NONE, SPEED, "speed", "v", "velocity")                                   \
    X(PRED, pred, V, "m", "m", DERIVED, NEIGHBOURS, NONE, "", "", "predicted position x + v dt")                 \
    X(RHO, rho, 1, "kg/m^3", "kg/m^2", DERIVED, DENSITY, DENSITY, "density", "rho", "density")                   \
    X(VOL, vol, 1, "m^3", "m^2", DERIVED, DENSITY, NONE, "", "", "volume m/rho")                                 \
    X(P, p, 1, "Pa", "N/m", DERIVED, PRESSURE, NONE, "pressure", "p", "pressure")                                \
    X(PRHO2, p_rho2, 1, "Pa m^6/kg^2", "N m^3/kg^2", DERIVED, PRESSURE, NONE, "", "", "p / rho^2")               \
    X(ACC_P, acc_p, V, "m/s^2", "m/s^2", ACCELERATION, PRESSURE_FORCE, NONE, "pressure-acc", "a pressure",       \
      "pressure acceleration")                                                                                   \
    X(ACC_V, acc_v, V, "m/s^2", "m/s^2", ACCELERATION, VISCOSITY, NONE, "viscosity-acc", "a viscosity",          \
      "viscous acceleration")                                                                                    \
    X(ACC_C, acc_c, V, "m/s^2", "m/s^2", ACCELERATION, COHESION, NONE, "cohesion-acc", "a cohesion",            \
      "cohesion acceleration (surface tension)")                                                                 \
    X(NORMAL, normal, V, "1", "1", DERIVED, NORMALS, NONE, "normal", "normal",                                   \
      "surface normal h sum_j m_j/rho_j grad_i W_ij (Akinci 2013 eq. 3, pointing into the fluid): ~0 inside, " \
      "of order 1 at a surface")                                                                                    \
    X(ACC_K, acc_k, V, "m/s^2", "m/s^2", ACCELERATION, CURVATURE, NONE, "curvature-acc", "a curvature",         \
      "curvature acceleration of surface_tension = akinci, -gamma sum_j K_ij (n_i - n_j)")                     \
    X(CURV, curv, 1, "1/m", "1/m", DERIVED, CSF, NONE, "curvature", "curvature",                              \
      "curvature of the surface (surface_tension = csf): the renormalised divergence of the outward unit "      \
      "normal, positive on a convex surface; 0 where the normal is too short to have a direction")          \
    X(ACC_S, acc_s, V, "m/s^2", "m/s^2", ACCELERATION, CSF, NONE, "csf-acc", "a csf",                            \
      "continuum surface force of surface_tension = csf per unit mass, sigma kappa s_i n / m_i")               \
    X(ACC_T, acc_t, V, "m/s^2", "m/s^2", ACCELERATION, SURFACE_STRESS, NONE, "stress-acc", "a stress",          \
      "surface tension of surface_tension = stress per unit mass, the divergence of the surface stress "          \
      "sigma (I - n n) delta_s")                                                                                 \
    X(ACC_X, acc_x, V, "m/s^2", "m/s^2", ACCELERATION, XSPH, NONE, "xsph-acc", "a xsph",                        \
      "XSPH velocity smoothing as an acceleration, (eps / dt) sum_j m_j / rho_ij (v_j - v_i) W_ij")            \
    X(ACC_I, acc_i, V, "m/s^2", "m/s^2", ACCELERATION, INTERACTION, NONE, "", "a mouse", "interaction acceleration") \
    X(MASS, mass, 1, "kg", "kg/m", STATE, NONE, NONE, "", "", "mass")                                           \
    X(FIXED, fixed, 1, "1", "1", STATE, WALL_STATE, NONE, "", "wall", "1 for a fixed wall particle, 0 for fluid") \
    X(VEL_VISC, vel_visc, V, "m/s", "m/s", WALL, WALL_STATE, NONE, "", "v viscous",                              \
      "velocity the viscous term sees: the fluid's own; a wall particle's mirrored (no-slip) or the fluid's "     \
      "(free-slip)")                                                                                             \
    X(RHO_C, rho_c, 1, "kg/m^3", "kg/m^2", STATE, DENSITY_RATE, DENSITY, "", "rho carried",                      \
      "density carried by the continuity equation (density_method = continuity): rho_c += dt drho")             \
    X(DRHO, drho, 1, "kg/(m^3 s)", "kg/(m^2 s)", DERIVED, DENSITY_RATE, NONE, "density-rate", "drho/dt",         \
      "rate of change of the density: continuity equation with density diffusion (delta-SPH)")            \
    X(GRAD_RHO, grad_rho, V, "kg/m^4", "kg/m^3", DERIVED, DENSITY_GRADIENT, NONE, "", "grad rho",             \
      "renormalised gradient of the carried density, L_i sum_j (rho_j - rho_i) grad W_ij V_j (delta_form = "    \
      "antuono)")                                                                                              \
    X(SHIFT, shift, V, "m", "m", DERIVED, SHIFTING, NONE, "", "shift",                                          \
      "displacement of the particle shifting (shifting = lind): -D grad C, 0 at the free surface")             \
    X(SURFACE, surface, 1, "1", "1", DERIVED, SHIFTING, NONE, "", "surface",                                  \
      "1 where the particle is at the free surface (divergence of position below dim - 0.5), else 0")   \
    X(DRIFT, drift, V, "m", "m", DERIVED, TRANSPORT, NONE, "", "drift",                                          \
      "the transport velocity's extra displacement in this step (shifting = tvf): dt (dt/2) a_b")            \
    X(OBSTACLE, obstacle, 1, "1", "1", STATE, WALL_STATE, NONE, "", "obstacle",                                  \
      "the obstacle a wall particle belongs to: 1, 2, ... in the scene's order; 0 for the domain box and fluid")  \
    X(SLIP, slip, 1, "1", "1", STATE, WALL_STATE, NONE, "", "free-slip",                                        \
      "1 for a free-slip wall particle, 0 for a no-slip one (and fluid)")   \
    X(P_PCI, p_pci, 1, "Pa", "N/m", DERIVED, PCISPH, NONE, "pcisph-pressure", "p pcisph",                         \
      "pressure PCISPH iterated to in this step")                                                     \
    X(X_PCI, x_pci, V, "m", "m", DERIVED, PCISPH, NONE, "", "",                                                  \
      "PCISPH's predicted position x + dt v + dt^2 a with this iteration's pressure")                           \
    X(RHO_PCI, rho_pci, 1, "kg/m^3", "kg/m^2", DERIVED, PCISPH, NONE, "pcisph-density", "rho pcisph",           \
      "PCISPH's predicted density at the predicted positions, this iteration")                                  \
    X(P_PCI_BEST, p_pci_best, 1, "Pa", "N/m", DERIVED, PCISPH, NONE, "", "",                                     \
      "PCISPH's pressure at this solve's least density error so far (a solve that starts to rise takes it back)") \
    X(P_PCI_PREV, p_pci_prev, 1, "Pa", "N/m", DERIVED, PCISPH, NONE, "", "",                                     \
      "PCISPH's pressure one iteration back, which the Chebyshev acceleration blends (solver_chebyshev > 0)")    \
    X(DELTA_PCI, delta_pci, 1, "m^2", "m^2", DERIVED, PCISPH, NONE, "", "delta pcisph",                         \
      "PCISPH's delta at dt = 1 s from this particle's neighbourhood (pcisph_local_delta = on)")               \
    X(ACC_PCI, acc_pci, V, "m/s^2", "m/s^2", ACCELERATION, PCISPH, NONE, "pcisph-acc", "a pcisph",               \
      "pressure acceleration of PCISPH")                                                                         \
    X(ALPHA, alpha, 1, "m^3/kg", "m^2/kg", DERIVED, DFSPH, NONE, "", "alpha",                                    \
      "DFSPH's factor rho_i / (|sum_j m_j grad W_ij|^2 + sum_j |m_j grad W_ij|^2), < 0: own push raises rho")     \
    X(ALPHA_V, alpha_v, 1, "m^3/kg", "m^2/kg", DERIVED, DFSPH, NONE, "", "alpha div",                            \
      "DFSPH's divergence factor rho_i / (|sum_j m_j grad W^p_ij|^2 + sum_j |m_j grad W^p_ij|^2), walls in the sum") \
    X(KAPPA, kappa, 1, "m^2/s^2", "m^2/s^2", STATE, DFSPH, NONE, "", "kappa",                                    \
      "DFSPH's constant-density stiffness kappa = p / rho of the last step (warm start)")                       \
    X(KAPPA_V, kappa_v, 1, "m^2/s^2", "m^2/s^2", STATE, DFSPH, NONE, "", "kappa div",                            \
      "DFSPH's divergence-free stiffness (times dt) of the last step (warm start)")                             \
    X(KAPPA_BEST, kappa_best, 1, "m^2/s^2", "m^2/s^2", DERIVED, DFSPH, NONE, "", "",                             \
      "DFSPH's kappa at this density solve's least error so far (a solve that starts to rise takes it back)")   \
    X(KAPPA_PREV, kappa_prev, 1, "m^2/s^2", "m^2/s^2", DERIVED, DFSPH, NONE, "", "",                             \
      "DFSPH's kappa one iteration back, which the Chebyshev acceleration blends (solver_chebyshev > 0)")        \
    X(RHO_DF, rho_df, 1, "kg/m^3", "kg/m^2", DERIVED, DFSPH, NONE, "dfsph-density", "rho dfsph",               \
      "DFSPH's predicted density (constant-density solve) or D rho/Dt times dt (divergence solve)")             \
    X(DV_DF, dv_df, V, "m/s", "m/s", DERIVED, DFSPH, NONE, "", "",                                               \
      "DFSPH's velocity change this step, dt (other accelerations + a dfsph): v* = v + dv")                     \
    X(ACC_DF, acc_df, V, "m/s^2", "m/s^2", ACCELERATION, DFSPH, NONE, "dfsph-acc", "a dfsph",                    \
      "pressure acceleration of DFSPH (divergence-free plus constant-density)")                                  \
    X(POS_R, pos_r, V, "m", "m", STATE, INTEGRATE, NONE, "", "",                                                 \
      "what the float position could not hold of the moves dt v (position_sum = compensated): added to the next")

typedef enum sph_field_id {
#define SPH_FIELD_ENUM(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about) SPH_FIELD_##ID,
    SPH_FIELDS(SPH_FIELD_ENUM)
#undef SPH_FIELD_ENUM
    SPH_FIELD_COUNT
} sph_field_id;

typedef enum sph_field_kind {
    SPH_KIND_STATE,
    SPH_KIND_DERIVED,
    SPH_KIND_ACCELERATION,
    SPH_KIND_WALL,
} sph_field_kind;

typedef enum sph_field_check {
    SPH_CHECK_NONE,  /* finite only */
    SPH_CHECK_SPEED, /* |value| under the scene's speed bound */
    SPH_CHECK_DENSITY, /* in (0, the scene's density bound] */
} sph_field_check;

/* What a pass reads or writes: one bit per field, then the search's own data
 * (above every field bit). The same bits say what a backend's host copy lacks
 * (sph_sim_sync). */
#define SPH_BIT(ID) ((sph_mask)1 << SPH_FIELD_##ID)
#define SPH_FIELD_BIT(f) ((sph_mask)1 << (f))
#define SPH_RES_ID ((sph_mask)1 << 56)      /* creation ids (the reorder pass permutes them) */
#define SPH_RES_ENTRIES ((sph_mask)1 << 57) /* the index's (key, hash, particle) entries */
#define SPH_RES_START ((sph_mask)1 << 58)   /* the start-offset table */
#define SPH_RES_LISTS ((sph_mask)1 << 59)   /* the neighbour lists (nbr_start, nbr) */
#define SPH_FIELD_MASK_ALL (((sph_mask)1 << SPH_FIELD_COUNT) - 1)
/* Every field of kind ACCELERATION: what integration sums. */
#define SPH_KIND_IS_ACC_STATE 0
#define SPH_KIND_IS_ACC_DERIVED 0
#define SPH_KIND_IS_ACC_ACCELERATION 1
#define SPH_KIND_IS_ACC_WALL 0
#define SPH_ACC_BIT_(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about) \
    | (SPH_KIND_IS_ACC_##kind ? SPH_BIT(ID) : 0)
#define SPH_MASK_ACCELERATIONS ((sph_mask)0 SPH_FIELDS(SPH_ACC_BIT_))
_Static_assert(SPH_FIELD_COUNT <= 56, "field bits would run into the resource bits");

/* One row of the registry. */
typedef struct sph_field_info {
    const char *id;     /* "RHO": the GL backend's binding B_RHO (the field's number) and the name in a
                           shader's "// uses:" line */
    const char *name;   /* as in the struct, in files and in messages */
    const char *unit;   /* SI, 3D */
    const char *unit2;  /* SI, 2D (per metre of depth) */
    const char *label;  /* the inspector's row, "" for none */
    const char *about;
    const char *colour; /* colour-by name, "" if particles are not coloured by it */
    bool vector;        /* one array per axis (the scene's dimension), else one array */
    sph_field_kind kind;
    sph_pass_id made_by; /* SPH_PASS_COUNT: always allocated */
    sph_field_check check;
} sph_field_info;

extern const sph_field_info sph_field_infos[SPH_FIELD_COUNT];

/* Whether a scene allocates field f: its pass runs (in_pipeline, by pass), and for pos_r the scene asks for
 * compensated positions, so the default costs no memory for it. sph_sim_create and sph_memory_estimate both
 * ask here. */
bool sph_field_allocated(int f, const sph_scene_def *def, const bool in_pipeline[SPH_PASS_COUNT]);
/* The field's unit in a scene of dimension dim. */
const char *sph_field_unit(int f, int dim);
/* -1 if no field has that name. */
int sph_field_find(const char *name);
/* The names of the fields and resources in `m`, space-separated in registry
 * order ("vel pos", "nbr_start nbr"), for the HUD and `sphlab check`. */
void sph_mask_names(sph_mask m, char *out, int n);

#endif
