// uses: PRED MASS P_PCI X_PCI ACC_PCI ACCELERATIONS ENTRIES START WALL FIXED
// Pass pcisph's force (src/passes/pcisph.c, force()), a program of its own
// beside gpu_pcisph.comp, as gpu_dfsph_force.comp is DFSPH's: with every
// acceleration field and the wall particles' FIXED that one would declare more
// than the 16 storage blocks a shader may have. u_count says which stage:
//   0 start:   p = 0, a = 0, x* = pred + dt^2 (other accelerations); with solver_warm_start = on (and a last
//              step) the host calls 1 instead, from the p the last step ended with
//   1 force:   a_i = -(1/rho_r^2) sum_j m_j (p_i + p_j) grad W^p_ij at pred, walls push back; x* as above plus a
//   2 the start-up evaluation (dt = 0): a = 0, x* = pred
// Wall particles (FIXED) keep a = 0 and x* = pred, and p = 0: as neighbours they push back with p_i alone
// (solver_wall_pressure = extrapolated: with p_i + their p, extrapolated by gpu_wall_extrapolate.comp).
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_dt;
vec3 acc;
float p_i;

void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (r2 < R_MIN * R_MIN) { // coincident: apart along x, as pressure_force.c
        dx = vec3(i < j ? -R_MIN : R_MIN, 0.0, 0.0);
        r2 = R_MIN * R_MIN;
    }
    float r = sqrt(r2);
    float c = mass_[j] * (p_i + p_pci_[j]) * INV_RHO_R2 * kernel_dw(KP, SIG_P, r) / r;
    for (int d = 0; d < DIM; d++) acc[d] -= c * dx[d];
}
#include_walk

// x* = pred + dt^2 (a + the other accelerations), clamped into the box as
// the walls pass will (sph_solver_clamped in src/passes/solver.h), and a stored
void put_prediction(uint i, vec3 a)
{
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        acc_pci_[k] = a[d];
        precise float x = pred_[k] + u_dt * u_dt * (a[d] + ACC_OTHER(k));
#if HAS_WALLS
        if (PER[d] <= 0.0) x = min(max(x, DOM_MIN[d]), DOM_MAX[d]);
#endif
        x_pci_[k] = x;
    }
}

void main()
{
    uint i = gid();
    if (i >= N) return;
    bool wall = false;
#if HAS_FIXED
    wall = fixed_[i] != 0.0;
#endif
    if (u_count == 0u) p_pci_[i] = 0.0;
    if (u_count == 2u || wall) { // held still (pcisph.c), or nothing moves yet
        for (int d = 0; d < DIM; d++) {
            acc_pci_[uint(d) * N + i] = 0.0;
            x_pci_[uint(d) * N + i] = pred_[uint(d) * N + i];
        }
    } else if (u_count == 0u) {
        put_prediction(i, vec3(0.0));
    } else {
        acc = vec3(0.0);
        p_i = p_pci_[i];
        vec3 xi = PRED3(i);
        sph_walk(i, xi);
#if WALL_VOLUME
        vec3 grad;
        solver_walls(xi, grad);
        for (int d = 0; d < DIM; d++) acc[d] -= p_i * INV_RHO_R * grad[d];
#endif
        put_prediction(i, acc);
    }
}
