/* The scene key table: every key of a scene file, its type, range, unit, default and meaning, as data.
 * The parser (sph_scene.c) and docs/scene-format.md (`sphlab keys`) both follow it. */
#include "sph_scene.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define NAMES(id, name) name,
const char *const sph_eos_names[SPH_EOS_COUNT] = {SPH_EOS_CHOICES(NAMES)};
const char *const sph_eos_rest_names[SPH_EOSREST_COUNT] = {SPH_EOS_REST_CHOICES(NAMES)};
const char *const sph_pressure_form_names[SPH_PFORM_COUNT] = {SPH_PFORM_CHOICES(NAMES)};
const char *const sph_viscosity_form_names[SPH_VFORM_COUNT] = {SPH_VFORM_CHOICES(NAMES)};
const char *const sph_search_names[SPH_SEARCH_COUNT] = {SPH_SEARCH_CHOICES(NAMES)};
const char *const sph_sort_names[SPH_SORT_COUNT] = {SPH_SORT_CHOICES(NAMES)};
const char *const sph_negative_pressure_names[SPH_NEGP_COUNT] = {SPH_NEGP_CHOICES(NAMES)};
const char *const sph_wall_model_names[SPH_WALL_COUNT] = {SPH_WALL_CHOICES(NAMES)};
const char *const sph_wall_slip_names[SPH_SLIP_COUNT] = {SPH_SLIP_CHOICES(NAMES)};
const char *const sph_wall_force_names[SPH_WFORCE_COUNT] = {SPH_WALL_FORCE_CHOICES(NAMES)};
const char *const sph_density_method_names[SPH_DMETHOD_COUNT] = {SPH_DMETHOD_CHOICES(NAMES)};
const char *const sph_delta_form_names[SPH_DFORM_COUNT] = {SPH_DFORM_CHOICES(NAMES)};
const char *const sph_shifting_names[SPH_SHIFT_COUNT] = {SPH_SHIFT_CHOICES(NAMES)};
const char *const sph_side_slip_names[SPH_SIDE_SLIP_COUNT] = {SPH_SIDE_SLIP_CHOICES(NAMES)};
const char *const sph_shape_names[SPH_SHAPE_COUNT] = {SPH_SHAPE_CHOICES(NAMES)};
const char *const sph_axis_names[3] = {"x", "y", "z"};
const char *const sph_velocity_field_names[SPH_VFIELD_COUNT] = {SPH_FIELD_CHOICES(NAMES)};
const char *const sph_initial_pressure_names[SPH_INITP_COUNT] = {SPH_INITP_CHOICES(NAMES)};
const char *const sph_accumulate_names[SPH_ACC_COUNT] = {SPH_ACC_CHOICES(NAMES)};
const char *const sph_position_sum_names[SPH_POSSUM_COUNT] = {SPH_POSSUM_CHOICES(NAMES)};
const char *const sph_onoff_names[SPH_ONOFF_COUNT] = {SPH_ONOFF_CHOICES(NAMES)};
const char *const sph_backend_names[SPH_BACKEND_COUNT] = {SPH_BACKEND_CHOICES(NAMES)};
const char *const sph_pressure_solver_names[SPH_PSOLVER_COUNT] = {SPH_PSOLVER_CHOICES(NAMES)};
const char *const sph_surface_tension_names[SPH_STENSION_COUNT] = {SPH_STENSION_CHOICES(NAMES)};
const char *const sph_solver_wall_pressure_names[SPH_SWALLP_COUNT] = {SPH_SWALLP_CHOICES(NAMES)};
#undef NAMES
#define EFFECT_NAME(id, name, about, needs) name,
const char *const sph_effect_names[SPH_EFFECT_COUNT] = {SPH_EFFECTS(EFFECT_NAME)};
#undef EFFECT_NAME
#define EFFECT_ABOUT(id, name, about, needs) about,
const char *const sph_effect_about[SPH_EFFECT_COUNT] = {SPH_EFFECTS(EFFECT_ABOUT)};
#undef EFFECT_ABOUT

/* ---- the key table ------------------------------------------------------ */

#define S(field) (int)offsetof(sph_scene_def, field)
#define B(field) (int)offsetof(sph_block_def, field)
#define CH(names) names, (int)(sizeof names / sizeof names[0])
#define BIG 1e6

