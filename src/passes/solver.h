/* What the two incompressible pressure solvers (pcisph.c, dfsph.c) share:
 * the density they hold, the non-pressure accelerations, the walls' share at
 * any position, the end of a solve. Internal to src/passes/. */
#ifndef SPH_SOLVER_H
#define SPH_SOLVER_H

#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>

/* The density the solvers hold, rho_rest, is the one a particle of the
 * scene's finest lattice sums to at rest (sph_sim_lattice_rest_density), not
 * rho0: holding rho0 would expand every block by the summation's excess at
 * its first step. */

/* The accelerations other than pressure at particle i (viscosity, cohesion,
 * the mouse; gravity is in the velocity already): every acceleration field
 * of the registry except the solvers' own. */
static inline void sph_solver_other_acc(const sph_sim *sim, int i, float a[3])
{
    const sph_particles *P = &sim->P;
    a[0] = a[1] = a[2] = 0.0f;
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if ((SPH_MASK_ACCELERATIONS & SPH_FIELD_BIT(f)) && f != SPH_FIELD_ACC_PCI && f != SPH_FIELD_ACC_DF &&
            P->field[f][0])
            for (int d = 0; d < sim->dim; d++) a[d] += P->field[f][d][i];
}

/* The walls as the solvers count them: the fluid's lattice continued
 * behind each wall, its rows at s/2, 3s/2, ... beyond it, each row summed
 * along the wall at the lattice's own nodes. A block placed on the lattice
 * then reads rho_rest in every row, at the walls too; the volume model's
 * continuous integral (sph_wall_hidden) made the first row read 1.5 % more
 * (2D, poly6, h = 2 s), and the solvers pushed that row off the wall at
 * 3.7 m/s in their first step. Tabulated once over d in [0, h]. */
static inline void sph_solver_wall_table(sph_sim *sim)
{
    sph_solver_state *st = &sim->solver;
    const sph_scene_def *def = &sim->def;
    const float s = sph_scene_finest_spacing(def), h = def->h;
    const int dim = sim->dim, R = s > 0 ? (int)ceilf(h / s) : 0;
    const double m = s > 0 ? def->rest_density * (dim == 3 ? (double)s * s * s : (double)s * s) : 0.0;
    for (int t = 0; t <= SPH_SOLVER_WALL_SAMPLES; t++) {
        const double d = (double)h * t / SPH_SOLVER_WALL_SAMPLES;
        double sum = 0, slope = 0;
        for (int k = 0; s > 0 && d + (k + 0.5) * s < h; k++) {
            const double n = d + (k + 0.5) * s; /* the row's distance from the particle, across the wall */
            for (int a = -R; a <= R; a++)
                for (int b = dim == 3 ? -R : 0; b <= (dim == 3 ? R : 0); b++) {
                    const double r = sqrt(n * n + (double)s * s * (a * a + b * b));
                    if (r >= h) continue;
                    sum += m * sph_kernel_w(&sim->k_density, (float)r);
                    slope += m * sph_kernel_dw(&sim->k_density, (float)r) * n / r;
                }
        }
        st->wall_share[t] = (float)(sum / st->rho_rest);
        st->wall_slope[t] = (float)(slope / st->rho_rest);
    }
}

/* The share of rho_rest the walls add at position x (combined over walls as
 * sph_wall_hidden does: 1 - prod (1 - share)), and its gradient [1/m]. */
static inline float sph_solver_walls(const sph_sim *sim, const float x[3], float grad[3])
{
    const sph_solver_state *st = &sim->solver;
    const int dim = sim->dim;
    const float scale = (float)SPH_SOLVER_WALL_SAMPLES / sim->def.h;
    float vis[6], dvis[6], all = 1.0f;
    for (int d = 0; d < dim; d++)
        for (int side = 0; side < 2; side++) {
            const int w = 2 * d + side;
            vis[w] = 1.0f;
            dvis[w] = 0.0f;
            if (sim->period[d] > 0) continue; /* no walls on a periodic axis */
            const float dist = side == 0 ? x[d] - sim->def.domain_min[d] : sim->def.domain_max[d] - x[d];
            float t = fmaxf(dist, 0.0f) * scale;
            if (!(t < (float)SPH_SOLVER_WALL_SAMPLES)) continue;
            const int i = (int)t;
            const float f = t - (float)i;
            vis[w] = 1.0f - (st->wall_share[i] + f * (st->wall_share[i + 1] - st->wall_share[i]));
            const float slope = st->wall_slope[i] + f * (st->wall_slope[i + 1] - st->wall_slope[i]);
            dvis[w] = side == 0 ? -slope : slope; /* d(visible)/dx along the axis */
            all *= vis[w];
        }
    if (grad)
        for (int d = 0; d < 3; d++) {
            grad[d] = 0.0f;
            if (d >= dim) continue;
            for (int w = 2 * d; w <= 2 * d + 1; w++) {
                float others = 1.0f;
                for (int o = 0; o < 2 * dim; o++)
                    if (o != w) others *= vis[o];
                grad[d] -= dvis[w] * others;
            }
        }
    return 1.0f - all;
}

