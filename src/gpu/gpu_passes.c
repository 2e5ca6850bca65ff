/* The GL backend's table of passes: one row per pass of the time step (its
 * shader, its dispatches if more than one, the helpers it needs), and the
 * dispatches of the passes that are more than one shader run once. A pass
 * added to SPH_PASSES runs on GL with a shader and a row here; without a row
 * the backend refuses a scene that needs it, by name. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_internal.h"
#include "gpu_shaders.h"
#include "solver.h"
#include "sph_start.h"

const char *const gpu_common_source = shader_gpu_common_glsl;
const char *const gpu_walk_source = shader_gpu_walk_glsl;
const char *const gpu_force_terms_source = shader_gpu_force_terms_glsl;

const char *const gpu_helper_names[H_TOTAL] = {
#define GPU_H_NAME(name) #name,
    GPU_HELPERS(GPU_H_NAME)
#undef GPU_H_NAME
};
const char *const gpu_helper_sources[H_TOTAL] = {
#define GPU_H_SRC(name) shader_gpu_##name##_comp,
    GPU_HELPERS(GPU_H_SRC)
#undef GPU_H_SRC
};

/* ---- helpers: fill, prefix sum, sorts -------------------------------------- */

static void fill(gpu *g, GLuint b, uint32_t count, uint32_t value)
{
    gpu_use(g, PROG_H(fill));
    gpu_bind(g, B_SCAN, b);
    gpu_set_u(g, PROG_H(fill), U_count, count);
    gpu_set_u(g, PROG_H(fill), U_value, value);
    gpu_dispatch(g, count);
}

/* Inclusive prefix sum of count values of b, in place. */
static void scan(gpu *g, GLuint b, uint32_t count, int level)
{
    gpu_use(g, PROG_H(scan_block));
    gpu_bind(g, B_SCAN, b);
    gpu_bind(g, B_SUMS, g->levels[level]);
    gpu_set_u(g, PROG_H(scan_block), U_count, count);
    gpu_dispatch(g, count);
    uint32_t groups = (count + WG - 1) / WG;
    if (groups <= 1) return;
    scan(g, g->levels[level], groups, level + 1);
    gpu_use(g, PROG_H(scan_add));
    gpu_bind(g, B_SCAN, b);
    gpu_bind(g, B_SUMS, g->levels[level]);
    gpu_set_u(g, PROG_H(scan_add), U_count, count);
    gpu_dispatch(g, count);
}

/* The seed's bitonic network over the next power of two P. Steps whose
 * stride fits a work group (w <= WG) run in shared memory, all of a block's
 * in one dispatch (gpu_bitonic_local.comp): the stages w0 <= WG whole, and
 * the short tail of every longer stage; only the long steps (w > WG) are one
 * dispatch each (gpu_bitonic.comp). log2(P / 2WG) (log2(P / 2WG) + 1) / 2 +
 * log2(P / 2WG) + 1 dispatches instead of log2(P) (log2(P) + 1) / 2. */
static void sort_bitonic(gpu *g)
{
    uint32_t P = 1;
    while (P < g->n) P <<= 1;
    const uint32_t pairs = P / 2 > WG ? P / 2 : WG; /* a block of 2 WG, padded, at the least */
    gpu_use(g, PROG_H(bitonic_local));
    gpu_set_u(g, PROG_H(bitonic_local), U_w, 0);
    gpu_dispatch(g, pairs);
    for (uint32_t w0 = 2 * WG; w0 < P; w0 <<= 1) {
        gpu_use(g, PROG_H(bitonic));
        gpu_set_u(g, PROG_H(bitonic), U_count, P / 2);
        for (uint32_t w = w0; w > WG; w >>= 1) {
            gpu_set_u(g, PROG_H(bitonic), U_w, w);
            gpu_set_u(g, PROG_H(bitonic), U_flip, w == w0);
            gpu_dispatch(g, P / 2);
        }
        gpu_use(g, PROG_H(bitonic_local));
        gpu_set_u(g, PROG_H(bitonic_local), U_w, w0);
        gpu_dispatch(g, P / 2);
    }
}

/* Counting sort with a prefix sum: histogram of keys, inclusive scan (each
 * key's first slot), atomic scatter, then each run put in index order. */
static void sort_counting(gpu *g)
{
    fill(g, g->buf[B_COUNT], g->table + 1, 0);
    gpu_use(g, PROG_H(histogram));
    gpu_dispatch(g, g->n);
    scan(g, g->buf[B_COUNT], g->table + 1, 0);
    gpu_use(g, PROG_H(scatter));
    gpu_dispatch(g, g->n);
    gpu_use(g, PROG_H(rank));
    gpu_dispatch(g, g->n);
}

