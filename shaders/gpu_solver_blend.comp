// uses: FIXED SRC DST
// The pressure solvers' Chebyshev blend ([physics] solver_chebyshev > 0; src/passes/solver.h,
// sph_solver_chebyshev_blend): before each correction of the density solve (run_pcisph, run_dfsph in
// src/gpu/gpu_passes.c) the solver's pressure q (DST: PCISPH's p_pci, DFSPH's kappa) becomes
// w q + (1 - w) q_last (SRC: p_pci_prev or kappa_prev, the iterate before), q itself where w = 1, and q_last
// becomes q; u_value = w. The correction stage then steps from it by w dq. Wall particles keep theirs, as the
// CPU's correct() skips them.
layout(local_size_x = WG) in;
uniform float u_value;

void main()
{
    uint i = gid();
    if (i >= N) return;
#if HAS_FIXED
    if (fixed_[i] != 0.0) return;
#endif
    float q = uintBitsToFloat(dst_[i]), last = uintBitsToFloat(src_[i]);
    precise float b = u_value == 1.0 ? q : u_value * q + (1.0 - u_value) * last;
    dst_[i] = floatBitsToUint(b);
    src_[i] = floatBitsToUint(q);
}