const sph_key sph_scene_keys[] = {
    {"scene", "name", SPH_KEY_STRING, S(name), 0, 0, 0, 0, NULL, 0, "", "", "title shown in tables and windows"},
    {"scene", "dimension", SPH_KEY_INT, S(dim), 2, 3, 0, 0, NULL, 0, "", "2", "2 or 3"},
    {"scene", "effects", SPH_KEY_FLAGS, S(effects), 0, 0, 0, 0, CH(sph_effect_names), "",
     "gravity pressure viscosity walls",
     "the effects to simulate; passes needed only by others are left out"},
    {"scene", "steps", SPH_KEY_INT, S(steps), 1, 1e9, 0, 0, NULL, 0, "", "1000",
     "default run length in steps (--steps overrides)"},
    {"scene", "duration", SPH_KEY_FLOAT, S(duration), 0, BIG, 0, 0, NULL, 0, "s", "0",
     "default run length in simulated seconds; 0: use steps (--time overrides)"},
    {"scene", "jitter", SPH_KEY_FLOAT, S(jitter), 0, 0.5, 0, 0, NULL, 0, "spacing", "0",
     "random offset of each particle from its lattice node, as a fraction of the spacing"},
    {"scene", "seed", SPH_KEY_UINT, S(seed), 0, 4294967295.0, 0, 0, NULL, 0, "", "1", "random seed of the jitter"},

    {"domain", "min", SPH_KEY_POINT, S(domain_min), -BIG, BIG, 0, 0, NULL, 0, "m", "0 0 0", "lower corner of the box"},
    {"domain", "max", SPH_KEY_POINT, S(domain_max), -BIG, BIG, 0, 0, NULL, 0, "m", "1 1 1", "upper corner of the box"},
    {"domain", "wall_damping", SPH_KEY_FLOAT, S(wall_damping), 0, 1, 0, 0, NULL, 0, "", "0.5",
     "share of the normal speed a particle keeps when it bounces off a wall"},
    {"domain", "periodic", SPH_KEY_FLAGS, S(periodic), 0, 0, 0, 0, CH(sph_axis_names), "", "none",
     "axes that wrap around: a particle leaving at max comes back at min (no walls there); each needs a length of "
     "at least 3 h"},
    {"domain", "wall_model", SPH_KEY_CHOICE, S(wall_model), 0, 0, 0, 0, CH(sph_wall_model_names), "", "volume",
     "volume: the space behind each wall counts as the fluid's lattice continued at rest (one table per distance, "
     "the finest block's spacing) in the density sum and pushes back with the particle's pressure, so particles "
     "near a wall miss none of their support and a lattice's first row reads its interior's density; reflect: only the seed's damped "
     "reflection (particles near walls lack neighbours and sink into them); particles: layers of fixed wall "
     "particles outside the box, on the fluid's lattice, whose pressure is extrapolated from the fluid (Adami, Hu "
     "& Adams 2012; under pcisph and dfsph only with solver_wall_pressure = extrapolated)"},
    {"domain", "wall_force", SPH_KEY_CHOICE, S(wall_force), 0, 0, 0, 0, CH(sph_wall_force_names), "", "energy",
     "with wall_model = volume, how the hidden lattice pushes: energy: -(p_i / rho_i^2) grad(rho0 H), the "
     "gradient of the walls' density term (conserves energy; a lattice's overpressure pushes the first rows into "
     "the wall); ghost: the hidden lattice's nodes as ghost particles in the pressure pair term, their pressure "
     "p_i + rho_i g . (x_k - x_i) (Adami et al. 2012, eq. 27), so a block at rest stays at rest "
     "(docs/accuracy.md, section 6)"},
    {"domain", "wall_slip", SPH_KEY_CHOICE, S(wall_slip), 0, 0, 0, 0, CH(sph_wall_slip_names), "", "no",
     "with wall_model = particles: no: no-slip walls (the wall particles' velocity in the viscous term mirrors the "
     "fluid's); free: free-slip (they take the fluid's velocity, no shear at the wall)"},
#define SIDE_SLIP(side, k)                                                                                    \
    {"domain", "wall_slip_" side, SPH_KEY_CHOICE, S(wall_slip_side[k]), 0, 0, 0, 0, CH(sph_side_slip_names), "", \
     "same", "with wall_model = particles: the " side " side's wall particles: same (as wall_slip), no or free; "  \
     "a corner particle is free-slip only if every side it lies beyond is"}
    SIDE_SLIP("xmin", 0), SIDE_SLIP("xmax", 1), SIDE_SLIP("ymin", 2), SIDE_SLIP("ymax", 3), SIDE_SLIP("zmin", 4),
    SIDE_SLIP("zmax", 5),
#undef SIDE_SLIP
    {"domain", "wall_velocity", SPH_KEY_VEC, S(wall_velocity), -BIG, BIG, 0, 0, NULL, 0, "m/s", "0 0 0",
     "with wall_model = particles: velocity of the wall beyond the top side (y max), along the wall (its y "
     "component must be 0): its wall particles stay in place but the viscous term sees them move, so a no-slip "
     "top wall drags the fluid (Couette flow, a lid-driven cavity); the other walls stand still"},

    {"physics", "rest_density", SPH_KEY_FLOAT, S(rest_density), 1e-3, BIG, 0, 0, NULL, 0, "kg/m^dim", "1000",
     "rho0: density at which the pressure is zero; at least 0.001 (a rarefied gas): the pressure force divides by "
     "rho^2, which a float loses below about 1e-19"},
    {"physics", "eos", SPH_KEY_CHOICE, S(eos), 0, 0, 0, 0, CH(sph_eos_names), "", "linear",
     "equation of state: linear p = k (rho - rho0) as in the seeds, or tait p = (k rho0 / gamma) ((rho/rho0)^gamma - 1)"},
    {"physics", "eos_rest", SPH_KEY_CHOICE, S(eos_rest), 0, 0, 0, 0, CH(sph_eos_rest_names), "", "rest_density",
     "the density rho0 at which the equation of state gives p = 0. rest_density: [physics] rest_density. lattice: "
     "the density a particle of the scene's finest lattice sums to at rest with its whole support in the fluid, "
     "rest_density (1 + e), e the summation's own excess on a lattice (+1.46 % for poly6 at h = 2 spacing in 2D, "
     "+1.2 % for the 3D bench scene): the density pcisph and dfsph hold, so a block placed on the lattice starts at "
     "zero pressure instead of compressed by e (its free surfaces then burst outward at a speed growing with "
     "sqrt(k)). The walls' inverse equation of state, the hydrostatic and Taylor-Green initial pressures and the "
     "internal energy use the same reference; the particles' mass stays rest_density spacing^dim"},
    {"physics", "stiffness", SPH_KEY_FLOAT, S(stiffness), 0, 1e9, 1, 0, NULL, 0, "m^2/s^2", "1000",
     "k; the speed of sound is sqrt(k), keep it about 10x the fastest flow"},
    {"physics", "tait_gamma", SPH_KEY_FLOAT, S(tait_gamma), 1, 20, 0, 0, NULL, 0, "", "7", "exponent of the Tait equation"},
    {"physics", "negative_pressure", SPH_KEY_CHOICE, S(negative_pressure), 0, 0, 0, 0,
     CH(sph_negative_pressure_names), "", "clamp",
     "keep: below rho0 particles attract (the seeds); clamp: pressure >= 0, no tensile clumping"},
    {"physics", "pressure_form", SPH_KEY_CHOICE, S(pressure_form), 0, 0, 0, 0, CH(sph_pressure_form_names), "",
     "symmetric",
     "symmetric: -m_j (p_i/rho_i^2 + p_j/rho_j^2) grad W, conserves momentum; shared: the seed's (p_i+p_j)/2 form"},
    {"physics", "viscosity", SPH_KEY_FLOAT, S(viscosity), 0, 1e3, 0, 0, NULL, 0, "m^2/s", "0.001",
     "kinematic viscosity nu"},
    {"physics", "viscosity_form", SPH_KEY_CHOICE, S(viscosity_form), 0, 0, 0, 0, CH(sph_viscosity_form_names), "",
     "laplacian",
     "laplacian: Mueller's nu m_j (v_j - v_i)/rho_j lap W; smoothing: the seed's kernel-weighted velocity average; "
     "morris: nu m_j (rho_i + rho_j)/(rho_i rho_j) (x_ij . grad W)/(r^2 + 1e-4 h^2) (v_i - v_j), a Laplacian from "
     "the kernel's gradient (needs a kernel whose slope vanishes at r = 0: [kernels] viscosity = cubic, wendland or "
     "poly6); artificial: Monaghan's term of [physics] alpha alone (nu unused); morris-artificial: both summed, the "
     "physical nu in Morris's term (which sees the wall particles' no-slip velocity, so a floor has friction) and "
     "alpha's term for the shocks"},
    {"physics", "cohesion", SPH_KEY_FLOAT, S(cohesion), 0, 1e6, 0, 0, NULL, 0, "m^4/(kg s^2)", "1",
     "gamma of the cohesion effect (Akinci 2013): a_i = -gamma sum_j 2 rho0/(rho_i + rho_j) m_j C(r) x_ij/r"},
    {"physics", "accumulate", SPH_KEY_CHOICE, S(accumulate), 0, 0, 0, 0, CH(sph_accumulate_names), "", "float",
     "precision of the density and force sums: float, or double (slower; shows what round-off costs)"},
    {"physics", "gravity", SPH_KEY_VEC, S(gravity), -1e4, 1e4, 0, 0, NULL, 0, "m/s^2", "0 -9.81 0", "g"},
    {"physics", "alpha", SPH_KEY_FLOAT, S(alpha), 0, 10, 0, 0, NULL, 0, "", "0.1",
     "alpha of viscosity_form = artificial or morris-artificial (Monaghan 1992): Pi_ij = -alpha c (h/2) (v_ij . x_ij) / (rho_avg (r^2 + "
     "0.01 (h/2)^2)) for approaching pairs, c = sqrt(stiffness); typically 0.01 to 0.1"},
    {"physics", "gravity_ramp", SPH_KEY_FLOAT, S(gravity_ramp), 0, BIG, 0, 0, NULL, 0, "s", "0",
     "gravity grows as g (1 - cos(pi t / T)) / 2 over the first T seconds (as in Adami et al. 2012's hydrostatic "
     "tank), so a column at rest is loaded without a pressure shock; 0: full g from the start"},
    {"physics", "damping_time", SPH_KEY_FLOAT, S(damping_time), 0, BIG, 0, 0, NULL, 0, "s", "0",
     "over the first T seconds every step multiplies the velocities by (1 - cos(pi t / T)) / 2: all motion is "
     "removed at t = 0 and none at T, so an initial state settles; 0: no damping"},
    {"physics", "density_method", SPH_KEY_CHOICE, S(density_method), 0, 0, 0, 0, CH(sph_density_method_names), "",
     "summation",
     "summation: rho = sum_j m_j W_ij every step; continuity: rho starts from the lattice's m / spacing^dim "
     "(summed after a reconfiguration that switches it on), then carried by "
     "drho/dt = sum_j m_j v_ij . grad W_ij plus the density diffusion term of delta (Molteni & Colagrossi 2009)"},
    {"physics", "delta", SPH_KEY_FLOAT, S(delta), 0, 1, 0, 0, NULL, 0, "", "0.1",
     "delta of density_method = continuity's diffusion term delta (h/2) c sum_j psi_ij . grad W_ij V_j, "
     "psi_ij = 2 (rho_j - rho_i) x_ji / |x_ji|^2, c = sqrt(stiffness); 0: none; typically 0.1"},
    {"physics", "delta_form", SPH_KEY_CHOICE, S(delta_form), 0, 0, 0, 0, CH(sph_delta_form_names), "", "molteni",
     "the density diffusion term of delta: molteni: psi_ij as above (Molteni & Colagrossi 2009); antuono: psi_ij "
     "minus the renormalised density gradients <grad rho>^L_i + <grad rho>^L_j (Antuono et al. 2010, Comput. Phys. "
     "Commun. 181:532), which vanishes for a hydrostatic (linear) density, so a column at rest does not drift; "
     "fourtakas: rho_j - rho_i minus the hydrostatic density difference of the pair, the equation of state's density "
     "at p = rho0 g . (x_j - x_i) minus rho0 (Fourtakas et al. 2019, Comput. Fluids 190:346), zero for a column at "
     "rest with no gradient to estimate, walls or free surface alike"},
    {"physics", "shifting", SPH_KEY_CHOICE, S(shifting), 0, 0, 0, 0, CH(sph_shifting_names), "", "none",
     "particle shifting after each step: none; lind: every particle moves by -D grad C_i, C the particle "
     "concentration (Lind et al. 2012, J. Comput. Phys. 231:1499), D = shifting_coefficient h |v_i| dt; particles "
     "at the free surface are not shifted; tvf: every particle also drifts by dt (dt/2) a_b, a_b the acceleration of a "
     "background pressure p_b = rest_density * stiffness (the transport velocity of Adami, Hu & Adams 2013, J. Comput. "
     "Phys. 241:292, without its extra stress term), for flows that fill their domain (no free surface)"},
    {"physics", "shifting_coefficient", SPH_KEY_FLOAT, S(shifting_coefficient), 0, 100, 0, 0, NULL, 0, "", "2",
     "A of shifting = lind's D = A h |v_i| dt (2 in Skillen et al. 2013, who scaled Lind's D with the step)"},
    {"physics", "pressure_solver", SPH_KEY_CHOICE, S(pressure_solver), 0, 0, 0, 0, CH(sph_pressure_solver_names),
     "", "eos",
     "eos: pressure from the equation of state (weakly compressible, dt bound by the speed of sound); pcisph: "
     "predictive-corrective iterations (Solenthaler & Pajarola 2009); dfsph: divergence-free and constant-density "
     "solves (Bender & Koschier 2015/2017); both iterate until solver_tolerance, and dt follows the flow speed "
     "(walls: volume, reflect or particles, obstacles too; wall particles push back with the fluid particle's "
     "pressure alone, or with their own under solver_wall_pressure = extrapolated)"},
    {"physics", "solver_tolerance", SPH_KEY_FLOAT, S(solver_tolerance), 0, 1, 1, 0, NULL, 0, "", "0.001",
     "pcisph, dfsph: the largest relative density error (rho - rho_rest) / rho_rest a step may end with"},
    {"physics", "solver_max_iterations", SPH_KEY_INT, S(solver_max_iterations), 2, 10000, 0, 0, NULL, 0, "", "100",
     "pcisph, dfsph: iterations a solve takes at most; a step that reaches it is counted (HUD, --stats, run's "
     "summary). An iteration measures the error and, unless it is within the tolerance or the last, corrects the "
     "pressure: N allows N - 1 corrections (so at least 2: 1 would apply no pressure)"},
    {"physics", "divergence_tolerance", SPH_KEY_FLOAT, S(divergence_tolerance), 0, 1, 1, 0, NULL, 0, "", "0.001",
     "dfsph: the mean over the particles of max(dt D rho/Dt, 0) / rho_rest (the density change the flow makes "
     "in one step, counted where rho >= rho_rest; Bender & Koschier's average) the divergence-free solve may "
     "leave"},
    {"physics", "solver_warm_start", SPH_KEY_CHOICE, S(solver_warm_start), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "pcisph, dfsph: on: each solve starts from the pressure the last step ended with (PCISPH's p; DFSPH's kappa "
     "and kappa_v times (dt_last / dt)^2, Bender & Koschier 2017, Algorithm 3), not from 0: fewer iterations "
     "(docs/accuracy.md, section 8); on the GL backend too"},
    {"physics", "pcisph_local_delta", SPH_KEY_CHOICE, S(pcisph_local_delta), 0, 0, 0, 0, CH(sph_onoff_names), "",
     "off",
     "pcisph: on: each particle's delta from its own neighbourhood at the step's start (walls included), as "
     "DFSPH's alpha and IISPH's a_ii are, instead of the full lattice's (Solenthaler & Pajarola 2009's prototype "
     "particle): a corner or wall particle with fewer neighbours is corrected at its own rate; on the GL "
     "backend too"},
    {"physics", "solver_chebyshev", SPH_KEY_FLOAT, S(solver_chebyshev), 0, 1, 0, 1, NULL, 0, "", "0",
     "pcisph, dfsph: rho, the spectral radius the density solve's Chebyshev semi-iterative acceleration assumes "
     "(Wang 2015, ACM Trans. Graph. 34(6):246): from a solve's 10th correction on (the first 9 plain) each is "
     "blended with the iterate before, q_next = w (q + dq) + (1 - w) q_last (q: PCISPH's p, DFSPH's kappa), "
     "w_(k+1) = 4 / (4 - rho^2 w_k); a rise under it goes on plain from the best iterate. Fewer iterations on deep "
     "columns (docs/accuracy.md, section 8: 0.9 takes lesson 11's dam break from 60.5 to 30.6 per step; larger "
     "rho fewer still but moves the answer more within the tolerance); 0: plain (relaxed) Jacobi steps; on the GL "
     "backend too"},
    {"physics", "solver_wall_pressure", SPH_KEY_CHOICE, S(solver_wall_pressure), 0, 0, 0, 0,
     CH(sph_solver_wall_pressure_names), "", "none",
     "pcisph, dfsph with wall particles: none (the default): the wall particles hold no pressure and push back "
     "with the fluid particle's own (the row at a wall then reads twice its pressure); extrapolated: after each iteration each "
     "wall particle takes the pressure of its fluid neighbours with the hydrostatic term (Adami, Hu & Adams 2012, "
     "eq. 27), so the pair term is symmetric at the wall and the row there reads its own pressure; on the GL "
     "backend too"},
    {"physics", "surface_tension", SPH_KEY_CHOICE, S(surface_tension), 0, 0, 0, 0, CH(sph_surface_tension_names), "",
     "none",
     "none; akinci: Akinci, Akinci & Teschner 2013 (ACM TOG 32(6)), the cohesion term (eq. 1-2, the cohesion pass) "
     "plus the curvature term a_i = -gamma sum_j K_ij (n_i - n_j) (eq. 4-5) with the normals n_i = h sum_j m_j/rho_j "
     "grad W (eq. 3, pointing into the fluid); gamma = surface_tension_coefficient; not with the effect cohesion; "
     "csf: a continuum surface force (Brackbill, Kothe & Zemach 1992; Morris 2000) a_i = sigma kappa_i s_i n_i / "
     "m_i of the stated sigma, kappa the renormalised divergence of the unit normals (Shepard-averaged), s_i the "
     "particle's share of the surface (a partition of unity along it); "
     "stress: the divergence of the surface stress sigma (I - n n) delta_s (Lafaurie et al. 1994, J. Comput. Phys. "
     "113:134; in SPH as Hu & Adams 2006, J. Comput. Phys. 213:844), delta_s = s_i / (V_i c_i) (csf's share "
     "s_i over the colour c_i), pair terms equal and opposite (momentum kept to rounding; csf's are not: a drop "
     "left alone grows an n = 2 oscillation), with Monaghan 2000's artificial stress (eps 0.3, n 4) against the "
     "tensile instability; not on the GL backend"},
    {"physics", "surface_tension_coefficient", SPH_KEY_FLOAT, S(surface_tension_coefficient), 0, 1e6, 0, 0, NULL, 0,
     "m^4/(kg s^2)", "1",
     "gamma of surface_tension = akinci (both terms; the paper's gamma, not a physical sigma: docs/accuracy.md "
     "measures sigma from a drop's Laplace pressure)"},
    {"physics", "xsph", SPH_KEY_FLOAT, S(xsph), 0, 1, 0, 0, NULL, 0, "", "0",
     "epsilon of XSPH velocity smoothing (Monaghan 1989, J. Comput. Phys. 82:1): a_i = (epsilon / dt) sum_j m_j / "
     "((rho_i + rho_j)/2) (v_j - v_i) W_ij, so a step moves v_i towards its neighbours' average; 0: none"},
    {"physics", "sigma", SPH_KEY_FLOAT, S(sigma), 0, 1e6, 0, 0, NULL, 0, "N/m", "0.0728",
     "surface tension coefficient of surface_tension = csf or stress (in 2D per metre of depth: N); water at "
     "20 C: 0.0728"},

    {"kernels", "h", SPH_KEY_FLOAT, S(h), 1e-4, BIG, 0, 0, NULL, 0, "m", "0.04",
     "support radius, also the cell size of the neighbour search; about 2 spacings; at least 0.1 mm: below it the "
     "kernels' factors (315 / (64 pi h^9) for poly6 in 3D) overflow a float"},
    {"kernels", "density", SPH_KEY_KERNEL, S(kernel_density), 0, 0, 0, 0, CH(sph_kernel_names), "", "poly6",
     "kernel of the density sum"},
    {"kernels", "pressure", SPH_KEY_KERNEL, S(kernel_pressure), 0, 0, 0, 0, CH(sph_kernel_names), "", "spiky",
     "kernel whose gradient drives the pressure force"},
    {"kernels", "viscosity", SPH_KEY_KERNEL, S(kernel_viscosity), 0, 0, 0, 0, CH(sph_kernel_names), "", "viscosity",
     "kernel of the viscous force (its Laplacian, or its value for the smoothing form)"},

    {"time", "dt", SPH_KEY_FLOAT, S(dt), 0, 1, 1, 0, NULL, 0, "s", "0.0005",
     "time step with cfl = 0; upper bound of the adaptive step otherwise"},
    {"time", "cfl", SPH_KEY_FLOAT, S(cfl), 0, 1, 0, 0, NULL, 0, "", "0.4",
     "Courant factor; > 0 chooses dt each step from h, the speed of sound, speeds, forces and viscosity"},
    {"time", "dt_min", SPH_KEY_FLOAT, S(dt_min), 0, 1, 1, 0, NULL, 0, "s", "1e-7",
     "the adaptive step never goes below this; at most `dt` with `cfl` > 0"},
    {"time", "position_sum", SPH_KEY_CHOICE, S(position_sum), 0, 0, 0, 0, CH(sph_position_sum_names), "", "float",
     "how x += dt v is summed: float: rounded to the position's float each step, so a move under half a float "
     "spacing of x (1.5e-8 m near 0.15 m) is lost; compensated: Kahan's compensated summation (Kahan 1965, Comm. "
     "ACM 8:40; Higham 2002, Accuracy and Stability of Numerical Algorithms, sec. 4.3), each particle keeps the "
     "rounding remainder per axis (field pos_r, one more float per axis and particle) and adds it to the next "
     "step's move and to the predicted positions; for a fluid at rest whose particles creep 1e-9 m a step "
     "(docs/accuracy.md, \"hydrostatic\")"},

    {"search", "method", SPH_KEY_CHOICE, S(search), 0, 0, 0, 0, CH(sph_search_names), "", "hash",
     "hash: the seed's spatial hash; grid: a dense grid over the domain; brute: all pairs, O(N^2)"},
    {"search", "sort", SPH_KEY_CHOICE, S(sort), 0, 0, 0, 0, CH(sph_sort_names), "", "counting",
     "how hash entries are sorted by key: bitonic (the seed), counting, qsort (reference); none: no sort, each key "
     "chains its particles in a linked list (the unsorted hash)"},
    {"search", "table_size", SPH_KEY_UINT, S(table_size), 0, 2147483648.0, 0, 0, NULL, 0, "", "0",
     "number of hash keys; 0: the particle count, as in the seed"},

    {"interaction", "radius", SPH_KEY_FLOAT, S(interaction_radius), 0, BIG, 1, 0, NULL, 0, "m", "0.2",
     "reach of the push/pull around the mouse point"},
    {"interaction", "strength", SPH_KEY_FLOAT, S(interaction_strength), -1e6, 1e6, 0, 0, NULL, 0, "m/s^2", "40",
     "acceleration at the point, fading to 0 at the radius; > 0 pulls, < 0 pushes"},

    {"search", "reorder", SPH_KEY_CHOICE, S(reorder), 0, 0, 0, 0, CH(sph_onoff_names), "", "on",
     "on: after the sort, store the particle data in cell order, so neighbours sit close in memory and the search "
     "scans contiguous runs; off: keep the creation order (the seed)"},

    {"search", "vector", SPH_KEY_CHOICE, S(vector), 0, 0, 0, 0, CH(sph_onoff_names), "", "on",
     "on: inner loops written with the CPU's vector instructions (AVX-512, 16 floats at a time) use them, where the "
     "build has them (AVX2 with vector_avx2 = on); off: plain scalar loops"},
    {"search", "vector_avx2", SPH_KEY_CHOICE, S(vector_avx2), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with vector = on, the neighbour search's scan and the density, pressure_force and viscosity passes (and "
     "their fused walk) use AVX2 loops, 8 floats at a time, instead of AVX-512's 16: they run on CPUs without "
     "AVX-512 (where vector = on alone leaves the scalar loops); the same lists, and results within round-off "
     "(the pair sums in another order); off: AVX-512 where the build has it, else scalar"},
    {"search", "cell_batch", SPH_KEY_CHOICE, S(cell_batch), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with vector_avx2 = on, after a reorder and with no periodic axis, the neighbour search tests the "
     "particles of one cell together: each 8 candidates of a stencil run are loaded once for all of them instead "
     "of once per particle, and the rows are packed to 16-bit offsets 8 at a time; the same lists, entry for "
     "entry, so the same results to the bit. Elsewhere (periodic, no reorder, no AVX2) the search runs as with off"},
    {"search", "wide_batch", SPH_KEY_CHOICE, S(wide_batch), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with cell_batch = on, on a CPU with AVX-512, the search tests a cell's particles against 16 candidates "
     "at a time instead of 8 (the survivors compressed in a register); the same sums and tests, so the same lists "
     "entry for entry and the same results to the bit. Elsewhere it runs as with off"},
    {"search", "lists_in_place", SPH_KEY_CHOICE, S(lists_in_place), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: the first thread writes its particles' neighbour lists straight into the joined array the other passes "
     "read, instead of into a buffer of its own that is then copied there (the same lists, one copy less of the "
     "first thread's share in memory and in time); off: every thread builds in its own buffer"},
    {"search", "lists_resident", SPH_KEY_CHOICE, S(lists_resident), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with lists_in_place = on and more than one thread, the pages of the other threads' buffers and of the "
     "joined lists are kept from one build to the next, instead of handed back to the system as they are copied: "
     "no page faults at the next build, for the other threads' share of the lists held twice (about half the "
     "lists more memory with two threads); the same lists, so the same results to the bit. Off: handed back, so "
     "that a step's peak holds the lists once"},
    {"search", "compact_lists", SPH_KEY_CHOICE, S(compact_lists), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: the neighbour lists hold each neighbour j of particle i as the 16-bit offset j - i (in cell order the "
     "neighbours lie near i), half the memory of 32-bit indices; a row with a neighbour more than 32,767 places "
     "away is stored wide (32-bit indices behind a marker); the same neighbours and results; off: 32-bit indices. "
     "With density, pressure_force and viscosity only"},
    {"search", "skin", SPH_KEY_FLOAT, S(skin), 0, 1, 0, 0, NULL, 0, "h", "0",
     "Verlet lists: > 0 builds the neighbour lists out to h (1 + skin) and keeps them (no hash, sort, reorder or "
     "search) over the following steps, until some particle has moved skin h / 2 since the build; the passes "
     "that walk them count only pairs within h, so the results are those of lists rebuilt every step. In units "
     "of h (0.1: a tenth of h); 0: the lists are built every step"},

    {"compute", "backend", SPH_KEY_CHOICE, S(backend), 0, 0, 0, 0, CH(sph_backend_names), "", "cpu",
     "where the passes run: cpu (C with OpenMP), or gl (GLSL compute shaders, OpenGL 4.3 through EGL: the GPU, or "
     "Mesa's llvmpipe without one); sphlab run --backend overrides it"},
    {"compute", "fuse_forces", SPH_KEY_CHOICE, S(fuse_forces), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: the pressure force and viscosity passes share one walk of each particle's neighbours (each neighbour's "
     "data gathered once for both), where the vector loops run both (spiky pressure kernel, laplacian viscosity "
     "form); otherwise, and off, the two passes walk the lists each"},
    {"compute", "packed_records", SPH_KEY_CHOICE, S(packed_records), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with vector_avx2 = on, the density and pressure_force passes (and the fused walk) first copy each "
     "particle's fields into one record (x, y, z, m: 16 bytes for density; x, y, z, volume, velocity, p/rho^2 or p: "
     "32 bytes for the forces) and read 8 neighbours as 8 loads and a transpose instead of one gather per field; "
     "the same operations per pair, so the same results to the bit; 32 bytes per particle more. Off: gathers"},
    {"compute", "uniform_mass", SPH_KEY_CHOICE, S(uniform_mass), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with packed_records = on and the symmetric pressure form, when every particle has the same mass (checked "
     "each step as the records are written) the force walk takes it as a constant instead of gathering each "
     "neighbour's mass; the same products, so the same results to the bit; unequal masses are gathered as with "
     "off. Off: gathered"},
    {"compute", "wide_density", SPH_KEY_CHOICE, S(wide_density), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: with packed_records = on, on a CPU with AVX-512, the density pass reads 16 neighbours at a time from its "
     "records (16 loads and a transpose in 512-bit registers) instead of 8: the same operations per pair, the lanes "
     "summed in another order, so results within round-off of off. The force walk stays 8 wide (16 wide it was "
     "slower, docs/performance.md). A wide row (32-bit indices) and CPUs without AVX-512 go 8 at a time as with off"},

    {"fluid", "min", SPH_KEY_POINT, B(min), -BIG, BIG, 0, 0, NULL, 0, "m", "0 0 0", "lower corner of the block"},
    {"fluid", "max", SPH_KEY_POINT, B(max), -BIG, BIG, 0, 0, NULL, 0, "m", "0 0 0", "upper corner of the block"},
    {"fluid", "spacing", SPH_KEY_FLOAT, B(spacing), 0, BIG, 1, 0, NULL, 0, "m", "0.02",
     "lattice spacing; particles sit at the centres of the lattice cells"},
    {"fluid", "velocity", SPH_KEY_VEC, B(velocity), -BIG, BIG, 0, 0, NULL, 0, "m/s", "0 0 0",
     "initial velocity; with field = taylor-green, its x component is the vortex's amplitude U"},
    {"fluid", "field", SPH_KEY_CHOICE, B(field), 0, 0, 0, 0, CH(sph_velocity_field_names), "", "uniform",
     "initial velocity field: uniform, or the Taylor-Green vortex u = U sin(kx) cos(ky), v = -U cos(kx) sin(ky), "
     "k = 2 pi / L with L the domain's x length (it decays as exp(-2 nu k^2 t))"},
    {"fluid", "field_pressure", SPH_KEY_CHOICE, B(field_pressure), 0, 0, 0, 0, CH(sph_onoff_names), "", "off",
     "on: the block starts with the pressure of its field, p = -rho0 U^2 (cos 2kx + cos 2ky) / 4 for taylor-green "
     "(the exact solution's), as the density the equation of state gives for it, carried by the masses "
     "m = rho(p) spacing^dim; off: every particle at rest_density (p = 0 at t = 0)"},
    {"fluid", "initial_pressure", SPH_KEY_CHOICE, B(initial_pressure), 0, 0, 0, 0, CH(sph_initial_pressure_names), "",
     "none",
     "none: the block starts at rest density, without pressure; hydrostatic: at the pressure rho0 |g| d of its "
     "depth d below the block's top, each particle's mass rho(p) spacing^dim with rho(p) the equation of state "
     "solved for the density (Colagrossi & Landrini 2003; Adami et al. 2012), so the summed or carried density "
     "starts there; needs gravity, and no gravity_ramp"},

#define O(field) (int)offsetof(sph_obstacle_def, field)
    {"obstacle", "shape", SPH_KEY_CHOICE, O(shape), 0, 0, 0, 0, CH(sph_shape_names), "", "box",
     "box (min, max) or circle (centre, radius; a sphere in 3D): a solid of wall particles, which needs [domain] "
     "wall_model = particles"},
    {"obstacle", "min", SPH_KEY_POINT, O(min), -BIG, BIG, 0, 0, NULL, 0, "m", "0 0 0", "box: lower corner"},
    {"obstacle", "max", SPH_KEY_POINT, O(max), -BIG, BIG, 0, 0, NULL, 0, "m", "0 0 0", "box: upper corner"},
    {"obstacle", "centre", SPH_KEY_POINT, O(centre), -BIG, BIG, 0, 0, NULL, 0, "m", "0 0 0", "circle: centre"},
    {"obstacle", "radius", SPH_KEY_FLOAT, O(radius), 0, BIG, 0, 0, NULL, 0, "m", "0",
     "circle: radius, at least one spacing"},
    {"obstacle", "slip", SPH_KEY_CHOICE, O(slip), 0, 0, 0, 0, CH(sph_wall_slip_names), "", "no",
     "no: no-slip surface (its particles' velocity in the viscous term mirrors the fluid's); free: free-slip"},
#undef O
};
const int sph_scene_key_count = (int)(sizeof sph_scene_keys / sizeof sph_scene_keys[0]);
_Static_assert(sizeof sph_scene_keys / sizeof sph_scene_keys[0] <= SPH_MAX_KEYS, "raise SPH_MAX_KEYS (sph_scene_def.origin)");

void sph_scene_key_sections(const char *name, const char *value, char *out, size_t n)
{
    /* "physics.viscosity=V", then ", " or " or " between them; each section once */
    const char *hits[8];
    int k = 0;
    for (int i = 0; i < sph_scene_key_count && k < 8; i++) {
        if (strcmp(sph_scene_keys[i].name, name) != 0) continue;
        bool seen = false;
        for (int j = 0; j < k; j++) seen = seen || strcmp(hits[j], sph_scene_keys[i].section) == 0;
        if (!seen) hits[k++] = sph_scene_keys[i].section;
    }
    size_t len = 0;
    if (n) out[0] = '\0';
    for (int j = 0; j < k && len < n; j++) {
        const char *sep = j == 0 ? "" : j == k - 1 ? " or " : ", ";
        int w = snprintf(out + len, n - len, "%s%s.%s%s%s", sep, hits[j], name, value ? "=" : "", value ? value : "");
        if (w < 0) break;
        len += (size_t)w;
    }
}
