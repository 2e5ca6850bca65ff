// uses: PRED VEL MASS RHO ALPHA ALPHA_V KAPPA KAPPA_V KAPPA_BEST RHO_DF DV_DF ENTRIES START WALL REDUCE FIXED
// Pass dfsph (src/passes/dfsph.c): one stage of an iteration per dispatch,
// u_count says which (run_dfsph in src/gpu/gpu_passes.c calls them in the
// CPU pass's order); every walk is over the pairs within h at pred (the
// CPU's lists). The force is gpu_dfsph_force.comp, a program of its own:
// with every acceleration field this one would declare more than the 16
// storage blocks a shader may have (with wall particles, FIXED makes this one's 16).
//   0 factors: alpha_i = rho_r / max(G^rho_i . G^p_i + sum_j m_j^2 grad W^rho_ij . grad W^p_ij, DEN_FULL), walls in G
//     negative where that sum is not above ALPHA_MIN (src/passes/dfsph.c says why), and the divergence
//     solve's alpha_v_i = rho_r / max(|G^p_i|^2 + sum_j m_j^2 |grad W^p_ij|^2, DEN_FULL_V)
//   1, 2 warm start: kappa_v (1) or kappa (2) *= u_value
//   3 measure the divergence: rho_df = dt D rho/Dt of v + dv where rho >= rho_r (else 0), error rho_df / rho_r,
//     with the pressure kernel's gradient, the push's (dfsph.c says why)
//   4 measure the density: rho_df = sum_j m_j W^rho(x*_i - x*_j) + rho_r (walls' share at x*_i) at the
//     positions the step will reach, x* = pred + dt dv clamped into the box, error (rho_df - rho_r) / rho_r
//     4 puts the largest error, at least 0, into reduce_[2], and the largest (rho_r - rho_df) / rho_r of a
//     pushed particle (kappa + kappa_v > 0), at least 0, into reduce_[3] (the stopping test, dfsph.c): per work
//     group in shared memory, then one
//     atomicMax on the float's bits (non-negative floats order as their bits do; a NaN counts as 0, as fmaxf
//     leaves it out on the CPU); 3 the sum of max(error, 0), in units of 2^-28 N_FLUID (so that the host reads
//     the mean over the N_FLUID fluid particles as the count times 2^-28): per work group in shared memory, then
//     one atomicAdd
//   5 correct: kappa_v += max(dt D, 0) alpha_v / dt^2, u_value = dt^2
//   6 correct: kappa = max(kappa + OMEGA (rho_df - rho_r) |alpha| / dt^2, -kappa_v) (a relaxed Jacobi step,
//     kappa_v + kappa kept >= 0; src/passes/dfsph.c says why)
//   7 keep:      kappa_best = kappa (the density solve's least error so far)
//   8 take back: kappa = kappa_best (the error rose above twice that least plus the tolerance)
// Wall particles (wall_model = particles, obstacles; FIXED) are neighbours at their fixed places with
// kappa = kappa_v = 0, as in dfsph.c: alpha = alpha_v = 0 (0), they add to G_i but not to the sums over the
// neighbours i's push moves (0), their x* is pred + dt dv unclamped (beyond the box, where they stay), and
// they count in neither solve's error (3: rho_df = 0; 4: rho_df = rho_r) nor in the mean (N_FLUID). With
// solver_wall_pressure = extrapolated the host gives them the fluid's kappa and kappa_v after each correction
// (5, 6: gpu_wall_extrapolate.comp), which the force then reads.
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_dt;
uniform float u_value;
uniform float u_bound; // [m^2/s^2] the most a warm start carries (1, 2: dfsph.c, warm)
shared uint s_err[WG];
shared float s_sum[WG];
vec3 gr, gp, g1, vi, xs; // g1: G^p with the walls once (dfsph.c, factors)
float dots, dots_p, sum;
const float OMEGA = 0.5; // SPH_DFSPH_OMEGA in src/passes/dfsph.c

bool is_wall(uint i)
{
#if HAS_FIXED
    return fixed_[i] != 0.0;
#else
    return false;
#endif
}

float grad_factor(int kind, float s, float r2)
{
    float r = sqrt(r2);
    return r > 0.0 ? kernel_dw(kind, s, r) / r : 0.0;
}

// v* - v + (v in the divergence solve)
vec3 velocity(uint j)
{
    vec3 v = vec3(0.0);
    for (int d = 0; d < DIM; d++) v[d] = dv_df_[uint(d) * N + j] + (u_count == 3u ? vel_[uint(d) * N + j] : 0.0);
    return v;
}

// x* = pred + dt dv, clamped into the box as the walls pass will (sph_solver_clamped in src/passes/solver.h)
vec3 reached(uint j)
{
    vec3 x = vec3(0.0);
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + j;
        precise float y = pred_[k] + u_dt * dv_df_[k];
#if HAS_WALLS
        if (PER[d] <= 0.0 && !is_wall(j)) y = min(max(y, DOM_MIN[d]), DOM_MAX[d]);
#endif
        x[d] = y;
    }
    return x;
}

