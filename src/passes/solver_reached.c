/* The compression of the positions a step reached (not a pass): what the
 * study's compression metric and the solver tests measure. The density
 * pass's rho is summed at the step's predicted x + dt v, before any
 * pressure acts: for the iterated solvers that is the compression the next
 * solve starts from, 0.5 to 0.8 % in lesson 11's dam break at a 0.1 %
 * tolerance, not the one the fluid reaches (docs/accuracy.md, section 8).
 * Summed here at x after integration and the walls, over the step's lists
 * (made at x + dt v: a pair that came within h during the step is missed,
 * docs/accuracy.md says how often), each pressure model against the density
 * it holds: its reference (rho0, or rho_rest with eos_rest = lattice) with
 * the volume model's walls for the equation of state,
 * rho_rest with the solvers' walls (solver.h) for PCISPH and DFSPH. */
#include "solver.h"

/* solver: against rho_rest with the solvers' walls, else against the eos's reference with
 * the volume model's. */
static void compression(const sph_sim *sim, bool solver, double *largest, double *mean)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const double held = solver ? sim->solver.rho_rest : sim->eos_rho0; /* [kg/m^dim] the eos's: eos_rest */
    const bool walls = sph_sim_wall_volume(sim);
    double mx = -INFINITY, sum = 0;
    long cnt = 0;
#pragma omp parallel for schedule(static) reduction(max : mx) reduction(+ : sum, cnt) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) continue;
        float xi[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) xi[d] = P->pos[d][i];
        double rho = P->mass[i] * sph_kernel_w(&sim->k_density, 0.0f);
        const sph_nbr_row row = S->nbr_start ? sph_nbr_row_of(S, (uint32_t)i) : (sph_nbr_row){0};
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t j = sph_nbr_at(&row, e);
            float r2 = 0;
            for (int d = 0; d < dim; d++) {
                const float dx = sph_solver_dx(sim, xi[d] - P->pos[d][j], d);
                r2 += dx * dx;
            }
            if (r2 < sim->def.h * sim->def.h) rho += P->mass[j] * sph_kernel_w(&sim->k_density, sqrtf(r2));
        }
        if (walls)
            rho += solver ? held * sph_solver_walls(sim, xi, NULL)
                          : held * sph_wall_hidden_at(sim, &sim->k_density, xi, NULL);
        const double e = rho / held - 1.0;
        mx = fmax(mx, e);
        sum += fmax(e, 0.0);
        cnt++;
    }
    *largest = cnt ? mx : 0.0;
    *mean = cnt ? sum / (double)cnt : 0.0;
}

void sph_sim_compression(const sph_sim *sim, double *largest, double *mean)
{
    compression(sim, sim->def.pressure_solver != SPH_PSOLVER_EOS && sim->solver.rho_rest > 0, largest, mean);
}

void sph_sim_compression_lattice(sph_sim *sim, double *largest, double *mean)
{
    if (!(sim->solver.rho_rest > 0)) { /* no solver made them: what the solvers would hold */
        sim->solver.rho_rest = sph_sim_lattice_rest_density(sim);
        sph_solver_wall_table(sim);
    }
    compression(sim, true, largest, mean);
}