/* ---- the passes' dispatches ------------------------------------------------ */

static void run_external(gpu *g, sph_sim *sim)
{
    gpu_use(g, SPH_PASS_EXTERNAL);
    gpu_set_f(g, SPH_PASS_EXTERNAL, U_dt, sim->dt);
    gpu_set_f(g, SPH_PASS_EXTERNAL, U_gscale, sph_start_gravity_scale(sim)); /* the CPU pass's factors */
    gpu_set_f(g, SPH_PASS_EXTERNAL, U_damp, sph_start_damping(sim));
    gpu_dispatch(g, g->n);
}

static void run_hash(gpu *g, sph_sim *sim)
{
    (void)sim;
    g->reordered = false;
    gpu_use(g, SPH_PASS_HASH);
    gpu_dispatch(g, g->n);
}

static void run_sort(gpu *g, sph_sim *sim)
{
    if (sim->def.sort == SPH_SORT_BITONIC)
        sort_bitonic(g);
    else
        sort_counting(g);
}

static unsigned sort_helpers(const sph_scene_def *def)
{
    if (def->sort == SPH_SORT_BITONIC) return HELPER_BIT(bitonic) | HELPER_BIT(bitonic_local);
    return HELPER_BIT(fill) | HELPER_BIT(histogram) | HELPER_BIT(scan_block) | HELPER_BIT(scan_add) |
           HELPER_BIT(scatter) | HELPER_BIT(rank);
}

/* Gathers the ids and every field the CPU's reorder pass moves into sorted
 * order; each gathered copy becomes the field, the old buffer the spare. */
static void run_reorder(gpu *g, sph_sim *sim)
{
    gpu_use(g, PROG_H(gather));
    const sph_mask moved = sph_passes[SPH_PASS_REORDER]->writes;
    for (int b = 0; b < B_TOTAL; b++) {
        bool field = b < SPH_FIELD_COUNT;
        if (field ? !(moved & SPH_FIELD_BIT(b)) : b != B_ID) continue;
        if (!g->buf[b]) continue;
        gpu_bind(g, B_SRC, g->buf[b]);
        gpu_bind(g, B_DST, g->spare);
        gpu_set_u(g, PROG_H(gather), U_count, field && sph_field_infos[b].vector ? (uint32_t)sim->dim : 1u);
        gpu_dispatch(g, g->n);
        GLuint t = g->buf[b];
        g->buf[b] = g->spare;
        g->spare = t;
        gpu_bind(g, b, g->buf[b]);
    }
    gpu_use(g, PROG_H(reindex));
    gpu_dispatch(g, g->n);
    g->reordered = true;
}

static unsigned reorder_helpers(const sph_scene_def *def)
{
    (void)def;
    return HELPER_BIT(gather) | HELPER_BIT(reindex);
}

static void run_offsets(gpu *g, sph_sim *sim)
{
    (void)sim;
    fill(g, g->buf[B_START], g->table, SPH_EMPTY);
    gpu_use(g, SPH_PASS_OFFSETS);
    gpu_dispatch(g, g->n);
}

static unsigned offsets_helpers(const sph_scene_def *def)
{
    (void)def;
    return HELPER_BIT(fill);
}

/* The force passes walk the cells themselves (gpu_walk.glsl): no lists on
 * the device; the host builds them from the index when a reader asks. */
static void run_neighbours(gpu *g, sph_sim *sim)
{
    (void)g;
    (void)sim;
}

static void run_interaction(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_INTERACTION;
    gpu_use(g, p);
    gpu_set_u(g, p, U_count, sim->interaction_active);
    gpu_set_f(g, p, U_value, sim->def.interaction_strength * sim->interaction_sign);
    if (g->loc[p][U_point] >= 0)
        g->gl.Uniform3f(g->loc[p][U_point], sim->interaction_point[0], sim->interaction_point[1],
                        sim->interaction_point[2]);
    gpu_dispatch(g, g->n);
}

