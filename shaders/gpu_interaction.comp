// uses: POS VEL PRED ACC_I
// Pass interaction (src/passes/interaction.c): the mouse's push or pull.
layout(local_size_x = WG) in;
uniform uint u_count;   // 1 while the button is down
uniform vec3 u_point;   // [m]
uniform float u_value;  // [m/s^2] strength times the sign
void main()
{
    uint i = gid();
    if (i >= N) return;
    vec3 a = vec3(0.0);
    if (u_count != 0u) {
#if HAS_PRED
        vec3 x = PRED3(i);
#else
        vec3 x = POS3(i);
#endif
        vec3 dx = vec3(0.0), v = VEL3(i);
        float r2 = 0.0;
        for (int d = 0; d < DIM; d++) {
            dx[d] = u_point[d] - x[d];
            r2 += dx[d] * dx[d];
        }
        if (r2 < INTER_R * INTER_R) {
            float r = sqrt(r2), fall = 1.0 - r / INTER_R;
            float toward = r > 0.0 ? u_value * fall / r : 0.0;
            for (int d = 0; d < DIM; d++) a[d] = toward * dx[d] - fall * v[d];
        }
    }
    for (int d = 0; d < DIM; d++) acc_i_[uint(d) * N + i] = a[d];
}
