/* Pass: DFSPH, divergence-free SPH (Bender & Koschier 2015; 2017, Algorithms
 * 1 to 3), one iteration per call.
 *
 * Each step makes two solves at the step's predicted positions x + dt v
 * (where the neighbour lists and the density were made), both on the
 * velocity v* = v + dt (other accelerations + this pass's a):
 *   divergence-free: D_i = sum_j m_j (v*_i - v*_j) . grad W^p_ij (+ rho_r grad(walls' share) . v*_i at walls,
 *     solver.h),
 *     kappa^v_i += max(D_i, 0) alpha^v_i / dt, until the mean of max(dt D_i, 0) / rho_r <= divergence_tolerance
 *     (the density change the flow would make in one step, counted where rho_i >= rho_r; the average, as
 *     Bender & Koschier's Algorithm 2);
 *   constant density: rho*_i = sum_j m_j W(x*_i - x*_j) + rho_r (walls' share at x*_i), summed at the positions
 *     x* = x + dt v* the step will reach, clamped into the box as the walls pass will (as PCISPH does, solver.h);
 *     kappa_i = max(kappa_i + omega (rho*_i - rho_r) alpha_i / dt^2, -kappa^v_i), until
 *     max (rho*_i - rho_r) / rho_r <= solver_tolerance: the largest error, not Bender & Koschier's average;
 *     and until no pushed particle (kappa + kappa^v > 0) is below rho_r by more than the tolerance: a warm start's
 *     pressure must be removable where the flow no longer needs it, as the cold solve's bound removes it (stopping
 *     on compression alone, the warm 2D dam break of tests/test_solvers.c ended with 545.2 J of kinetic energy
 *     against 502.3 J cold at 0.1 %, 534.6 against 488.0 J at 0.01 %; now 538.0 and 489.5 J, docs/accuracy.md);
 * with the factor alpha_i = rho_r / max(G^rho_i . G^p_i + sum_j m_j^2 grad W^rho_ij . grad W^p_ij, its full-lattice
 * value, see below),
 * G_i = sum_j m_j grad W_ij + rho_r grad(walls' share) (Bender & Koschier 2017, eq. 12 with rho_i = rho_r),
 * and the divergence solve's alpha^v_i = rho_r / max(|G^p_i|^2 + sum_j m_j^2 |grad W^p_ij|^2, its full-lattice value)
 * and the acceleration a_i = -sum_j m_j (K_i + K_j) / rho_r grad W^p_ij - K_i grad(walls' share),
 * K = kappa^v + kappa (eq. 10).
 * Why the density solve differs from the paper's (rho* = rho + dt^2 sum_j m_j (a_i - a_j) . grad W_ij, eq. 11, and
 * kappa only growing): the linearised rho* misses the second-order terms and the walls pass, and the 2D dam break
 * of tests/test_solvers.c (dfsph_holds_reached_2d) ended 26 of 260 steps above its 0.1 % at the positions reached,
 * up to 3.4 %. With the relaxed step below the linearised rho* still does not hold it: in the paper's form with the
 * velocities, rho*_i = rho_i + dt sum_j m_j (dv_i - dv_j) . grad W_ij at pred (+ the walls' gradient term; pred is
 * x + dt v, so dv where the paper has v* about x), the same test ended 80 of 202 converged steps above 0.1 % at
 * the positions reached, up to 14.4 %, 58 solves capped, in 66.7 iterations per step (summed at x*: none above,
 * 4 capped, 62.0); the 3D one 56 of 99 above, up to 0.60 %, 22.2 iterations (summed: none, 22.5). Nor was it
 * cheaper: on the bench's 15,360-particle dam break (10 steps, one thread) 147.6 iterations per step in 34.8 s of
 * user CPU time, against 148.4 in 20.2 to 23.4 s summed at x* made once per particle (it redoes the walls'
 * volume-model term each iteration; docs/performance.md). Summed at x*, a kappa that only grows ran away where a
 * particle's own push cannot lower its density
 * (pressed onto a wall) and, once past, stays: hence a step that can also lower kappa, relaxed by omega = 0.5 as
 * Ihmsen et al. 2014 (IISPH, IEEE TVCG 20(3)) relax their Jacobi step (unrelaxed, the watchdog stopped both dam
 * breaks of those tests within 2 steps). K stays >= 0 (no pull, as negative_pressure = clamp), and the bound is on
 * K, not on kappa alone, so that the density solve can take back a divergence pressure that overshot: with kappa
 * >= 0, lesson 11's dam break at a 1 % tolerance stopped the watchdog at step 210 (near-coincident particles in
 * the far corner driven apart by kappa^v up to 420 m^2/s^2), as the linearised solve did at step 176. The
 * divergence solve stops on the average as the paper's does: on the largest, at 0.1 % it ran to its cap of 100
 * iterations where the front met the far wall, its kappa^v only growing (to 610 m^2/s^2), and pressed particles
 * onto the wall so that the density solve, summing at positions the walls pass clamps, could not lower their
 * density (lesson 11 at 0.1 %: 12 capped solves, one ending at 4.0 %; with the floor on alpha below, the watchdog
 * at step 207).
 * alpha's denominator is at least that of a particle with a full neighbourhood (sph_sim_lattice_dots): where a
 * wall's gradient cancels the pairs' differently for the two kernels it fell to 0 or below, alpha read 0 and the
 * particle was never corrected (lesson 11 at 0.1 %, step 106: 3 capped solves in a row).
 * Where the denominator itself is not positive, alpha is stored negative: with two kernels G^rho . G^p can be
 * below -sum m^2 grad W^rho . grad W^p (a near neighbour on one side weighs in grad W^p, farther ones on the other in
 * grad W^rho), and the particle's own push then raises its density. The density solve, which can take its kappa
 * back, uses |alpha|.
 * The divergence solve reads D with the pressure kernel's gradient, the one its push acts with: Bender & Koschier
 * (2017, eqs. 9 and 10) take one grad W_ij in both, so that the solve's matrix is symmetric and positive
 * semi-definite (the push's work is -rho_r sum m_i kappa^v_i D_i); D is then rho div v, estimated with the pressure
 * kernel, and its factor alpha^v (above) is always > 0. Read with grad W^rho, as before, the matrix was neither:
 * lesson 11's dam break at divergence_tolerance = 1e-5 stopped the watchdog at step 227 (t = 0.444 s), where two
 * particles with a near-coincident neighbour between them (0.0026 m, h = 0.04 m; own G^rho . G^p = -6.6e8 against
 * dots 6.7e8 kg^2/m^6, the self-response 1 % of a full one) each raised the other's divergence more than its own push
 * lowered its own: their kappa^v, which only grows, grew 9 % an iteration, to 5.9e4 m^2/s^2 and a mean error of 5.9e-2
 * at the cap (alpha < 0 had let it run 0.5 s at 1e-4; before that, kappa^v ran away at 1e-4 too). Now it runs to
 * 0.5 s at 1e-5 (tests/test_dfsph_tight.c: 53.1 divergence iterations per step, 18 of 263 solves capped, ending at up
 * to 2.2e-5, early in the run where the column is deep and Jacobi slow), and the 2D dam break of
 * lessons/scenes/dam-break-2d.ini at 1e-5 runs its 1 s (it stopped at step 838; docs/accuracy.md, section 8).
 * A step that can also lower kappa^v, max(kappa^v + omega alpha^v dt D / dt^2, 0) as SPlisHSPlasH's
 * TimeStepDFSPH does (omega 1 or 0.5), converged worse there: 198 or 145 capped solves, against 18.
 * Left: the 2D dam break of tests/test_solvers.c (check_dam) at 1e-5 ends 27.6 J/m (0.56 %) above its start's energy,
 * put in by four constant-density solves capped in a row (steps 208 to 211); at the default 1e-3 it is unchanged.
 * Bender & Koschier solve the divergence after moving the particles, with
 * new neighbours; here both solves use the step's lists, the divergence one
 * first, so the density solve accounts for the positions it changes. Warm
 * start (Bender & Koschier 2017 start each solve from the last step's kappa):
 * solver_warm_start = on (off by default, see SPH_DFSPH_WARM below).
 * Wall particles (wall_model = particles, obstacles) are neighbours like the
 * fluid's in the sums, at their fixed places, with kappa = kappa^v = 0: they
 * push back with K_i alone, as the volume model's walls do with -K_i
 * grad(share) (Akinci et al. 2012's boundary force has the same single term),
 * add to G_i but not to the sums over the neighbours i's push moves, and
 * count in neither solve's error. With solver_wall_pressure = extrapolated
 * they take the fluid's kappa and kappa^v after each correction
 * (solver_walls.c; kappa with the hydrostatic term).
 * rho_r is the lattice's rest density (solver.h); the walls
 * count as the lattice continued behind them (solver.h), in place of the
 * density pass's volume-model term. */
