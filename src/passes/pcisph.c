/* Pass: PCISPH, predictive-corrective incompressible SPH (Solenthaler &
 * Pajarola 2009, Algorithm 1 and eq. 8), one iteration per call.
 *
 * With the other forces known (gravity is in v, viscosity and cohesion in
 * their fields), each iteration:
 *   1. pressure acceleration a_i = -(1/rho_r^2) sum_j m_j (p_i + p_j) grad W_ij (at the predicted positions of
 *      the step, x + dt v), walls pushing back with -(p_i / rho_r) grad(walls' share) (solver.h);
 *   2. predicted positions x*_i = x_i + dt v_i + dt^2 (a_i + the other accelerations), clamped into the box
 *      as the walls pass will: where the step will put the particle with this pressure;
 *   3. predicted density rho*_i = sum_j m_j W(x*_i - x*_j) + rho_r (walls' share at x*_i), and the error
 *      max_i (rho*_i - rho_r) / rho_r over the fluid;
 *   4. if the error is above [physics] solver_tolerance (and the iteration cap is not reached):
 *      p_i += delta (rho*_i - rho_r), clamped at 0 with negative_pressure = clamp, and the pass asks to
 *      be called again (sim->pass_again): stepping pass by pass shows each iteration.
 * The acceleration written by the last iteration is the one whose density
 * was measured, so the step ends with that density error.
 * A solve whose error rises above twice the least it has reached plus the
 * tolerance is diverging: it takes back the pressure of that least
 * (p_pci_best), ends the step there (counted in `stopped`) and leaves the
 * next step to go on (solver.h, sph_solver_least).
 * On the bench's 3D dam break (50,688 particles, cold, h = 2 s, dt = 2 ms)
 * step 4 fell to 0.118 % by iteration 400, then rose to 36 % and the watchdog
 * stopped the run; it now ends at 0.118 % (docs/accuracy.md, section 8).
 * Wall particles (wall_model = particles, obstacles) are neighbours like the
 * fluid's in the sums, at their fixed places, with p = 0: in the pair term
 * -(m_j / rho_r^2) (p_i + p_j) grad W they push back with p_i alone, as the
 * volume model's walls do with -(p_i / rho_r) grad(share) (the energy's form;
 * Akinci et al. 2012's boundary force, eq. 10, has the same single term).
 * Their own pressure, prediction and error are not solved for. With
 * solver_wall_pressure = extrapolated they take the fluid's pressure after
 * each correction (solver_walls.c), and the pair term is the interior's.
 * rho_r is the density of the lattice at rest (solver.h); the forces divide
 * by it, not by each particle's density, as delta's derivation assumes (eq. 8).
 *
 * delta: with p_j = p_i = p~ around a particle whose neighbourhood is full,
 * its pressure moves it and its neighbours by dt^2 a, which changes its
 * density by -dt^2 2 m^2 / rho_r^2 p~ ((sum grad W) . (sum grad W) + sum grad W . grad W); setting that to
 * -(rho* - rho_r) gives p~ = delta (rho* - rho_r) with
 *   delta = rho_r^2 / (2 dt^2 m^2 S),  S = (sum_j grad W^rho_ij) . (sum_j grad W^p_ij) + sum_j grad W^rho_ij . grad W^p_ij
 * over the finest block's lattice (Solenthaler & Pajarola's beta = 2 (dt m / rho0)^2, eq. 8), with this
 * scene's two kernels: the density kernel's gradient moves the density, the pressure kernel's the particles.
 * pcisph_local_delta = on: delta_i from particle i's own neighbourhood at
 * the step's predicted positions, S_i = G^rho_i . G^p_i + sum_j grad W^rho_ij . grad W^p_ij with
 * G_i = sum_j grad W_ij + (rho_r / m) grad(walls' share), as DFSPH's alpha (Bender & Koschier 2017, eq. 12) and
 * IISPH's a_ii (Ihmsen et al. 2014) are per particle; the term G^rho . G^p only where positive (beside a wall
 * the two kernels' sums can point apart, and S_i fell towards 0 as DFSPH's denominator did, dfsph.c). With the
 * prototype's delta a particle in a corner of the box (7 neighbours of 26 in 3D at h = 2 s) is corrected at
 * 42 % of its own rate (its own delta is 2.37 times the prototype's): on the 3D bench scene the bottom
 * corners held each step's largest error for hundreds of iterations (docs/accuracy.md, section 8).
 * Each step starts from p = 0, or with solver_warm_start = on from the
 * pressure the last step ended with (a warm start). That blew up the 2D dam
 * break of tests/test_solvers.c at dt = 2 ms when an earlier version of this
 * pass first tried it; it no longer does, and it cuts the iterations 3 to 4
 * times, but ends that dam break with 9 to 11 % more kinetic energy than the
 * converged answer (docs/accuracy.md, section 8): off by default. */
