// The pair terms of the pressure force (src/passes/pressure_force.c) and of
// the viscosity (src/passes/viscosity.c), written once for the two passes'
// shaders and the fused walk (gpu_forces.comp, [compute] fuse_forces = on),
// so that all three do the same arithmetic. A shader defines FORCE_PRESSURE
// and FORCE_VISCOSITY (0 or 1) before "#include_forces", then its sph_pair
// calls forces_pair and its main forces_begin, sph_walk and forces_end.
#if FORCE_VISCOSITY && VFORM != VFORM_LAPLACIAN && VFORM != VFORM_SMOOTHING && VFORM != VFORM_MORRIS && \
    VFORM != VFORM_ARTIFICIAL && VFORM != VFORM_MORRIS_ARTIFICIAL
#error "a viscosity form this shader does not implement"
#endif
// morris-artificial: the sum of the two forms, Morris's scaled by nu and
// Monaghan's kept apart in acc_av (viscosity.c adds them in that order)
#define VISC_MORRIS (VFORM == VFORM_MORRIS || VFORM == VFORM_MORRIS_ARTIFICIAL)
#define VISC_ARTIFICIAL (VFORM == VFORM_ARTIFICIAL || VFORM == VFORM_MORRIS_ARTIFICIAL)
float rho_i; // the particle's density [kg/m^DIM]
#if FORCE_PRESSURE && WALL_VOLUME
#if HAS_GRAVITY
uniform float u_gscale; // the share of g of the step (gravity_ramp)
#endif
// The hidden lattice's second moments tn (returned in out) and tt at distance d
// from a wall (sph_kernel_wall_table on wall_lat_tt, wall_lat_tn).
float wall_moment(float d, out float tn)
{
    float t = d * INV_H * float(WALL_TABLE);
    if (!(t < float(WALL_TABLE))) { tn = 0.0; return 0.0; }
    if (t < 0.0) t = 0.0;
    int i = int(t);
    float f = t - float(i);
    int at = WALLP_AT + 2 * (WALL_TABLE + 1) + 2 * (WALL_CORNER + 1) * (WALL_CORNER + 1);
    int p = at + (WALL_TABLE + 1) + i, q = at + i;
    tn = wall_[q] + f * (wall_[q + 1] - wall_[q]);
    return wall_[p] + f * (wall_[p + 1] - wall_[p]);
}
#endif
#if FORCE_PRESSURE
vec3 acc_pf;       // sum of the pressure terms [m/s^2]
float pi_over, p_i; // p_i / rho_i^2 [Pa m^(2 DIM)/kg^2], p_i [Pa]
// Symmetric or shared form; a coincident pair is pushed apart along x
// (repulsion only).
void pressure_pair(uint i, uint j, vec3 dx, float r2)
{
    float r;
    if (r2 < R_MIN * R_MIN) {
        dx = vec3(i < j ? -R_MIN : R_MIN, 0.0, 0.0);
        r = R_MIN;
    } else {
        r = sqrt(r2);
    }
    float dw_over_r = kernel_dw(KP, SIG_P, r) / r;
#if PFORM_SYM
    float coef = mass_[j] * (pi_over + p_rho2_[j]);
#else
    float coef = vol_[j] * 0.5 * (p_i + p_[j]) / rho_i;
#endif
    if (r2 < R_MIN * R_MIN && coef < 0.0) coef = 0.0; // a coincident pair only repels
    for (int d = 0; d < DIM; d++) acc_pf[d] -= coef * dw_over_r * dx[d];
}
#endif
#if FORCE_VISCOSITY
vec3 acc_vs, vi; // sum of the viscous terms (unscaled), the particle's velocity [m/s]
#if VISC_ARTIFICIAL
vec3 acc_av; // sum of Monaghan's terms [m/s^2]
uniform vec3 u_kick; // [m/s] a wall particle's velocity in the step's frame, g dt (viscosity.c)
// Monaghan 1992: -m_j Pi_ij grad W_ij for approaching pairs, along x_ij,
// with the pressure kernel's gradient; the neighbour's own velocity, a wall
// particle's seen at v_w + g dt (sph_wall_kick), as the fluid's v is kicked
void artificial_pair(uint j, vec3 dx, float r2, float r)
{
    vec3 vj = VEL3(j);
#if HAS_FIXED
    if (fixed_[j] != 0.0) vj += u_kick;
#endif
    float vx = 0.0;
    for (int d = 0; d < DIM; d++) vx += (vi[d] - vj[d]) * dx[d];
    if (!(vx < 0.0) || r <= 0.0) return;
    float pi_ij = -AV_ACH * vx / (0.5 * (rho_i + rho_[j]) * (r2 + AV_EPS2));
    float f = -mass_[j] * pi_ij * kernel_dw(KP, SIG_P, r) / r;
    for (int d = 0; d < DIM; d++) acc_av[d] += f * dx[d];
}
#endif
// With wall particles the neighbours' velocities are vel_visc (the
// wall_state pass: the fluid's own, a no-slip wall's mirrored).
void viscosity_pair(uint i, uint j, vec3 dx, float r2)
{
    float r = sqrt(r2);
#if VISC_ARTIFICIAL
    artificial_pair(j, dx, r2, r);
#endif
#if VFORM != VFORM_ARTIFICIAL
#if VISC_MORRIS
    // -(x_ij . grad W) / (r^2 + eta^2), eta = 0.01 h, symmetrised in density (Morris 1997)
    float coef = -mass_[j] * (rho_i + rho_[j]) / (rho_i * rho_[j]) * r * kernel_dw(KV, SIG_V, r) / (r2 + 1e-4 * H2);
#elif VFORM == VFORM_LAPLACIAN
    float coef = vol_[j] * kernel_lap(KV, SIG_V, r);
#else
    float coef = vol_[j] * kernel_w(KV, SIG_V, r);
#endif
#if HAS_VEL_VISC
    vec3 vj = LOAD3(vel_visc_, j);
#else
    vec3 vj = VEL3(j);
#endif
    for (int d = 0; d < DIM; d++) acc_vs[d] += coef * (vj[d] - vi[d]);
#endif
}
#endif