#include "solver.h"
#include "sph_memory.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The share of the last step's kappa a solve starts from. 0: the warm start
 * is off. Measured with the linearised density solve, whose kappa only grew
 * (see the top), on the 2D dam break of tests/test_solvers.c (dt = 0.5 ms,
 * 300 steps): share 0 ended with 511 J of kinetic energy (PCISPH: 516 J),
 * 6.9 iterations per step; 0.5 with 646 J (+26 %, energy the stale pressure
 * put in, which that solve could not take back) and 4.2 iterations; 1
 * (Bender & Koschier 2017, Algorithm 3's sums) stopped the watchdog at step
 * 50. With the density solve that can lower kappa, [physics]
 * solver_warm_start = on starts both solves from all of the last step's
 * kappa times (dt_last / dt)^2 (kappa [m^2/s^2] holds 1/dt^2): it holds the
 * tolerance (tests/test_solvers.c, dfsph_warm_holds_reached_2d/_3d) in 23.5
 * instead of 62.0 iterations per step in 2D, 10.4 instead of 22.5 in 3D, and
 * ended that dam break with 545 J instead of 502 J; with the stopping test on
 * pushed particles below rho_r (see the top) 30.4 and 12.8 iterations, 538 J
 * (docs/accuracy.md, section 8). */
#define SPH_DFSPH_WARM 0.0f

/* The relaxation of the density solve's Jacobi step (see the top): 0.5, as
 * Ihmsen et al. 2014 (IISPH, IEEE TVCG) relax theirs. */
#define SPH_DFSPH_OMEGA 0.5f

static const char *skip_reason(const sph_scene_def *def)
{
    if (def->pressure_solver != SPH_PSOLVER_DFSPH) return "pressure_solver is not dfsph";
    return (def->effects & SPH_EFFECT(PRESSURE)) ? NULL : "effects do not list pressure";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    char cheb[112] = "";
    if (def->solver_chebyshev > 0.0f)
        snprintf(cheb, sizeof cheb,
                 ", the density solve Chebyshev-accelerated from the 10th correction (solver_chebyshev = %g)",
                 def->solver_chebyshev);
    snprintf(out, (size_t)n,
             "divergence-free solve until the mean max(dt D rho/Dt, 0) / rho_rest <= %g, then constant density "
             "until the largest (rho - rho_rest) / rho_rest <= %g (at most %d iterations each%s%s)%s",
             def->divergence_tolerance, def->solver_tolerance, def->solver_max_iterations,
             def->solver_warm_start == SPH_ON ? ", warm start" : "", cheb,
             sph_scene_wall_volume(def)     ? ", walls count and push back"
             : !sph_scene_wall_particles(def) ? ""
             : def->solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED
                 ? ", wall particles count and hold the fluid's pressure (extrapolated)"
                 : ", wall particles count and push back with the fluid particle's own pressure");
}

/* grad W_ij of kernel k for the pair offset dx (x_i - x_j); r2 = |dx|^2 > 0. */
static inline float grad_factor(const sph_kernel *k, float r2)
{
    const float r = sqrtf(r2);
    return r > 0 ? sph_kernel_dw(k, r) / r : 0.0f;
}

static inline void pair_dx(const sph_sim *sim, int i, uint32_t j, float dx[3], float *r2)
{
    *r2 = 0;
    dx[0] = dx[1] = dx[2] = 0;
    for (int d = 0; d < sim->dim; d++) {
        dx[d] = sph_solver_dx(sim, sim->P.pred[d][i] - sim->P.pred[d][j], d);
        *r2 += dx[d] * dx[d];
    }
}


static void factors(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float rho_r = sim->solver.rho_rest;
    const bool walls = sph_sim_wall_volume(sim);
    const float full = sim->solver.den_full;
    /* i's own push through a wall particle: K_i alone when the walls hold no pressure; with
     * solver_wall_pressure = extrapolated the wall particle takes its fluid neighbours' kappa after each
     * correction, near i about i's own, so the pair pushes with about K_i + K_w = 2 K_i and the factor must
     * count the walls' part of G^p twice. Counted once, the Jacobi step overshot where walls are most of a
     * particle's support: a 2D dam break hitting a box on the floor (2203 particles, h = 2 spacings) was
     * stopped by the watchdog at 21 m/s at the impact; counted twice it runs its 0.5 s, the splash at 7.86 m/s
     * at most (PCISPH 7.1, the equation of state 8.0), in as many iterations (16.1 a step against 15.7).
     * G^rho, which the density measures, counts the walls once. */
    const float wall_push = sph_scene_wall_particles(&sim->def) &&
                                    sim->def.solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED
                                ? 2.0f
                                : 1.0f;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) { /* a wall particle holds no kappa (see the top) */
            P->alpha[i] = P->alpha_v[i] = 0.0f;
            continue;
        }
        float gr[3] = {0, 0, 0}, gp[3] = {0, 0, 0}, g1[3] = {0, 0, 0}, dots = 0, dots_p = 0; /* g1: walls once */
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float dx[3], r2;
            pair_dx(sim, i, j, dx, &r2);
            const float fr = P->mass[j] * grad_factor(&sim->k_density, r2);
            const float fp = P->mass[j] * grad_factor(&sim->k_pressure, r2);
            const bool still = sph_is_wall(P, j); /* a wall particle counts, but i's push cannot move it */
            const float twice = still ? wall_push : 1.0f; /* see wall_push above */
            for (int d = 0; d < dim; d++) {
                gr[d] += fr * dx[d];
                gp[d] += twice * fp * dx[d];
                g1[d] += fp * dx[d];
                if (still) continue;
                dots += fr * fp * dx[d] * dx[d];
                dots_p += fp * fp * dx[d] * dx[d];
            }
        }
        if (walls) {
            float g[3];
            sph_solver_walls_pred(sim, i, g);
            for (int d = 0; d < dim; d++) {
                gr[d] += rho_r * g[d];
                gp[d] += rho_r * g[d];
                g1[d] += rho_r * g[d];
            }
        }
        const float raw = dots + gr[0] * gp[0] + gr[1] * gp[1] + gr[2] * gp[2];
        const float sign = raw > 1e-6f * rho_r * rho_r / (sim->def.h * sim->def.h) ? 1.0f : -1.0f; /* see the top */
        P->alpha[i] = sign * rho_r / fmaxf(raw, full);
        /* the divergence solve's: its divergence and its push take one gradient, so this is > 0 (see the top);
         * the divergence reads the walls once (g1), the push through them as wall_push says (gp) */
        P->alpha_v[i] = rho_r / fmaxf(dots_p + g1[0] * gp[0] + g1[1] * gp[1] + g1[2] * gp[2], sim->solver.den_full_v);
    }
}