#include "solver.h"

#include <stdio.h>
#include <string.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (def->pressure_solver != SPH_PSOLVER_PCISPH) return "pressure_solver is not pcisph";
    return (def->effects & SPH_EFFECT(PRESSURE)) ? NULL : "effects do not list pressure";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    char cheb[96] = "";
    if (def->solver_chebyshev > 0.0f)
        snprintf(cheb, sizeof cheb, ", Chebyshev-accelerated from the 10th correction (solver_chebyshev = %g)",
                 def->solver_chebyshev);
    snprintf(out, (size_t)n,
             "predict-correct until the largest (rho - rho_rest) / rho_rest <= %g (at most %d iterations%s%s%s)%s",
             def->solver_tolerance, def->solver_max_iterations,
             def->solver_warm_start == SPH_ON ? ", warm start" : "",
             def->pcisph_local_delta == SPH_ON ? ", delta per particle" : "", cheb,
             sph_scene_wall_volume(def)     ? ", walls count and push back"
             : !sph_scene_wall_particles(def) ? ""
             : def->solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED
                 ? ", wall particles count and hold the fluid's pressure (extrapolated)"
                 : ", wall particles count and push back with the fluid particle's own pressure");
}

/* delta at dt = 1 s, on the finest block's full lattice (see the top). */
static float delta_unit(const sph_sim *sim, float rho_r)
{
    const sph_scene_def *def = &sim->def;
    float s = 0;
    for (int b = 0; b < def->n_blocks; b++)
        if (s == 0 || def->blocks[b].spacing < s) s = def->blocks[b].spacing;
    if (!(s > 0)) return 0.0f;
    const int dim = sim->dim, r = (int)ceilf(def->h / s);
    const double m = def->rest_density * (dim == 3 ? (double)s * s * s : (double)s * s);
    double sum_r[3] = {0, 0, 0}, sum_p[3] = {0, 0, 0}, dots = 0;
    for (int z = dim == 3 ? -r : 0; z <= (dim == 3 ? r : 0); z++)
        for (int y = -r; y <= r; y++)
            for (int x = -r; x <= r; x++) {
                float dx[3] = {-(float)x * s, -(float)y * s, -(float)z * s}; /* x_i - x_j, i at the origin */
                float d = sqrtf(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
                if (d == 0.0f || d >= def->h) continue;
                double gr = sph_kernel_dw(&sim->k_density, d) / d, gp = sph_kernel_dw(&sim->k_pressure, d) / d;
                for (int a = 0; a < 3; a++) {
                    sum_r[a] += gr * dx[a];
                    sum_p[a] += gp * dx[a];
                    dots += gr * gp * dx[a] * dx[a];
                }
            }
    double S = dots + sum_r[0] * sum_p[0] + sum_r[1] * sum_p[1] + sum_r[2] * sum_p[2];
    return S > 0 ? (float)((double)rho_r * rho_r / (2.0 * m * m * S)) : 0.0f;
}

/* delta_i at dt = 1 s from particle i's own neighbourhood at pred (pcisph_local_delta = on, see the top). */
static void local_deltas(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float rho_r = sim->solver.rho_rest;
    const bool walls = sph_sim_wall_volume(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) { /* a wall particle holds no pressure (see the top) */
            P->delta_pci[i] = sim->solver.delta;
            continue;
        }
        /* in mass-weighted form: m^2 S_i, so that delta_i = rho_r^2 / (2 m^2 S_i) */
        float gr[3] = {0, 0, 0}, gp[3] = {0, 0, 0}, dots = 0;
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; d++) {
                dx[d] = sph_solver_dx(sim, P->pred[d][i] - P->pred[d][j], d);
                r2 += dx[d] * dx[d];
            }
            const float r = sqrtf(r2);
            if (!(r > 0.0f)) continue;
            const float fr = P->mass[j] * sph_kernel_dw(&sim->k_density, r) / r;
            const float fp = P->mass[j] * sph_kernel_dw(&sim->k_pressure, r) / r;
            const bool still = sph_is_wall(P, j); /* a wall particle counts, but i's pressure cannot move it */
            for (int d = 0; d < dim; d++) {
                gr[d] += fr * dx[d];
                gp[d] += fp * dx[d];
                if (!still) dots += fr * fp * dx[d] * dx[d];
            }
        }
        if (walls) {
            float g[3];
            sph_solver_walls_pred(sim, i, g);
            for (int d = 0; d < dim; d++) {
                gr[d] += rho_r * g[d];
                gp[d] += rho_r * g[d];
            }
        }
        const float den = dots + fmaxf(gr[0] * gp[0] + gr[1] * gp[1] + gr[2] * gp[2], 0.0f);
        /* no neighbour and no wall: nothing it could push, nothing to correct (its density is its own) */
        P->delta_pci[i] = den > 0.0f ? rho_r * rho_r / (2.0f * den) : sim->solver.delta;
    }
}