static void run_integrate(gpu *g, sph_sim *sim)
{
    static const uint32_t zero[4] = {0, 0, 0, 0};
    gpu_send(g, g->buf[B_REDUCE], 0, sizeof zero, zero);
    gpu_use(g, SPH_PASS_INTEGRATE);
    gpu_set_f(g, SPH_PASS_INTEGRATE, U_dt, sim->dt);
    gpu_dispatch(g, g->n);
    /* the only read-back of a step: two floats for the CFL step and the watchdog */
    uint32_t bits[2] = {0x7fc00000u, 0x7fc00000u}; /* NaN if the read fails: the watchdog stops the run */
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->buf[B_REDUCE]);
    g->gc.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof bits, bits);
    float v2, a2, g2 = 0;
    memcpy(&v2, &bits[0], sizeof v2);
    memcpy(&a2, &bits[1], sizeof a2);
    if (sim->def.effects & SPH_EFFECT(GRAVITY))
        for (int d = 0; d < sim->dim; d++) g2 += sim->def.gravity[d] * sim->def.gravity[d];
    sim->max_speed = sqrtf(v2);
    sim->max_acc = sqrtf(a2) + sqrtf(g2);
}

/* A pass that walks the neighbours, with dispatches of its own: its program,
 * told whether the particles are in cell order (as gpu_run_pass does). */
static void use_walk(gpu *g, sph_sim *sim, int p)
{
    gpu_use(g, p);
    gpu_set_u(g, p, U_rows, g->reordered && sim->S.cells.dense);
}

/* density_method = continuity: the sum at the start, which rho_c takes,
 * then rho_c += dt drho (density.c: the host's flag says which). */
static void run_density(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_DENSITY;
    const bool carried = sim->rho_carried && g->buf[SPH_FIELD_RHO_C];
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, carried);
    gpu_set_f(g, p, U_dt, sim->dt);
    gpu_dispatch(g, g->n);
    if (!carried && sim->P.rho_c) sim->rho_carried = sim->dt > 0.0f; /* as density.c's start_carrying */
}

/* The wall particles' velocity in the step's frame, g dt (sph_wall_kick, sph_start.h). */
static void set_kick(gpu *g, const sph_sim *sim, int p)
{
    float kick[3];
    sph_wall_kick(sim, kick);
    if (g->loc[p][U_kick] >= 0) g->gl.Uniform3f(g->loc[p][U_kick], kick[0], kick[1], kick[2]);
}

static void run_density_rate(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_DENSITY_RATE;
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, sim->rho_carried);
    /* delta h_s c [m^2/s], as density_rate.c computes it */
    gpu_set_f(g, p, U_value, sim->def.delta * 0.5f * sim->def.h * sqrtf(sim->def.stiffness));
    /* delta_form = fourtakas: rho0 g of the step, ramped as density_rate.c ramps it */
    float g0[3] = {0, 0, 0};
    if (sim->def.effects & SPH_EFFECT(GRAVITY)) {
        const float gs = sph_start_gravity_scale(sim);
        for (int d = 0; d < sim->dim; d++) g0[d] = sim->def.rest_density * sim->def.gravity[d] * gs;
    }
    if (g->loc[p][U_g0] >= 0) g->gl.Uniform3f(g->loc[p][U_g0], g0[0], g0[1], g0[2]);
    set_kick(g, sim, p);
    gpu_dispatch(g, g->n);
}

static void run_density_gradient(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_DENSITY_GRADIENT;
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, sim->rho_carried);
    gpu_dispatch(g, g->n);
}

/* Two sweeps of one program: the free-surface marks, then the shift, which
 * reads the marks of the particle's neighbours (shifting.c). */
static void run_shifting(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_SHIFTING;
    use_walk(g, sim, p);
    gpu_set_f(g, p, U_value, sim->def.shifting_coefficient * sim->def.h * sim->dt); /* A h dt [m s] */
    gpu_set_u(g, p, U_count, 0);
    gpu_dispatch(g, g->n);
    gpu_set_u(g, p, U_count, 1);
    gpu_dispatch(g, g->n);
}

/* ---- the pressure solvers: one iteration per call ------------------------------
 * The host keeps each solve's count and decides, as the CPU passes do
 * (src/passes/pcisph.c, dfsph.c: the same calls in the same order, with
 * sph_solver_done); the device measures. Per iteration the only read-back is
 * the density (or divergence) error, 4 bytes reduced on the device. */

/* One stage of a solver's program (its u_count). */
static void solver_stage(gpu *g, sph_sim *sim, int p, uint32_t stage, float value)
{
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, stage);
    gpu_set_f(g, p, U_dt, sim->dt);
    gpu_set_f(g, p, U_value, value);
    gpu_dispatch(g, g->n);
}

/* A stage that measures: reduce_[2] zeroed first, the largest error read
 * back (NaN if the read fails: not converged, the solve runs to its cap). */
