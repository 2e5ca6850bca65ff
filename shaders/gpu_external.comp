// uses: POS VEL PRED FIXED POS_R
// Pass external (src/passes/external.c): v = damp v + gscale g dt, then
// pred = x + v dt. u_gscale and u_damp are the start-up ramps' factors for
// this step (src/core/sph_start.h), 1 when the scene has none. Wall
// particles (wall_model = particles) get no gravity: they stand still.
// With position_sum = compensated, pred = x + (v dt + pos_r), as external.c.
layout(local_size_x = WG) in;
uniform float u_dt;
uniform float u_gscale;
uniform float u_damp;
void main()
{
    uint i = gid();
    if (i >= N) return;
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        float v = vel_[k];
        bool changed = u_damp != 1.0;
        v *= u_damp;
#if HAS_GRAVITY
        float gdt = GRAVITY[d] * u_gscale * u_dt;
#if HAS_FIXED
        if (fixed_[i] != 0.0) gdt = 0.0;
#endif
        if (gdt != 0.0) {
            v += gdt;
            changed = true;
        }
#endif
        if (changed) vel_[k] = v;
#if HAS_PRED
#if HAS_POS_R
        precise float xp = pos_[k] + (v * u_dt + pos_r_[k]);
#else
        precise float xp = pos_[k] + v * u_dt;
#endif
        if (PER[d] > 0.0) xp = wrap_coord(xp, DOM_MIN[d], PER[d], INV_PER[d]);
        pred_[k] = xp;
#endif
    }
}