/* 1 and 2 above: the pressure acceleration from p_pci, then x_pci. */
static void force(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float dt = sim->dt, inv_r2 = 1.0f / (sim->solver.rho_rest * sim->solver.rho_rest);
    const float inv_r = 1.0f / sim->solver.rho_rest, r_min = SPH_KERNEL_R_MIN * sim->def.h;
    const bool walls = sph_sim_wall_volume(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) { /* wall particles stay where they are */
            for (int d = 0; d < dim; d++) {
                P->acc_pci[d][i] = 0.0f;
                P->x_pci[d][i] = P->pred[d][i];
            }
            continue;
        }
        float a[3] = {0, 0, 0}, other[3];
        const float p_i = P->p_pci[i];
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; d++) {
                dx[d] = sph_solver_dx(sim, P->pred[d][i] - P->pred[d][j], d);
                r2 += dx[d] * dx[d];
            }
            if (r2 < r_min * r_min) { /* coincident: apart along x, as pressure_force.c */
                dx[0] = (uint32_t)i < j ? -r_min : r_min;
                dx[1] = dx[2] = 0.0f;
                r2 = r_min * r_min;
            }
            const float r = sqrtf(r2);
            const float c = P->mass[j] * (p_i + P->p_pci[j]) * inv_r2 * sph_kernel_dw(&sim->k_pressure, r) / r;
            for (int d = 0; d < dim; d++) a[d] -= c * dx[d];
        }
        if (walls) {
            float grad[3];
            sph_solver_walls_pred(sim, i, grad);
            for (int d = 0; d < dim; d++) a[d] -= p_i * inv_r * grad[d];
        }
        sph_solver_other_acc(sim, i, other);
        float x[3] = {0, 0, 0}, c[3];
        for (int d = 0; d < dim; d++) {
            P->acc_pci[d][i] = a[d];
            x[d] = P->pred[d][i] + dt * dt * (a[d] + other[d]);
        }
        sph_solver_clamped(sim, x, c); /* where the walls pass will put it (solver.h) */
        for (int d = 0; d < dim; d++) P->x_pci[d][i] = c[d];
    }
}

/* 3 above: rho_pci at x_pci; returns the largest relative excess over rho_r. */
static double predict(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float rho_r = sim->solver.rho_rest;
    const bool walls = sph_sim_wall_volume(sim);
    float worst = 0.0f;
#pragma omp parallel for schedule(static) reduction(max : worst) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) { /* not the fluid's: no error of its own */
            P->rho_pci[i] = rho_r;
            continue;
        }
        float xi[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) xi[d] = P->x_pci[d][i];
        float rho = P->mass[i] * sph_kernel_w(&sim->k_density, 0.0f);
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float r2 = 0;
            for (int d = 0; d < dim; d++) {
                const float dx = sph_solver_dx(sim, xi[d] - P->x_pci[d][j], d);
                r2 += dx * dx;
            }
            rho += P->mass[j] * sph_kernel_w(&sim->k_density, sqrtf(r2));
        }
        if (walls) rho += rho_r * sph_solver_walls(sim, xi, NULL);
        P->rho_pci[i] = rho;
        worst = fmaxf(worst, (rho - rho_r) / rho_r);
    }
    return worst;
}