/* acc_df from the kappa sums (with_density: also the constant-density one). */
static void force(sph_sim *sim, bool with_density)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float inv_r = 1.0f / sim->solver.rho_rest;
    const bool walls = sph_sim_wall_volume(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) { /* wall particles stay where they are */
            for (int d = 0; d < dim; d++) P->acc_df[d][i] = P->dv_df[d][i] = 0.0f;
            continue;
        }
        const float k_i = P->kappa_v[i] + (with_density ? P->kappa[i] : 0.0f);
        float a[3] = {0, 0, 0};
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float dx[3], r2;
            pair_dx(sim, i, j, dx, &r2);
            const float k_j = P->kappa_v[j] + (with_density ? P->kappa[j] : 0.0f);
            const float c = P->mass[j] * (k_i + k_j) * inv_r * grad_factor(&sim->k_pressure, r2);
            for (int d = 0; d < dim; d++) a[d] -= c * dx[d];
        }
        if (walls) {
            float g[3];
            sph_solver_walls_pred(sim, i, g);
            for (int d = 0; d < dim; d++) a[d] -= k_i * g[d];
        }
        float other[3];
        sph_solver_other_acc(sim, i, other);
        for (int d = 0; d < dim; d++) {
            P->acc_df[d][i] = a[d];
            P->dv_df[d][i] = sim->dt * (other[d] + a[d]);
        }
    }
}

