// uses: RHO P PRHO2
// Pass pressure (src/passes/pressure.c): the equation of state, p / rho^2.
layout(local_size_x = WG) in;
void main()
{
    uint i = gid();
    if (i >= N) return;
    float rho = rho_[i], p;
#if EOS_TAIT
    p = TAIT_B * (pow(rho * (1.0 / EOS_RHO0), GAMMA) - 1.0);
#else
    p = STIFF * (rho - EOS_RHO0);
#endif
#if CLAMP_NEG
    p = max(0.0, p);
#endif
    p_[i] = p;
    p_rho2_[i] = p / (rho * rho);
}