/* 4 above: p += delta (rho* - rho_r). */
static void correct(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n;
    /* solver_chebyshev: the blend with the iterate before and w times the step (solver.h) */
    float *restrict last = sim->def.solver_chebyshev > 0.0f ? P->p_pci_prev : NULL;
    const float w = last ? sph_solver_chebyshev_weight(sim) : 1.0f;
    /* as the GL host's u_value, bit for bit (w = 1: delta / dt^2 and dt^2) */
    const float delta = w * (sim->solver.delta / (sim->dt * sim->dt)), step2 = sim->dt * sim->dt / w;
    const float rho_r = sim->solver.rho_rest;
    const float floor = sim->def.negative_pressure == SPH_NEGP_CLAMP ? 0.0f : -INFINITY;
    const float *restrict local = sim->def.pcisph_local_delta == SPH_ON ? P->delta_pci : NULL;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) continue; /* p stays 0: the walls push with p_i alone (see the top) */
        float b = P->p_pci[i];
        if (last) {
            b = sph_solver_chebyshev_blend(w, P->p_pci[i], last[i]);
            last[i] = P->p_pci[i];
        }
        const float d_i = local ? local[i] / step2 : delta;
        P->p_pci[i] = fmaxf(floor, b + d_i * (P->rho_pci[i] - rho_r));
    }
    if (sim->def.solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED && sph_scene_wall_particles(&sim->def))
        sph_solver_wall_extrapolate(sim, P->p_pci, rho_r, floor); /* or from the fluid's (solver_walls.c) */
}

static void run(sph_sim *sim)
{
    sph_solver_state *s = &sim->solver;
    if (!(s->rho_rest > 0)) {
        s->rho_rest = sph_sim_lattice_rest_density(sim);
        sph_solver_wall_table(sim);
        s->delta = delta_unit(sim, s->rho_rest);
    }
    sph_particles *P = &sim->P;
    if (!(sim->dt > 0)) { /* the start-up evaluation (dt = 0): nothing moves, no pressure yet */
        for (int d = 0; d < sim->dim; d++)
            for (uint32_t i = 0; i < sim->n; i++) {
                P->acc_pci[d][i] = 0.0f;
                P->x_pci[d][i] = P->pred[d][i];
            }
        return;
    }
    if (s->iteration == 0) { /* the step's first call: from p = 0 or the last step's p (see the top) */
        if (!(sim->def.solver_warm_start == SPH_ON && s->dt_last > 0))
            for (uint32_t i = 0; i < sim->n; i++) P->p_pci[i] = 0.0f;
        if (sim->def.pcisph_local_delta == SPH_ON)
            local_deltas(sim);
        else /* the one delta, so that the field (the inspector's row, a colour) says which delta acts */
            for (uint32_t i = 0; i < sim->n; i++) P->delta_pci[i] = s->delta;
        force(sim);
    }
    const double error = predict(sim);
    const int least = sph_solver_least(sim, error, sim->def.solver_tolerance);
    if (least == SPH_SOLVER_KEEP) memcpy(P->p_pci_best, P->p_pci, sim->n * sizeof *P->p_pci);
    if (least == SPH_SOLVER_TAKE_BACK) { /* rising: back to the least (see the top) */
        memcpy(P->p_pci, P->p_pci_best, sim->n * sizeof *P->p_pci);
        force(sim);
        if (sph_solver_chebyshev_restart(sim, false)) { /* on from the least, plain (solver.h) */
            sim->pass_again = true;
            return;
        }
        sph_solver_stopped(sim, predict(sim));
        return;
    }
    if (sph_solver_done(sim, error, sim->def.solver_tolerance)) {
        s->iterations = s->iteration;
        s->density_error = error;
        s->iteration = 0;
        s->dt_last = sim->dt;
        return;
    }
    correct(sim);
    force(sim);
    sim->pass_again = true;
}

const sph_pass sph_pass_pcisph = {
    .name = "pcisph",
    .summary = "PCISPH: one predict-correct iteration of the pressure",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(VEL) | SPH_MASK_ACCELERATIONS | SPH_BIT(P_PCI) | SPH_RES_LISTS,
    .writes = SPH_BIT(P_PCI) | SPH_BIT(P_PCI_BEST) | SPH_BIT(P_PCI_PREV) | SPH_BIT(DELTA_PCI) | SPH_BIT(X_PCI) |
              SPH_BIT(RHO_PCI) | SPH_BIT(ACC_PCI),
    .group = SPH_GROUP_FORCES,
    .highlight = "pcisph-density",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