/* x*: where integration and the walls pass will put each particle with this
 * iteration's dv_df (x + dt v* = pred + dt dv_df, clamped into the box), once
 * per particle into the solver's scratch: the pair loop read it per pair, and
 * made the density iteration cost 4 to 4.5 PCISPH iterations. */
static float *reached(sph_sim *sim)
{
    sph_solver_state *st = &sim->solver;
    const int n = (int)sim->n, dim = sim->dim;
    if (st->x_df_cap < sim->n) {
        char size[32];
        float *grown = realloc(st->x_df, (size_t)sim->n * 3 * sizeof *grown);
        if (!grown) /* returning would leave the last iteration's rho_df in place: a wrong answer in silence */
            sph_memory_fail("the dfsph pass's scratch for x* could not be made (%s)",
                            sph_memory_text(3.0 * sim->n * sizeof *grown, size, sizeof size));
        st->x_df = grown;
        st->x_df_cap = sim->n;
    }
    float *restrict xs = st->x_df;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        float x[3] = {0, 0, 0}, c[3];
        for (int d = 0; d < dim; d++) x[d] = sim->P.pred[d][i] + sim->dt * sim->P.dv_df[d][i];
        if (sph_is_wall(&sim->P, i)) /* beyond the box, where they stay */
            memcpy(c, x, sizeof c);
        else
            sph_solver_clamped(sim, x, c);
        for (int d = 0; d < 3; d++) xs[3 * (size_t)i + (size_t)d] = c[d];
    }
    return xs;
}