static double solver_measure(gpu *g, sph_sim *sim, int p, uint32_t stage)
{
    static const uint32_t zero = 0;
    gpu_send(g, g->buf[B_REDUCE], 2 * sizeof zero, sizeof zero, &zero);
    solver_stage(g, sim, p, stage, 0.0f);
    uint32_t bits = 0x7fc00000u;
    gpu_get(g, g->buf[B_REDUCE], 2 * sizeof bits, sizeof bits, &bits);
    float e;
    memcpy(&e, &bits, sizeof e);
    return e;
}

/* The same for a stage that sums the error in units of 2^-28 N (DFSPH's
 * divergence, gpu_dfsph.comp): the mean over the particles. */
static double solver_mean(gpu *g, sph_sim *sim, int p, uint32_t stage)
{
    static const uint32_t zero = 0;
    gpu_send(g, g->buf[B_REDUCE], 2 * sizeof zero, sizeof zero, &zero);
    solver_stage(g, sim, p, stage, 0.0f);
    uint32_t count = 0;
    gpu_get(g, g->buf[B_REDUCE], 2 * sizeof count, sizeof count, &count);
    return ldexp((double)count, -28);
}

/* solver_wall_pressure = extrapolated with wall particles (src/passes/solver_walls.c) */
static bool wall_extrapolated(const sph_scene_def *def)
{
    return def->pressure_solver != SPH_PSOLVER_EOS && def->solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED &&
           sph_scene_wall_particles(def);
}

/* The wall particles' q (the solver's field f) from their fluid neighbours (gpu_wall_extrapolate.comp), after
 * each correction as the CPU's correct() calls sph_solver_wall_extrapolate: c g of the step as it computes it
 * (c = rho_rest for p, 1 for kappa, 0 for kappa_v), at least 0 where clamp. */
static void wall_extrapolate(gpu *g, sph_sim *sim, int f, float c, bool clamp)
{
    if (!wall_extrapolated(&sim->def)) return;
    const int p = PROG_H(wall_extrapolate);
    const float gs = (sim->def.effects & SPH_EFFECT(GRAVITY)) ? c * sph_start_gravity_scale(sim) : 0.0f;
    float g0[3] = {0, 0, 0};
    for (int d = 0; d < sim->dim; d++) g0[d] = gs * sim->def.gravity[d];
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, clamp);
    if (g->loc[p][U_g0] >= 0) g->gl.Uniform3f(g->loc[p][U_g0], g0[0], g0[1], g0[2]);
    gpu_bind(g, B_DST, g->buf[f]);
    gpu_dispatch(g, g->n);
}

static unsigned wall_extrapolate_helper(const sph_scene_def *def)
{
    return wall_extrapolated(def) ? HELPER_BIT(wall_extrapolate) : 0u;
}

/* solver_chebyshev > 0: before a density correction, q (the solver's field f) = w q + (1 - w) q_last and q_last
 * (field last) = q (gpu_solver_blend.comp), w of this correction as the CPU's correct() computes it
 * (sph_solver_chebyshev_weight, solver.h); returns w, 1 with no acceleration. */
static float solver_blend(gpu *g, sph_sim *sim, int f, int last)
{
    if (!(sim->def.solver_chebyshev > 0.0f)) return 1.0f;
    const float w = sph_solver_chebyshev_weight(sim);
    const int p = PROG_H(solver_blend);
    gpu_use(g, p);
    gpu_set_f(g, p, U_value, w);
    gpu_bind(g, B_DST, g->buf[f]);
    gpu_bind(g, B_SRC, g->buf[last]);
    gpu_dispatch(g, g->n);
    return w;
}

static unsigned solver_blend_helper(const sph_scene_def *def)
{
    return def->solver_chebyshev > 0.0f ? HELPER_BIT(solver_blend) : 0u;
}

/* shaders/gpu_pcisph.comp's stages, and gpu_pcisph_force.comp's (the force and x*: a program of its own, as
 * DFSPH's, for the storage blocks) */
enum { PCI_PREDICT = 2, PCI_CORRECT, PCI_DELTA = 5, PCI_CORRECT_LOCAL, PCI_KEEP, PCI_TAKE_BACK, PCI_DELTA_ONE };
enum { PCI_START, PCI_FORCE, PCI_STARTUP };

static void pcisph_force(gpu *g, sph_sim *sim, uint32_t stage)
{
    const int p = PROG_H(pcisph_force);
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, stage);
    gpu_set_f(g, p, U_dt, sim->dt);
    gpu_dispatch(g, g->n);
}