/* The same at particle i's predicted position (where the lists were made). */
static inline float sph_solver_walls_pred(const sph_sim *sim, int i, float grad[3])
{
    float x[3] = {0, 0, 0};
    for (int d = 0; d < sim->dim; d++) x[d] = sim->P.pred[d][i];
    return sph_solver_walls(sim, x, grad);
}

/* The most pressure per unit density [m^2/s^2] a warm start may carry into a step (dfsph.c, warm): the
 * kinetic energy per unit mass of the fastest the scene can make or has (speed_scale: a fall across the
 * domain, the blocks, the forces; max_speed: the last step's fastest particle), Bernoulli's g H + v^2 / 2
 * along a streamline from a free surface at rest, H the domain's height. */
static inline float sph_solver_warm_bound(const sph_sim *sim)
{
    return 0.5f * (sim->speed_scale * sim->speed_scale + sim->max_speed * sim->max_speed);
}

/* The minimum image along periodic axes (a no-op elsewhere). */
static inline float sph_solver_dx(const sph_sim *sim, float dx, int d)
{
    return sim->period[d] > 0 ? sph_min_image(dx, sim->period[d], sim->inv_period[d]) : dx;
}

/* Where the walls pass will put a particle predicted at x: a position past
 * a wall is put back on it (passes/walls.c); c receives it, and the result
 * says whether it moved. A prediction that ignores this reads a particle
 * past the wall as having left its neighbours, when the step then sets it
 * on the wall among them (docs/accuracy.md, section 8). */
static inline bool sph_solver_clamped(const sph_sim *sim, const float x[3], float c[3])
{
    bool moved = false;
    for (int d = 0; d < 3; d++) {
        c[d] = x[d];
        if (d >= sim->dim || !(sim->def.effects & SPH_EFFECT(WALLS)) || sim->period[d] > 0) continue;
        c[d] = fminf(fmaxf(x[d], (float)sim->def.domain_min[d]), (float)sim->def.domain_max[d]);
        moved |= c[d] != x[d];
    }
    return moved;
}

/* The density solves' guard against divergence (pcisph.c, at the top; dfsph.c): after an
 * iteration's error, SPH_SOLVER_KEEP when it is the least so far (the caller
 * keeps its pressure), SPH_SOLVER_TAKE_BACK when it has risen above twice
 * that least plus the tolerance (the caller puts that pressure back,
 * measures again and ends the solve with sph_solver_stopped), else
 * SPH_SOLVER_GO_ON. Twice: a warm-started solve may rise by more than the
 * tolerance in its first iterations and then converge (the warm 2D DFSPH dam
 * break of tests/test_solvers.c, step 219, from 3.7 %). NaN (a GL read that
 * failed) goes on. */
enum { SPH_SOLVER_GO_ON = 0, SPH_SOLVER_KEEP = 1, SPH_SOLVER_TAKE_BACK = 2 };
static inline int sph_solver_least(sph_sim *sim, double error, double tolerance)
{
    sph_solver_state *s = &sim->solver;
    if (s->iteration == 0 || error < s->least) {
        s->least = error;
        return SPH_SOLVER_KEEP;
    }
    return error > 2.0 * s->least + tolerance ? SPH_SOLVER_TAKE_BACK : SPH_SOLVER_GO_ON;
}

/* DFSPH's density solve holds two things: the compression (error) within the tolerance, and no pushed particle
 * below rho_r by more than it (over, dfsph.c). The first is the solve's target; the second is there so that a warm
 * start's pressure can be taken off where the flow no longer needs it. Once an iterate holds the compression,
 * kappa_best keeps, of the iterates that hold it, the one with the least over, so that a solve whose pursuit of the
 * second rises ends with the first held; before, it kept the least max(error, over), which could be an iterate
 * above the tolerance: the bench's 50,688-particle warm run ended its step 5 at 0.1175 % after 761 iterations,
 * where earlier iterates had held 0.1 % (docs/accuracy.md, section 8). Returns SPH_SOLVER_KEEP and
 * SPH_SOLVER_TAKE_BACK as bits (both: keep this iterate and end there), the rise measured on max(error, over) as
 * sph_solver_least's. */
static inline int sph_solver_least_held(sph_sim *sim, double error, double over, double tolerance)
{
    sph_solver_state *s = &sim->solver;
    const double stop = isnan(over) ? over : fmax(error, over); /* NaN (a GL read that failed) goes on */
    if (s->iteration == 0) s->held = false;
    int keep = 0;
    if (error <= tolerance && !isnan(over)) {
        if (!s->held || over < s->least_over) keep = SPH_SOLVER_KEEP;
        if (keep) s->least_over = over;
        s->held = true;
    } else if (!s->held && (s->iteration == 0 || stop < s->least)) {
        keep = SPH_SOLVER_KEEP;
    }
    if (s->iteration == 0 || stop < s->least) {
        s->least = stop;
        return keep;
    }
    return keep | (stop > 2.0 * s->least + tolerance ? SPH_SOLVER_TAKE_BACK : 0);
}