/* rho_df: dt D rho/Dt of v* (density false; linear, Bender & Koschier 2017 eq. 9, with grad W^p), or the density
 * rho* summed at the positions x* the step will reach (density true); returns the error: the mean over the particles of
 * max(dt D, 0) / rho_r (Bender & Koschier's average, Algorithm 2), or max (rho* - rho_r) / rho_r. The divergence
 * counts only where the density is at least rho_r: a particle below it (a free surface) may expand or
 * approach, and one with a thin neighbourhood (alpha small) could not be corrected anyway. over (density): the
 * largest (rho_r - rho*) / rho_r of a particle still pushed (kappa + kappa^v > 0), 0 if none. */
static double measure(sph_sim *sim, bool density, double *over)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float dt = sim->dt, rho_r = sim->solver.rho_rest, rho0 = sim->def.rest_density;
    const bool walls = sph_sim_wall_volume(sim);
    const float *restrict xs = density ? reached(sim) : NULL;
    float worst = 0.0f, pushed = 0.0f;
    double total = 0;
    long fluid = 0; /* the particles the average is over: not the wall particles */
#pragma omp parallel for schedule(static) reduction(max : worst, pushed) reduction(+ : total, fluid) \
    if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) { /* not the fluid's: no error of its own */
            P->rho_df[i] = density ? rho_r : 0.0f;
            continue;
        }
        fluid++;
        if (density) {
            const float *xi = xs + 3 * (size_t)i;
            float rho = P->mass[i] * sph_kernel_w(&sim->k_density, 0.0f);
            const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
            for (uint32_t e = 0; e < row.n; e++) {
                const float *xj = xs + 3 * (size_t)sph_nbr_at(&row, e);
                float r2 = 0;
                for (int d = 0; d < dim; d++) {
                    const float dx = sph_solver_dx(sim, xi[d] - xj[d], d);
                    r2 += dx * dx;
                }
                rho += P->mass[sph_nbr_at(&row, e)] * sph_kernel_w(&sim->k_density, sqrtf(r2));
            }
            if (walls) rho += rho_r * sph_solver_walls(sim, xi, NULL);
            P->rho_df[i] = rho;
            worst = fmaxf(worst, (rho - rho_r) / rho_r);
            if (P->kappa[i] + P->kappa_v[i] > 0.0f) pushed = fmaxf(pushed, (rho_r - rho) / rho_r);
            continue;
        }
        float vi[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) vi[d] = P->dv_df[d][i] + P->vel[d][i];
        float sum = 0;
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float dx[3], r2;
            pair_dx(sim, i, j, dx, &r2);
            const float f = P->mass[j] * grad_factor(&sim->k_pressure, r2); /* the push's gradient (see the top) */
            for (int d = 0; d < dim; d++) sum += f * (vi[d] - P->dv_df[d][j] - P->vel[d][j]) * dx[d];
        }
        float rho = P->rho[i];
        if (walls) {
            float g[3];
            const float share = sph_solver_walls_pred(sim, i, g);
            for (int d = 0; d < dim; d++) sum += rho_r * g[d] * vi[d];
            /* the density pass counted the walls as the volume model does: count them as the solvers do */
            rho += rho_r * share - rho0 * sph_wall_hidden(sim, &sim->k_density, i, NULL);
        }
        P->rho_df[i] = rho >= rho_r ? dt * sum : 0.0f;
        worst = fmaxf(worst, P->rho_df[i] / rho_r);
        total += fmaxf(P->rho_df[i], 0.0f) / rho_r;
    }
    if (over) *over = pushed;
    return density ? worst : (fluid > 0 ? total / (double)fluid : 0.0);
}

