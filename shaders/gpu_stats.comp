// uses: POS VEL MASS RHO P FIXED DST
// Not a pass: the statistics the HUD and --stats show (sph_sim_stats), per
// work group: kinetic, gravitational and internal energy, momentum, the
// fluid's density sum, min and max, the largest |v|^2, the fluid's particle
// count and the largest density of any particle (walls' too). Each group
// reduces its particles in shared memory (a tree: pairwise sums, whose
// rounding grows as log2 of the count) and writes STATS_Q floats' bits at
// dst_[group * STATS_Q]; gpu_stats_sum.comp reduces the groups' rows.
layout(local_size_x = WG) in;
#define STATS_Q 12
shared float s[STATS_Q][WG];

// Internal energy per unit mass stored by the equation of state at rho, as
// eos_energy in src/core/sph_sim.c. Near rho0 both forms cancel to O(z^2)
// (z = rho / rho0 - 1), which float cannot resolve from the closed form:
// there its Taylor series is summed instead.
float eos_energy(float rho)
{
    if (CLAMP_NEG != 0 && rho < EOS_RHO0) return 0.0;
    float z = (rho - EOS_RHO0) / EOS_RHO0;
#if EOS_TAIT
    // B / rho0 ((x^(g-1) - 1) / (g-1) + 1/x - 1), x = 1 + z
    float a = GAMMA - 1.0;
    if (abs(z) < 0.1) {
        float c = 1.0, zn = z, sum = 0.0; // c: binomial(a, n) / a
        for (int n = 1; n < 10; n++) {
            if (n >= 2) sum += (c + ((n & 1) == 0 ? 1.0 : -1.0)) * zn;
            c *= (a - float(n)) / float(n + 1);
            zn *= z;
        }
        return TAIT_B / EOS_RHO0 * sum;
    }
    float x = 1.0 + z;
    return TAIT_B / EOS_RHO0 * ((pow(x, a) - 1.0) / a + 1.0 / x - 1.0);
#else
    // k (log x + 1/x - 1) = k sum over n >= 2 of (-1)^n (n - 1) / n z^n
    if (abs(z) < 0.1) {
        float zn = z * z, sum = 0.0;
        for (int n = 2; n < 10; n++) {
            sum += ((n & 1) == 0 ? 1.0 : -1.0) * float(n - 1) / float(n) * zn;
            zn *= z;
        }
        return STIFF * sum;
    }
    return STIFF * (log(1.0 + z) + 1.0 / (1.0 + z) - 1.0);
#endif
}

void main()
{
    uint i = gid(), l = gl_LocalInvocationID.x;
    float q[STATS_Q];
    for (int k = 0; k < STATS_Q; k++) q[k] = 0.0;
    q[7] = uintBitsToFloat(0x7F800000u);  // rho min: +inf
    q[8] = -uintBitsToFloat(0x7F800000u); // rho max: -inf
    q[11] = q[8];
    if (i < N) {
        bool wall = false;
#if HAS_FIXED
        wall = fixed_[i] != 0.0;
#endif
#if HAS_RHO
        q[11] = rho_[i];
#endif
        if (!wall) {
            float m = mass_[i], v2 = 0.0;
            for (int d = 0; d < DIM; d++) {
                float v = vel_[uint(d) * N + i];
                v2 += v * v;
                q[3 + d] = m * v;
#if HAS_GRAVITY
                q[1] -= m * GRAVITY[d] * (pos_[uint(d) * N + i] - DOM_MIN[d]);
#endif
            }
            q[0] = 0.5 * m * v2;
            q[9] = v2;
            q[10] = 1.0;
#if HAS_RHO
            float r = rho_[i];
#if HAS_P
            if (r > 0.0) q[2] = m * eos_energy(r);
#endif
            q[6] = r;
            q[7] = r;
            q[8] = r;
#endif
        }
    }
    for (int k = 0; k < STATS_Q; k++) s[k][l] = q[k];
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off) {
            for (int k = 0; k < STATS_Q; k++) {
                float a = s[k][l], b = s[k][l + off];
                s[k][l] = k == 7 ? min(a, b) : (k == 8 || k == 9 || k == 11) ? max(a, b) : a + b;
            }
        }
        barrier();
    }
    if (l < uint(STATS_Q)) dst_[group_index() * uint(STATS_Q) + l] = floatBitsToUint(s[l][0]);
}