static void run_pcisph(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_PCISPH;
    sph_solver_state *s = &sim->solver;
    if (!(sim->dt > 0)) { /* the start-up evaluation (dt = 0): nothing moves, no pressure yet */
        pcisph_force(g, sim, PCI_STARTUP);
        return;
    }
    const bool local = sim->def.pcisph_local_delta == SPH_ON;
    if (s->iteration == 0) { /* the step's first call: from p = 0, or the last step's p (a warm start) */
        solver_stage(g, sim, p, local ? PCI_DELTA : PCI_DELTA_ONE, s->delta); /* the one delta written as pcisph.c */
        const bool warm = sim->def.solver_warm_start == SPH_ON && s->dt_last > 0;
        pcisph_force(g, sim, warm ? PCI_FORCE : PCI_START);
    }
    const double error = solver_measure(g, sim, p, PCI_PREDICT);
    const int least = sph_solver_least(sim, error, sim->def.solver_tolerance);
    if (least == SPH_SOLVER_KEEP) solver_stage(g, sim, p, PCI_KEEP, 0.0f);
    if (least == SPH_SOLVER_TAKE_BACK) { /* rising: back to the least, as pcisph.c */
        solver_stage(g, sim, p, PCI_TAKE_BACK, 0.0f);
        pcisph_force(g, sim, PCI_FORCE);
        if (sph_solver_chebyshev_restart(sim, false)) { /* on from the least, plain (solver.h) */
            sim->pass_again = true;
            return;
        }
        sph_solver_stopped(sim, solver_measure(g, sim, p, PCI_PREDICT));
        return;
    }
    if (sph_solver_done(sim, error, sim->def.solver_tolerance)) {
        s->iterations = s->iteration;
        s->density_error = error;
        s->iteration = 0;
        s->dt_last = sim->dt;
        return;
    }
    const float w = solver_blend(g, sim, SPH_FIELD_P_PCI, SPH_FIELD_P_PCI_PREV); /* and w times the step */
    if (local)
        solver_stage(g, sim, p, PCI_CORRECT_LOCAL, sim->dt * sim->dt / w);
    else
        solver_stage(g, sim, p, PCI_CORRECT, w * (s->delta / (sim->dt * sim->dt)));
    wall_extrapolate(g, sim, SPH_FIELD_P_PCI, s->rho_rest, sim->def.negative_pressure == SPH_NEGP_CLAMP);
    pcisph_force(g, sim, PCI_FORCE);
    sim->pass_again = true;
}

static unsigned pcisph_helpers(const sph_scene_def *def)
{
    return HELPER_BIT(pcisph_force) | wall_extrapolate_helper(def) | solver_blend_helper(def);
}

/* shaders/gpu_dfsph.comp's stages */
enum { DF_FACTORS, DF_WARM_V, DF_WARM, DF_MEASURE_V, DF_MEASURE, DF_CORRECT_V, DF_CORRECT, DF_KEEP, DF_TAKE_BACK };

/* The share of the last step's kappa a solve starts from: as warm() in
 * src/passes/dfsph.c, SPH_DFSPH_WARM there (0: off, see there), or with
 * solver_warm_start = on (dt_last / dt)^2; the lockstep tests compare kappa
 * after each call, so the two cannot differ unseen. */
#define GPU_DFSPH_WARM 0.0f

static float dfsph_warm(const sph_sim *sim)
{
    const float last = sim->solver.dt_last;
    if (sim->def.solver_warm_start != SPH_ON) return GPU_DFSPH_WARM;
    return last > 0 ? (last / sim->dt) * (last / sim->dt) : 0.0f;
}

/* A warm start: kappa (or kappa_v) times the share, at most the bound (dfsph.c, warm; solver.h,
 * sph_solver_warm_bound). */
static void dfsph_warm_stage(gpu *g, sph_sim *sim, uint32_t stage)
{
    const int p = SPH_PASS_DFSPH;
    use_walk(g, sim, p); /* as solver_stage, with the bound: uniforms go to the program in use */
    gpu_set_u(g, p, U_count, stage);
    gpu_set_f(g, p, U_dt, sim->dt);
    gpu_set_f(g, p, U_value, dfsph_warm(sim));
    gpu_set_f(g, p, U_bound, sph_solver_warm_bound(sim));
    gpu_dispatch(g, g->n);
}

