// uses: POS VEL FIXED
// Pass walls (src/passes/walls.c): damped reflection at the domain box.
layout(local_size_x = WG) in;
void main()
{
    uint i = gid();
    if (i >= N) return;
#if HAS_FIXED
    if (fixed_[i] != 0.0) return; // wall particles live outside the box
#endif
    for (int d = 0; d < DIM; d++) {
        if (PER[d] > 0.0) continue;
        uint k = uint(d) * N + i;
        float x = pos_[k], v = vel_[k];
        if (x < DOM_MIN[d]) {
            pos_[k] = DOM_MIN[d];
            if (v < 0.0) vel_[k] = -DAMP * v;
        } else if (x > DOM_MAX[d]) {
            pos_[k] = DOM_MAX[d];
            if (v > 0.0) vel_[k] = -DAMP * v;
        }
    }
}