/* The divergence: kappa^v += the increment that cancels this particle's
 * error (Bender & Koschier 2017, Algorithm 2), with alpha^v. The density: a relaxed,
 * projected Jacobi step, kappa = max(kappa + omega alpha (rho* - rho_r) / dt^2, 0), see the top. */
static void correct(sph_sim *sim, bool density)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n;
    const float dt = sim->dt, rho_r = sim->solver.rho_rest;
    float *restrict k = density ? P->kappa : P->kappa_v;
    /* solver_chebyshev: the blend with the iterate before and w times the step (solver.h) */
    float *restrict last = density && sim->def.solver_chebyshev > 0.0f ? P->kappa_prev : NULL;
    const float w = last ? sph_solver_chebyshev_weight(sim) : 1.0f;
    const float step2 = dt * dt / w; /* as the GL host's u_value, bit for bit; dt^2 where w = 1 */
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) continue; /* kappa stays 0: the walls push with K_i alone (see the top) */
        if (density) {
            float b = k[i];
            if (last) {
                b = sph_solver_chebyshev_blend(w, k[i], last[i]);
                last[i] = k[i];
            }
            k[i] = fmaxf(b + SPH_DFSPH_OMEGA * (P->rho_df[i] - rho_r) * fabsf(P->alpha[i]) / step2, -P->kappa_v[i]);
        } else
            k[i] += fmaxf(P->rho_df[i], 0.0f) * P->alpha_v[i] / (dt * dt); /* rho_df: dt D */
    }
    if (sim->def.solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED && sph_scene_wall_particles(&sim->def))
        sph_solver_wall_extrapolate(sim, k, density ? 1.0f : 0.0f, 0.0f); /* kappa = p / rho_r (solver_walls.c) */
}

/* The share of the last step's kappa this solve starts from: SPH_DFSPH_WARM, or with solver_warm_start = on
 * all of it, times (dt_last / dt)^2 (kappa holds 1/dt^2), and at most sph_solver_warm_bound: a solve that ended
 * short (capped) leaves a kappa that is no solution, and carried from step to step it grew. At 240,000
 * particles (the 3D dam break at 0.01 m, docs/accuracy.md section 8) the density solves capped from step 3,
 * the corner particle's kappa read 5.8, 30 and 52 m^2/s^2 at steps 3 to 5 where the hydrostatic one is 7.8,
 * step 7's warm start read 13.9 % and the watchdog stopped step 8 at 391 m/s; bounded, the run ends its
 * 0.05 s (its solves still cap, as the cold run's do). The bound is on the start only: a solve may raise
 * kappa above it (an impact), so a converged answer does not change. */