/* acc_df and dv_df from kappa_v (density: and kappa); startup: a = 0. */
static void dfsph_force(gpu *g, sph_sim *sim, bool density, bool startup)
{
    const int p = PROG_H(dfsph_force);
    use_walk(g, sim, p);
    gpu_set_u(g, p, U_count, startup ? 2u : density);
    gpu_set_f(g, p, U_dt, sim->dt);
    gpu_dispatch(g, g->n);
}

static void run_dfsph(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_DFSPH;
    sph_solver_state *s = &sim->solver;
    if (!(sim->dt > 0)) { /* the start-up evaluation (dt = 0): nothing moves, no pressure yet */
        dfsph_force(g, sim, false, true);
        return;
    }
    const float dt2 = sim->dt * sim->dt;
    if (s->iteration == 0 && s->phase == 0) { /* the step's first call */
        solver_stage(g, sim, p, DF_FACTORS, 0.0f);
        dfsph_warm_stage(g, sim, DF_WARM_V);
        dfsph_force(g, sim, false, false);
    }
    if (s->phase == 0) {
        const double error = solver_mean(g, sim, p, DF_MEASURE_V);
        if (!sph_solver_done(sim, error, sim->def.divergence_tolerance)) {
            solver_stage(g, sim, p, DF_CORRECT_V, dt2);
            wall_extrapolate(g, sim, SPH_FIELD_KAPPA_V, 0.0f, true); /* no hydrostatic term (dfsph.c) */
            dfsph_force(g, sim, false, false);
            sim->pass_again = true;
            return;
        }
        s->div_iterations = s->iteration;
        s->divergence_error = error;
        s->iteration = 0;
        s->phase = 1; /* and on to the density in this call */
        dfsph_warm_stage(g, sim, DF_WARM);
        dfsph_force(g, sim, true, false);
    }
    /* reduce_[3]: the largest shortfall of a pushed particle, which the solve also holds (dfsph.c) */
    static const uint32_t zero = 0;
    gpu_send(g, g->buf[B_REDUCE], 3 * sizeof zero, sizeof zero, &zero);
    const double error = solver_measure(g, sim, p, DF_MEASURE);
    uint32_t bits = 0x7fc00000u;
    gpu_get(g, g->buf[B_REDUCE], 3 * sizeof bits, sizeof bits, &bits);
    float over;
    memcpy(&over, &bits, sizeof over);
    const double stop = isnan(over) ? over : fmax(error, over);
    const int least = sph_solver_least_held(sim, error, over, sim->def.solver_tolerance);
    if (least & SPH_SOLVER_KEEP) solver_stage(g, sim, p, DF_KEEP, 0.0f);
    if (least & SPH_SOLVER_TAKE_BACK) { /* rising: back to the best kappa kept, as dfsph.c */
        solver_stage(g, sim, p, DF_TAKE_BACK, 0.0f);
        dfsph_force(g, sim, true, false);
        if (sph_solver_chebyshev_restart(sim, s->held)) { /* on from the best, plain (solver.h) */
            sim->pass_again = true;
            return;
        }
        sph_solver_stopped(sim, solver_measure(g, sim, p, DF_MEASURE));
        s->phase = 0;
        return;
    }
    const bool done = sph_solver_done(sim, stop, sim->def.solver_tolerance);
    s->error = error;
    if (!done) {
        const float w = solver_blend(g, sim, SPH_FIELD_KAPPA, SPH_FIELD_KAPPA_PREV); /* and w times the step */
        solver_stage(g, sim, p, DF_CORRECT, dt2 / w);
        wall_extrapolate(g, sim, SPH_FIELD_KAPPA, 1.0f, true); /* kappa = p / rho_r (dfsph.c) */
        dfsph_force(g, sim, true, false);
        sim->pass_again = true;
        return;
    }
    s->iterations = s->iteration;
    s->density_error = error;
    s->iteration = 0;
    s->phase = 0;
    s->dt_last = sim->dt;
}

static unsigned dfsph_helpers(const sph_scene_def *def)
{
    return HELPER_BIT(dfsph_force) | wall_extrapolate_helper(def) | solver_blend_helper(def);
}

/* [compute] fuse_forces = on: the pressure force and the viscosity in one
 * walk (gpu_forces.comp), run as the pressure_force pass, while both passes
 * are in the pipeline and switched on (as sph_forces_fused on the CPU; the
 * shaders have every form, so no form is left out). */
static bool forces_fused(const sph_sim *sim)
{
    return sim->def.fuse_forces == SPH_ON && sim->in_pipeline[SPH_PASS_PRESSURE_FORCE] &&
           sim->enabled[SPH_PASS_PRESSURE_FORCE] && sim->in_pipeline[SPH_PASS_VISCOSITY] &&
           sim->enabled[SPH_PASS_VISCOSITY];
}