void forces_pair(uint i, uint j, vec3 dx, float r2)
{
#if FORCE_VISCOSITY // first, as the CPU's fused loop: dx is the pressure term's to move
    viscosity_pair(i, j, dx, r2);
#endif
#if FORCE_PRESSURE
    pressure_pair(i, j, dx, r2);
#endif
}

// Wall particles (wall_model = particles) get no acceleration: they never
// move. true: particle i is one (its accelerations are written, zero).
bool forces_still(uint i)
{
#if HAS_FIXED
    if (fixed_[i] != 0.0) {
        for (int d = 0; d < DIM; d++) {
#if FORCE_PRESSURE
            acc_p_[uint(d) * N + i] = 0.0;
#endif
#if FORCE_VISCOSITY
            acc_v_[uint(d) * N + i] = 0.0;
#endif
        }
        return true;
    }
#endif
    return false;
}

void forces_begin(uint i)
{
    rho_i = rho_[i];
#if FORCE_PRESSURE
    acc_pf = vec3(0.0);
    pi_over = p_rho2_[i];
    p_i = p_[i];
#endif
#if FORCE_VISCOSITY
    acc_vs = vec3(0.0);
#if VISC_ARTIFICIAL
    acc_av = vec3(0.0);
#endif
    vi = VEL3(i);
#endif
}

// The walls' push on the pressure side, the viscosity's scale, and the stores.
void forces_end(uint i, vec3 xi)
{
#if FORCE_PRESSURE
#if WALL_VOLUME && !WALL_GHOST
    vec3 grad;
    wall_hidden(xi, grad);
    for (int d = 0; d < DIM; d++) acc_pf[d] -= RHO0 * pi_over * grad[d];
#elif WALL_VOLUME
    // the hidden lattice as ghosts in the pair term (sph_wall_ghost_accel)
    vec3 grad, tg = vec3(0.0);
    wall_hidden_of(WALLP_AT, WALL_FULL_P, xi, grad);
#if HAS_GRAVITY
    for (int d = 0; d < DIM; d++) {
        if (PER[d] > 0.0) continue;
        for (int side = 0; side < 2; side++) {
            float ds = side == 0 ? xi[d] - DOM_MIN[d] : DOM_MAX[d] - xi[d], tn;
            float tt = wall_moment(ds, tn);
            for (int e = 0; e < DIM; e++) tg[e] += (e == d ? tn : tt) * GRAVITY[e] * u_gscale;
        }
    }
#endif
#if PFORM_SYM
    const float form = 1.0;
#else
    const float form = 0.5;
#endif
    float c = form * RHO0 * pi_over * 2.0, cg = form * RHO0 / rho_i;
    for (int d = 0; d < DIM; d++) acc_pf[d] -= c * grad[d] + cg * tg[d];
#endif
    for (int d = 0; d < DIM; d++) acc_p_[uint(d) * N + i] = acc_pf[d];
#endif
#if FORCE_VISCOSITY
#if VFORM == VFORM_ARTIFICIAL
    for (int d = 0; d < DIM; d++) acc_v_[uint(d) * N + i] = acc_av[d];
#elif VFORM == VFORM_MORRIS_ARTIFICIAL
    for (int d = 0; d < DIM; d++) acc_v_[uint(d) * N + i] = NU * acc_vs[d] + acc_av[d];
#else
#if VFORM == VFORM_MORRIS
    float s = NU;
#elif VFORM == VFORM_LAPLACIAN
    float s = NU * RHO0 / rho_[i];
#else
    float s = NU * 2.0 * float(DIM) / M2_V;
#endif
    for (int d = 0; d < DIM; d++) acc_v_[uint(d) * N + i] = s * acc_vs[d];
#endif
#endif
}