/* The step's record of a solve that took its least back: error, measured again there. */
static inline void sph_solver_stopped(sph_sim *sim, double error)
{
    sph_solver_state *s = &sim->solver;
    s->iterations = s->iteration + 1;
    s->stopped++;
    s->density_error = s->error = error;
    s->iteration = 0;
    s->dt_last = sim->dt;
}

/* solver_chebyshev = rho > 0: the Chebyshev semi-iterative acceleration of the density solve's Jacobi steps (Wang
 * 2015, ACM Trans. Graph. 34(6):246, who applies it to the Jacobi iterations of projective and position-based
 * dynamics, nonlinear as these solves are). Correction k (the solve's iteration count, 1 at the first) weighs w_k:
 * 1 before SPH_CHEBYSHEV_FIRST (sph_scene.h: corrections 1 to 9 are plain), 2 / (2 - rho^2) at it, then
 * 4 / (4 - rho^2 w_(k-1)), falling towards 2 / (1 + sqrt(1 - rho^2)); the correction makes
 * q = w (q + dq) + (1 - w) q_last, q_last the iterate before. It is written as a blend b = w q + (1 - w) q_last
 * (sph_solver_chebyshev_blend; on the GL backend a stage of its own, gpu_solver_blend.comp) and the Jacobi step
 * from b with w dq (the solvers pass w in the step's divisor, as the
 * GL host's u_value), then the solver's clamp. Why: a Jacobi step corrects each particle from its own error, so
 * an error spread over a deep column falls slowly, the smooth part by 0.99 to 0.999 an iteration on the 2D dam
 * break of lessons/scenes/dam-break-2d.ini (a probe of the density error's ratio from iteration to iteration,
 * docs/accuracy.md, section 8); the blend carries each step on in the direction the last one took. The first
 * plain steps make q_last and start the solve where a Jacobi step is best, on the error's rough part; rho is the
 * contraction the acceleration is tuned to (a key, measured there: 0.9 halved the iterations). */
static inline float sph_solver_chebyshev_weight(sph_sim *sim)
{
    sph_solver_state *s = &sim->solver;
    const float rho = sim->def.solver_chebyshev;
    if (s->iteration <= s->chebyshev_from) s->chebyshev_from = 0; /* a new solve */
    const int k = s->iteration - s->chebyshev_from;
    if (!(rho > 0.0f) || k < SPH_CHEBYSHEV_FIRST)
        s->chebyshev_w = 1.0f;
    else if (k == SPH_CHEBYSHEV_FIRST)
        s->chebyshev_w = 2.0f / (2.0f - rho * rho);
    else
        s->chebyshev_w = 4.0f / (4.0f - rho * rho * s->chebyshev_w);
    return s->chebyshev_w;
}

/* A solve whose error rose (sph_solver_least, _held: SPH_SOLVER_TAKE_BACK), its best iterate taken back: under
 * the acceleration (the latest correction's w > 1) it goes on from there with plain corrections, the acceleration
 * starting again at the 10th after it, and this returns true; the call counts as an iteration (it measured and
 * took back, as sph_solver_stopped counts it). A rise under plain corrections ends the solve as without the
 * acceleration (false), and so does DFSPH's where an iterate already held the compression (held: that iterate is
 * taken back and ends the solve within the tolerance, as before). Why: the blend carries each step on in the
 * direction of the last, and where the error's shape changes (a particle's neighbourhood, the clamp) it
 * overshoots; ended there, the 240,000-particle dam break of docs/accuracy.md (section 8) stopped 6 of its density
 * solves, at up to 1.6 %. */
static inline bool sph_solver_chebyshev_restart(sph_sim *sim, bool held)
{
    sph_solver_state *s = &sim->solver;
    if (!(s->chebyshev_w > 1.0f) || held) return false;
    s->chebyshev_w = 1.0f;
    s->restarts++;
    s->iteration++;
    s->chebyshev_from = s->iteration;
    return true;
}

/* The blend before a correction: w q + (1 - w) q_last; q itself where w = 1 (q_last is then not read: in a solve's
 * first steps it holds the last solve's). As gpu_solver_blend.comp computes it, bit for bit (-ffp-contract=off). */
static inline float sph_solver_chebyshev_blend(float w, float q, float last)
{
    return w == 1.0f ? q : w * q + (1.0f - w) * last;
}

/* A solve's iteration ends: another call of the pass, or the step's record. */
static inline bool sph_solver_done(sph_sim *sim, double error, double tolerance)
{
    sph_solver_state *s = &sim->solver;
    s->error = error;
    s->iteration++;
    if (error <= tolerance) return true;
    if (s->iteration >= sim->def.solver_max_iterations) {
        s->capped++;
        return true;
    }
    return false;
}

/* solver_wall_pressure = extrapolated: the wall particles' q (PCISPH's p, c = rho_rest; DFSPH's kappa, c = 1;
 * its kappa_v, c = 0: no hydrostatic term) from their fluid neighbours, at least floor (solver_walls.c). */
void sph_solver_wall_extrapolate(sph_sim *sim, float *q, float c, float floor);

#endif