static void run_pressure_force(gpu *g, sph_sim *sim)
{
    const bool fused = forces_fused(sim);
    const int p = fused ? PROG_H(forces) : SPH_PASS_PRESSURE_FORCE;
    use_walk(g, sim, p);
    gpu_set_f(g, p, U_gscale, sph_start_gravity_scale(sim)); /* the volume walls' ghost pressure */
    if (fused) set_kick(g, sim, p);
    gpu_dispatch(g, g->n);
    /* the pass's registry row names acc_p only: the host copy of acc_v is
     * now old too (read by the inspector when stepping pass by pass) */
    if (fused) g->base.stale |= SPH_SYNC_FIELD(SPH_FIELD_ACC_V);
}

static unsigned pressure_force_helpers(const sph_scene_def *def)
{
    return def->fuse_forces == SPH_ON ? HELPER_BIT(forces) : 0;
}

static void run_viscosity(gpu *g, sph_sim *sim)
{
    if (forces_fused(sim)) return; /* the pressure_force pass wrote acc_v in its walk */
    use_walk(g, sim, SPH_PASS_VISCOSITY);
    set_kick(g, sim, SPH_PASS_VISCOSITY);
    gpu_dispatch(g, g->n);
}

/* The walls' hydrostatic term takes the step's share of g (wall_state.c). */
static void run_wall_state(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_WALL_STATE;
    use_walk(g, sim, p);
    gpu_set_f(g, p, U_gscale, sph_start_gravity_scale(sim));
    set_kick(g, sim, p);
    gpu_dispatch(g, g->n);
}

/* surface_tension = csf, csf.c's two sweeps: each surface particle's raw
 * curvature and surface density into the scratch (gpu_csf.comp), then the
 * averaged curvature and the force, sigma [N/m] (gpu_csf_force.comp) */
static void run_csf(gpu *g, sph_sim *sim)
{
    use_walk(g, sim, SPH_PASS_CSF);
    gpu_dispatch(g, g->n);
    const int p = PROG_H(csf_force);
    use_walk(g, sim, p);
    gpu_set_f(g, p, U_value, sim->def.sigma);
    gpu_dispatch(g, g->n);
}

static unsigned csf_helpers(const sph_scene_def *def)
{
    (void)def;
    return HELPER_BIT(csf_force);
}

/* XSPH's epsilon / dt [1/s], as xsph.c computes it (0 before the first step). */
static void run_xsph(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_XSPH;
    use_walk(g, sim, p);
    gpu_set_f(g, p, U_value, sim->dt > 0 ? sim->def.xsph / sim->dt : 0.0f);
    gpu_dispatch(g, g->n);
}

/* shifting = tvf: dt (dt/2) p_b, p_b = rho0 c^2 [Pa], as transport.c computes it. */
static void run_transport(gpu *g, sph_sim *sim)
{
    const int p = SPH_PASS_TRANSPORT;
    use_walk(g, sim, p);
    const float p_b = sim->def.rest_density * sim->def.stiffness;
    gpu_set_f(g, p, U_value, sim->dt * 0.5f * sim->dt * p_b);
    gpu_dispatch(g, g->n);
}

/* ---- the table ------------------------------------------------------------- */

