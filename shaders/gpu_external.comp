// uses: POS VEL PRED
// Pass external (src/passes/external.c): v += g dt, then pred = x + v dt.
layout(local_size_x = WG) in;
uniform float u_dt;
void main()
{
    uint i = gid();
    if (i >= N) return;
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        float v = vel_[k];
#if HAS_GRAVITY
        float gdt = GRAVITY[d] * u_dt;
        if (gdt != 0.0) {
            v += gdt;
            vel_[k] = v;
        }
#endif
#if HAS_PRED
        precise float xp = pos_[k] + v * u_dt;
        if (PER[d] > 0.0) xp = wrap_coord(xp, DOM_MIN[d], PER[d], INV_PER[d]);
        pred_[k] = xp;
#endif
    }
}
