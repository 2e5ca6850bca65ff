// uses: PRED MASS P_PCI P_PCI_BEST X_PCI RHO_PCI DELTA_PCI ENTRIES START WALL REDUCE FIXED
// Pass pcisph (src/passes/pcisph.c): one stage of a predict-correct
// iteration per dispatch, u_count says which (the host, run_pcisph in
// src/gpu/gpu_passes.c, calls them in the CPU pass's order). The pressure
// force and x* (stages 0, 1 and 4 below) are gpu_pcisph_force.comp, a program
// of its own: with every acceleration field this one would declare more than
// the 16 storage blocks a shader may have.
//   0 start, 1 force: gpu_pcisph_force.comp
//   2 predict: rho*_i = sum_j m_j W^rho(x*_i - x*_j) + rho_r (walls' share at x*_i), over the pairs within h at
//              pred (the CPU's lists); the largest (rho* - rho_r) / rho_r, at least 0, into reduce_[2] (per work
//              group in shared memory, then one atomicMax on the float's bits: non-negative floats order as their
//              bits do; a NaN counts as 0, as fmaxf leaves it out on the CPU)
//   3 correct: p += delta (rho* - rho_r), u_value = delta / dt^2, clamped at 0 with negative_pressure = clamp
//   4 the start-up evaluation (dt = 0): gpu_pcisph_force.comp
//   5 pcisph_local_delta = on: delta_i at dt = 1 s from i's neighbourhood at pred, rho_r^2 / (2 S_i) with
//     S_i = max(G^rho_i . G^p_i, 0) + sum_j m_j^2 grad W^rho_ij . grad W^p_ij, G_i = sum_j m_j grad W_ij + rho_r
//     grad(walls' share); u_value = the full lattice's delta, kept where S_i is 0 (local_deltas in pcisph.c)
//   6 correct with those: p += delta_i / dt^2 (rho* - rho_r), u_value = dt^2, clamped as 3
//   7 keep:      p_best = p (the solve's least error so far)
//   8 take back: p = p_best (the error rose above twice that least plus the tolerance)
//   9 pcisph_local_delta = off: delta_i = u_value, the full lattice's delta, for every particle (the field says
//     which delta acts, as pcisph.c writes it)
// Wall particles (wall_model = particles, obstacles; FIXED) are neighbours at their fixed places with p = 0, as
// in pcisph.c: they count in G_i but not in the sum over the neighbours i's pressure moves (5), have
// rho* = rho_r and no error of their own (2), and no p (3, 6); with solver_wall_pressure = extrapolated the
// host then gives them the fluid's p (gpu_wall_extrapolate.comp) before the force reads it.
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_dt;
uniform float u_value;
shared uint s_err[WG];
vec3 xs, gr, gp;
float rho, dots;

bool is_wall(uint i)
{
#if HAS_FIXED
    return fixed_[i] != 0.0;
#else
    return false;
#endif
}

void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (u_count == 5u) {
        float r = sqrt(r2);
        if (!(r > 0.0)) return;
        float fr = mass_[j] * kernel_dw(KD, SIG_D, r) / r, fp = mass_[j] * kernel_dw(KP, SIG_P, r) / r;
        bool still = is_wall(j); // a wall particle counts, but i's pressure cannot move it
        for (int d = 0; d < DIM; d++) {
            gr[d] += fr * dx[d];
            gp[d] += fp * dx[d];
            if (!still) dots += fr * fp * dx[d] * dx[d];
        }
    } else {
        precise float q2 = 0.0;
        for (int d = 0; d < DIM; d++) {
            float e = xs[d] - x_pci_[uint(d) * N + j];
            q2 += e * e;
        }
        rho += mass_[j] * kernel_w(KD, SIG_D, sqrt(q2));
    }
}
#include_walk

void main()
{
    uint i = gid(), l = gl_LocalInvocationID.x;
    uint err = 0u;
    if (i < N && is_wall(i)) { // no pressure, no error (see the top)
        if (u_count == 2u) rho_pci_[i] = RHO_R;
        if (u_count == 5u || u_count == 9u) delta_pci_[i] = u_value;
        if (u_count == 7u) p_pci_best_[i] = p_pci_[i];
        if (u_count == 8u) p_pci_[i] = p_pci_best_[i];
    } else if (i < N) {
        if (u_count == 2u) {
            xs = LOAD3(x_pci_, i);
            rho = mass_[i] * kernel_w(KD, SIG_D, 0.0);
            sph_walk(i, PRED3(i));
#if WALL_VOLUME
            vec3 grad;
            rho += RHO_R * solver_walls(xs, grad);
#endif
            rho_pci_[i] = rho;
            float e = (rho - RHO_R) / RHO_R;
            err = e > 0.0 ? floatBitsToUint(e) : 0u;
        } else if (u_count == 5u) {
            gr = vec3(0.0);
            gp = vec3(0.0);
            dots = 0.0;
            vec3 xi = PRED3(i);
            sph_walk(i, xi);
#if WALL_VOLUME
            vec3 g;
            solver_walls(xi, g);
            for (int d = 0; d < DIM; d++) {
                gr[d] += RHO_R * g[d];
                gp[d] += RHO_R * g[d];
            }
#endif
            precise float den = dots + max(gr.x * gp.x + gr.y * gp.y + gr.z * gp.z, 0.0);
            delta_pci_[i] = den > 0.0 ? RHO_R * RHO_R / (2.0 * den) : u_value;
        } else if (u_count == 9u) { // pcisph_local_delta = off: the one delta, in the field as on the CPU
            delta_pci_[i] = u_value;
        } else if (u_count == 7u) {
            p_pci_best_[i] = p_pci_[i];
        } else if (u_count == 8u) {
            p_pci_[i] = p_pci_best_[i];
        } else {
            float d_i = u_count == 6u ? delta_pci_[i] / u_value : u_value;
            precise float p = p_pci_[i] + d_i * (rho_pci_[i] - RHO_R);
#if CLAMP_NEG
            p = max(0.0, p);
#endif
            p_pci_[i] = p;
        }
    }
    if (u_count != 2u) return; // the same for the whole dispatch: no barrier skipped by part of a group
    s_err[l] = err;
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off) s_err[l] = max(s_err[l], s_err[l + off]);
        barrier();
    }
    if (l == 0u) atomicMax(reduce_[2], s_err[0]);
}