static void warm(sph_sim *sim, float *k)
{
    const float last = sim->solver.dt_last;
    float share = SPH_DFSPH_WARM;
    if (sim->def.solver_warm_start == SPH_ON) share = last > 0 ? (last / sim->dt) * (last / sim->dt) : 0.0f;
    const float bound = sph_solver_warm_bound(sim);
    for (uint32_t i = 0; i < sim->n; i++) k[i] = fminf(k[i] * share, bound);
}

static void run(sph_sim *sim)
{
    sph_solver_state *s = &sim->solver;
    sph_particles *P = &sim->P;
    if (!(s->rho_rest > 0)) {
        s->rho_rest = sph_sim_lattice_rest_density(sim);
        s->den_full = sph_sim_lattice_dots(sim);
        s->den_full_v = sph_sim_lattice_dots_pressure(sim);
        sph_solver_wall_table(sim);
    }
    if (!(sim->dt > 0)) { /* the start-up evaluation (dt = 0): nothing moves, no pressure yet */
        for (int d = 0; d < sim->dim; d++)
            for (uint32_t i = 0; i < sim->n; i++) P->acc_df[d][i] = 0.0f;
        return;
    }
    if (s->iteration == 0 && s->phase == 0) { /* the step's first call */
        factors(sim);
        warm(sim, P->kappa_v);
        force(sim, false);
    }
    if (s->phase == 0) {
        const double error = measure(sim, false, NULL);
        if (!sph_solver_done(sim, error, sim->def.divergence_tolerance)) {
            correct(sim, false);
            force(sim, false);
            sim->pass_again = true;
            return;
        }
        s->div_iterations = s->iteration;
        s->divergence_error = error;
        s->iteration = 0;
        s->phase = 1; /* and on to the density in this call */
        warm(sim, P->kappa);
        force(sim, true);
    }
    double over = 0;
    const double error = measure(sim, true, &over);
    /* rising: back to the best kappa kept, an iterate that held the compression if one did (solver.h,
     * sph_solver_least_held) */
    const int least = sph_solver_least_held(sim, error, over, sim->def.solver_tolerance);
    if (least & SPH_SOLVER_KEEP) memcpy(P->kappa_best, P->kappa, sim->n * sizeof *P->kappa);
    if (least & SPH_SOLVER_TAKE_BACK) {
        memcpy(P->kappa, P->kappa_best, sim->n * sizeof *P->kappa);
        force(sim, true);
        if (sph_solver_chebyshev_restart(sim, s->held)) { /* on from the best, plain (solver.h) */
            sim->pass_again = true;
            return;
        }
        sph_solver_stopped(sim, measure(sim, true, &over));
        s->phase = 0;
        return;
    }
    /* the solve also goes on while a pushed particle is below rho_r by more than the tolerance (see the top) */
    const bool done = sph_solver_done(sim, fmax(error, over), sim->def.solver_tolerance);
    s->error = error;
    if (!done) {
        correct(sim, true);
        force(sim, true);
        sim->pass_again = true;
        return;
    }
    s->iterations = s->iteration;
    s->density_error = error;
    s->iteration = 0;
    s->phase = 0;
    s->dt_last = sim->dt;
}

const sph_pass sph_pass_dfsph = {
    .name = "dfsph",
    .summary = "DFSPH: one iteration of the divergence-free or the constant-density solve",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(VEL) | SPH_BIT(RHO) | SPH_MASK_ACCELERATIONS |
             SPH_BIT(KAPPA) | SPH_BIT(KAPPA_V) | SPH_RES_LISTS,
    .writes = SPH_BIT(ALPHA) | SPH_BIT(ALPHA_V) | SPH_BIT(KAPPA) | SPH_BIT(KAPPA_V) | SPH_BIT(KAPPA_BEST) |
              SPH_BIT(KAPPA_PREV) | SPH_BIT(RHO_DF) | SPH_BIT(DV_DF) | SPH_BIT(ACC_DF),
    .group = SPH_GROUP_FORCES,
    .highlight = "dfsph-density",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