void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (u_count == 4u) {
        vec3 xj = reached(j);
        precise float q2 = 0.0;
        for (int d = 0; d < DIM; d++) {
            float e = xs[d] - xj[d];
            q2 += e * e;
        }
        sum += mass_[j] * kernel_w(KD, SIG_D, sqrt(q2));
    } else if (u_count == 0u) {
        float fr = mass_[j] * grad_factor(KD, SIG_D, r2), fp = mass_[j] * grad_factor(KP, SIG_P, r2);
        bool still = is_wall(j); // a wall particle counts, but i's push cannot move it
        float twice = still ? WALL_PUSH : 1.0; // twice with extrapolated wall pressure (dfsph.c, factors)
        for (int d = 0; d < DIM; d++) {
            gr[d] += fr * dx[d];
            gp[d] += twice * fp * dx[d];
            g1[d] += fp * dx[d];
            if (still) continue;
            dots += fr * fp * dx[d] * dx[d];
            dots_p += fp * fp * dx[d] * dx[d];
        }
    } else {
        float f = mass_[j] * grad_factor(KP, SIG_P, r2);
        vec3 vj = velocity(j);
        for (int d = 0; d < DIM; d++) sum += f * (vi[d] - vj[d]) * dx[d];
    }
}
#include_walk

void main()
{
    uint i = gid(), l = gl_LocalInvocationID.x, u = u_count;
    uint err = 0u, over = 0u;
    if (i < N && is_wall(i)) { // no kappa, no error of its own (see the top)
        if (u == 0u) {
            alpha_[i] = 0.0;
            alpha_v_[i] = 0.0;
        } else if (u == 3u) {
            rho_df_[i] = 0.0;
        } else if (u == 4u) {
            rho_df_[i] = RHO_R;
        } else if (u == 1u) {
            kappa_v_[i] = min(kappa_v_[i] * u_value, u_bound);
        } else if (u == 2u) {
            kappa_[i] = min(kappa_[i] * u_value, u_bound);
        } else if (u == 7u) {
            kappa_best_[i] = kappa_[i];
        } else if (u == 8u) {
            kappa_[i] = kappa_best_[i];
        }
    } else if (i < N) {
        vec3 xi = PRED3(i), g = vec3(0.0);
        float share = 0.0;
#if WALL_VOLUME
        if (u == 0u || u == 3u) share = solver_walls(xi, g);
#endif
        if (u == 0u) {
            gr = vec3(0.0);
            gp = vec3(0.0);
            g1 = vec3(0.0);
            dots = 0.0;
            dots_p = 0.0;
            sph_walk(i, xi);
#if WALL_VOLUME
            for (int d = 0; d < DIM; d++) {
                gr[d] += RHO_R * g[d];
                gp[d] += RHO_R * g[d];
                g1[d] += RHO_R * g[d];
            }
#endif
            precise float raw = dots + gr.x * gp.x + gr.y * gp.y + gr.z * gp.z;
            alpha_[i] = (raw > ALPHA_MIN ? 1.0 : -1.0) * RHO_R / max(raw, DEN_FULL);
            precise float raw_v = dots_p + g1.x * gp.x + g1.y * gp.y + g1.z * gp.z; // the walls once in g1 (dfsph.c)
            alpha_v_[i] = RHO_R / max(raw_v, DEN_FULL_V);
        } else if (u == 1u) {
            kappa_v_[i] = min(kappa_v_[i] * u_value, u_bound);
        } else if (u == 2u) {
            kappa_[i] = min(kappa_[i] * u_value, u_bound);
        } else if (u == 4u) {
            xs = reached(i);
            sum = mass_[i] * kernel_w(KD, SIG_D, 0.0);
            sph_walk(i, xi);
#if WALL_VOLUME
            vec3 gs;
            sum += RHO_R * solver_walls(xs, gs);
#endif
            rho_df_[i] = sum;
            float e = (sum - RHO_R) / RHO_R;
            err = e > 0.0 ? floatBitsToUint(e) : 0u;
            over = kappa_[i] + kappa_v_[i] > 0.0 && e < 0.0 ? floatBitsToUint(-e) : 0u; // a pushed particle below rho_r
        } else if (u == 3u) {
            vi = velocity(i);
            sum = 0.0;
            sph_walk(i, xi);
            float rho = rho_[i];
#if WALL_VOLUME
            for (int d = 0; d < DIM; d++) sum += RHO_R * g[d] * vi[d];
            // the density pass counted the walls as the volume model does: count them as the solvers do
            vec3 gh;
            rho += RHO_R * share - RHO0 * wall_hidden(xi, gh);
#endif
            float r = rho >= RHO_R ? u_dt * sum : 0.0;
            rho_df_[i] = r;
            float e = r / RHO_R;
            err = e > 0.0 ? floatBitsToUint(e) : 0u;
        } else if (u == 6u) {
            precise float k = kappa_[i] + OMEGA * (rho_df_[i] - RHO_R) * abs(alpha_[i]) / u_value;
            kappa_[i] = max(k, -kappa_v_[i]);
        } else if (u == 7u) {
            kappa_best_[i] = kappa_[i];
        } else if (u == 8u) {
            kappa_[i] = kappa_best_[i];
        } else {
            precise float add = max(rho_df_[i], 0.0) * alpha_v_[i] / u_value; // rho_df: dt D
            kappa_v_[i] += add;
        }
    }
    if (u != 3u && u != 4u) return; // the same for the whole dispatch: no barrier skipped by part of a group
    if (u == 3u) {
        s_sum[l] = uintBitsToFloat(err);
        barrier();
        for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
            if (l < off) s_sum[l] += s_sum[l + off];
            barrier();
        }
        if (l == 0u) atomicAdd(reduce_[2], uint(min(round(s_sum[0] * (268435456.0 / float(N_FLUID))), 4294967040.0)));
        return;
    }
    s_err[l] = err;
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off) s_err[l] = max(s_err[l], s_err[l + off]);
        barrier();
    }
    if (l == 0u) atomicMax(reduce_[2], s_err[0]);
    barrier();
    s_err[l] = over;
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off) s_err[l] = max(s_err[l], s_err[l + off]);
        barrier();
    }
    if (l == 0u) atomicMax(reduce_[3], s_err[0]);
}