const gpu_pass_row gpu_pass_rows[SPH_PASS_COUNT] = {
    [SPH_PASS_EXTERNAL] = {.source = shader_gpu_external_comp, .run = run_external},
    [SPH_PASS_HASH] = {.source = shader_gpu_hash_comp, .run = run_hash},
    [SPH_PASS_SORT] = {.run = run_sort, .helpers = sort_helpers},
    [SPH_PASS_REORDER] = {.run = run_reorder, .helpers = reorder_helpers},
    [SPH_PASS_OFFSETS] = {.source = shader_gpu_offsets_comp, .run = run_offsets, .helpers = offsets_helpers},
    [SPH_PASS_NEIGHBOURS] = {.run = run_neighbours},
    [SPH_PASS_DENSITY_GRADIENT] = {.source = shader_gpu_density_gradient_comp, .run = run_density_gradient},
    [SPH_PASS_DENSITY_RATE] = {.source = shader_gpu_density_rate_comp, .run = run_density_rate},
    [SPH_PASS_DENSITY] = {.source = shader_gpu_density_comp, .run = run_density},
    [SPH_PASS_PRESSURE] = {.source = shader_gpu_pressure_comp},
    [SPH_PASS_WALL_STATE] = {.source = shader_gpu_wall_state_comp, .run = run_wall_state},
    [SPH_PASS_PRESSURE_FORCE] = {.source = shader_gpu_pressure_force_comp,
                                 .run = run_pressure_force,
                                 .helpers = pressure_force_helpers},
    [SPH_PASS_VISCOSITY] = {.source = shader_gpu_viscosity_comp, .run = run_viscosity},
    [SPH_PASS_COHESION] = {.source = shader_gpu_cohesion_comp},
    [SPH_PASS_NORMALS] = {.source = shader_gpu_normals_comp},
    [SPH_PASS_CURVATURE] = {.source = shader_gpu_curvature_comp},
    [SPH_PASS_CSF] = {.source = shader_gpu_csf_comp, .run = run_csf, .helpers = csf_helpers},
    [SPH_PASS_XSPH] = {.source = shader_gpu_xsph_comp, .run = run_xsph},
    [SPH_PASS_INTERACTION] = {.source = shader_gpu_interaction_comp, .run = run_interaction},
    [SPH_PASS_PCISPH] = {.source = shader_gpu_pcisph_comp, .run = run_pcisph, .helpers = pcisph_helpers},
    [SPH_PASS_DFSPH] = {.source = shader_gpu_dfsph_comp, .run = run_dfsph, .helpers = dfsph_helpers},
    [SPH_PASS_INTEGRATE] = {.source = shader_gpu_integrate_comp, .run = run_integrate},
    [SPH_PASS_SHIFTING] = {.source = shader_gpu_shifting_comp, .run = run_shifting},
    [SPH_PASS_TRANSPORT] = {.source = shader_gpu_transport_comp, .run = run_transport},
    [SPH_PASS_WALLS] = {.source = shader_gpu_walls_comp},
};

void gpu_needed_programs(const sph_sim *sim, bool need[PROG_TOTAL])
{
    memset(need, 0, PROG_TOTAL * sizeof *need);
    need[PROG_H(range)] = true; /* the window's colour scale */
    need[PROG_H(stats)] = need[PROG_H(stats_sum)] = true; /* the HUD's and --stats' figures (gpu_stats.c) */
    /* the HUD's hash health, where there is a hash table (gpu_health.c) */
    need[PROG_H(health)] = sim->in_pipeline[SPH_PASS_HASH] && !sim->S.cells.dense;
    need[SPH_PASS_INTEGRATE] = true;
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (!sim->in_pipeline[p]) continue;
        const gpu_pass_row *row = &gpu_pass_rows[p];
        if (row->source) need[p] = true;
        unsigned h = row->helpers ? row->helpers(&sim->def) : 0;
        for (int k = 0; k < H_TOTAL; k++)
            if (h & (1u << k)) need[SPH_PASS_COUNT + k] = true;
    }
}

/* Storage buffer bindings are the context's state, not the program's: in a
 * shared context another simulation (a reset or a variant switch in the
 * window) may have rebound them, or unbound them by deleting its buffers. */
static void rebind(gpu *g)
{
    for (int k = 0; k < B_TOTAL; k++)
        if (g->buf[k]) gpu_bind(g, k, g->buf[k]);
}

void gpu_run_pass(sph_backend *b, sph_sim *sim, sph_pass_id pass)
{
    gpu *g = (gpu *)b;
    gpu_current(g);
    if (g->share) rebind(g);
    const gpu_pass_row *row = (unsigned)pass < SPH_PASS_COUNT ? &gpu_pass_rows[pass] : NULL;
    if (!row || (!row->run && !row->source)) { /* the backend refuses such a pipeline when it is made */
        fprintf(stderr, "sphlab: the GL backend has no pass %d (%s)\n", (int)pass,
                (unsigned)pass < SPH_PASS_COUNT ? sph_passes[pass]->name : "unknown");
        abort();
    }
    g->changes++;
    gpu_timer_begin(g, sim, (int)pass);
    if (row->run) {
        row->run(g, sim);
    } else {
        gpu_use(g, pass);
        /* the walk's row runs need this step's particles in cell order (the
         * reorder pass may be switched off in the window) */
        gpu_set_u(g, pass, U_rows, g->reordered && sim->S.cells.dense);
        gpu_dispatch(g, g->n);
    }
    gpu_timer_end(g);
    if (g->pass_sync && !g->timer.on) { /* without timer queries: the host clock, after the device */
        g->gl.Finish();
        g->finishes++;
    }
}
