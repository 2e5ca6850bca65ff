/* Smoothing kernels W(r, h) with compact support radius h, normalised so that
 * the integral of W over the plane (2D) or space (3D) is 1.
 *
 * Each kernel is written as W(r) = sigma_d * f(r) with the shape f shared by
 * 2D and 3D and only the normalisation sigma_d depending on the dimension.
 * The gradient is dW/dr along r_ij / |r_ij|; the Laplacian of a radial
 * function in d dimensions is W'' + (d - 1) W' / r.
 *
 * The viscosity kernel is the exception: Mueller's function is built so that
 * its 3D Laplacian is 45/(pi h^6)(h - r). Used in 2D, its Laplacian gains a
 * + h/(2 r^3) term that explodes for close pairs (and a simulation with it).
 * In 2D we use the kernel built the same way for the plane,
 *   W = 40/(pi h^5) (h r^2/4 - r^3/9 + (h^3/6) ln(h/r) - 5h^3/36),
 * whose 2D Laplacian is 40/(pi h^5)(h - r) (docs/kernels.md derives it). */
#ifndef SPH_KERNEL_H
#define SPH_KERNEL_H

#include <math.h>

#define SPH_KERNELS(X)                                                        \
    X(POLY6, "poly6", "Mueller 2003, (h^2-r^2)^3: smooth, for density")       \
    X(SPIKY, "spiky", "Mueller 2003, (h-r)^3: gradient does not vanish at 0") \
    X(VISCOSITY, "viscosity", "Mueller 2003: Laplacian 45/(pi h^6)(h-r) in 3D; its 2D analogue 40/(pi h^5)(h-r)") \
    X(CUBIC, "cubic", "cubic B-spline, Monaghan 1992")                        \
    X(WENDLAND, "wendland", "Wendland C2, (1-q)^4 (1+4q)")

typedef enum sph_kernel_kind {
#define SPH_KERNEL_ENUM(id, name, about) SPH_KERNEL_##id,
    SPH_KERNELS(SPH_KERNEL_ENUM)
#undef SPH_KERNEL_ENUM
    SPH_KERNEL_COUNT
} sph_kernel_kind;

extern const char *const sph_kernel_names[SPH_KERNEL_COUNT];
extern const char *const sph_kernel_about[SPH_KERNEL_COUNT];

#define SPH_WALL_TABLE 128
#define SPH_WALL_CORNER 32

/* A kernel bound to a dimension and a support radius, with its constants
 * precomputed so the per-pair functions do no divisions by h. */
typedef struct sph_kernel {
    sph_kernel_kind kind;
    int dim;       /* 2 or 3 */
    float h;       /* [m] support radius: W = 0 for r >= h */
    float h2;      /* [m^2] h * h */
    float inv_h;   /* [1/m] */
    float sigma;   /* [1/m^dim] normalisation of the shape */
    float m2;      /* [m^2] second moment: integral of r^2 W dV */
    /* A plane wall at distance d from a particle hides part of its support.
     * wall_psi(d) = integral of W over the half-space beyond the wall [1];
     * wall_area(d) = integral of W over the wall's plane [1/m] = -d psi / dd.
     * Tabulated at d = i h / SPH_WALL_TABLE; 0.5 and its slope at d = 0. */
    float wall_psi[SPH_WALL_TABLE + 1];
    float wall_area[SPH_WALL_TABLE + 1];
    /* The same share as the particles count it (the volume wall model): the
     * space beyond the wall cut into cells of the fluid's particle volume
     * s^dim, a lattice whose first row lies s/2 beyond the wall, each cell
     * counted at its centre as the density sum counts a particle
     * (sph_kernel_wall_lattice). wall_lat_psi(d) [1], wall_lat_area(d) =
     * -d wall_lat_psi / dd [1/m]; same points as wall_psi. Equal to the
     * integral tables when no spacing is known. */
    float wall_lat_psi[SPH_WALL_TABLE + 1];
    float wall_lat_area[SPH_WALL_TABLE + 1];
    float wall_lat_full; /* [1] the whole lattice's sum s^dim sum W (1 when no spacing is known) */
    /* The hidden lattice's second moments of the gradient, T = -s^dim sum
     * (W'(r) / r) D D^T over its nodes, D = node - particle: along the wall's
     * normal (tn) and along one tangent (tt) [1]; the rest is zero by the
     * lattice's symmetry. The ghost pressure p_i + rho_i g . D (Adami et al.
     * 2012, eq. 27) makes the pair term carry -(rho0 / rho_i) T g
     * (sph_wall_ghost_accel). At the full lattice T is about the identity. */
    float wall_lat_tn[SPH_WALL_TABLE + 1];
    float wall_lat_tt[SPH_WALL_TABLE + 1];
    /* Two walls meeting (a corner in 2D, an edge in 3D), at distances d1 and
     * d2: the share of the lattice beyond both, which inclusion-exclusion
     * subtracts once (sph_wall_hidden). wall_corner[i1 * (C + 1) + i2] at
     * d = i h / C, C = SPH_WALL_CORNER [1]; wall_corner_slope: -d/dd1 [1/m]
     * (-d/dd2 is the transposed entry: the share is symmetric). */
    float wall_corner[(SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1)];
    float wall_corner_slope[(SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1)];
} sph_kernel;

sph_kernel sph_kernel_make(sph_kernel_kind kind, int dim, float h);
/* Fills the lattice tables (one wall, two walls) for the fluid's spacing [m];
 * spacing <= 0 makes them from the integral's (the corner share psi1 psi2). */
void sph_kernel_wall_lattice(sph_kernel *k, float spacing);
/* Spacings per h beyond which the lattice tables are the integral's (sph_kernel_wall_lattice). */
#define SPH_WALL_LATTICE_MAX 16

/* The per-pair functions are forced inline so that a pass's loop, which
 * calls them with a loop-invariant kind, gets them inlined (gcc -O2 keeps
 * the switch out of line otherwise: a call per neighbour pair). */
#define SPH_INLINE static inline __attribute__((always_inline))

/* Value W(r) [1/m^dim]. The viscosity kernel is singular at r = 0 (its h/2r
 * term); there it returns its value at r = 1e-3 h: it is meant for its Laplacian. */
SPH_INLINE float sph_kernel_w(const sph_kernel *k, float r);
/* dW/dr [1/m^(dim+1)]: the gradient is dW/dr * (r_vec / r); 0 at r = 0. */
SPH_INLINE float sph_kernel_dw(const sph_kernel *k, float r);
/* Laplacian W'' + (d-1) W'/r [1/m^(dim+2)]; at r = 0 its limit where one
 * exists (poly6, cubic, Wendland, viscosity), else its value at r = 1e-3 h. */
SPH_INLINE float sph_kernel_lap(const sph_kernel *k, float r);

/* Looks a kernel up by name; returns -1 if there is none. */
int sph_kernel_find(const char *name);

#define SPH_KERNEL_R_MIN 1e-3f /* [h] where singular kernels are evaluated instead of 0 */

/* psi(d) and, in *area, the plane integral at distance d from a wall (linear
 * interpolation in the tables); both 0 for d >= h, and d < 0 counts as 0. */
SPH_INLINE float sph_kernel_wall_table(const sph_kernel *k, const float *psi, const float *slope, float d,
                                       float *area)
{
    float t = d * k->inv_h * (float)SPH_WALL_TABLE;
    if (!(t < (float)SPH_WALL_TABLE)) {
        *area = 0.0f;
        return 0.0f;
    }
    if (t < 0.0f) t = 0.0f;
    int i = (int)t;
    float f = t - (float)i;
    *area = slope[i] + f * (slope[i + 1] - slope[i]);
    return psi[i] + f * (psi[i + 1] - psi[i]);
}
SPH_INLINE float sph_kernel_wall(const sph_kernel *k, float d, float *area)
{
    return sph_kernel_wall_table(k, k->wall_psi, k->wall_area, d, area);
}
/* Bilinear interpolation in a (C + 1)^2 corner table at fractional indices (a, b). */
SPH_INLINE float sph_kernel_corner_lerp(const float *tab, int a, int b, float fa, float fb)
{
    const int n = SPH_WALL_CORNER + 1;
    float lo = tab[a * n + b] + fb * (tab[a * n + b + 1] - tab[a * n + b]);
    float hi = tab[(a + 1) * n + b] + fb * (tab[(a + 1) * n + b + 1] - tab[(a + 1) * n + b]);
    return lo + fa * (hi - lo);
}
/* The corner share at distances d1, d2 from two walls of different axes, and
 * in *s1, *s2 its slopes -d/dd1 and -d/dd2; all 0 if either is >= h. */
SPH_INLINE float sph_kernel_wall_corner(const sph_kernel *k, float d1, float d2, float *s1, float *s2)
{
    const float c = (float)SPH_WALL_CORNER;
    float t1 = d1 * k->inv_h * c, t2 = d2 * k->inv_h * c;
    if (!(t1 < c) || !(t2 < c)) {
        *s1 = *s2 = 0.0f;
        return 0.0f;
    }
    if (t1 < 0.0f) t1 = 0.0f;
    if (t2 < 0.0f) t2 = 0.0f;
    int i1 = (int)t1, i2 = (int)t2;
    float f1 = t1 - (float)i1, f2 = t2 - (float)i2;
    *s1 = sph_kernel_corner_lerp(k->wall_corner_slope, i1, i2, f1, f2);
    *s2 = sph_kernel_corner_lerp(k->wall_corner_slope, i2, i1, f2, f1);
    return sph_kernel_corner_lerp(k->wall_corner, i1, i2, f1, f2);
}
/* The lattice's share (wall_lat_psi), as sph_kernel_wall: what the volume wall model counts. */
SPH_INLINE float sph_kernel_wall_lat(const sph_kernel *k, float d, float *area)
{
    return sph_kernel_wall_table(k, k->wall_lat_psi, k->wall_lat_area, d, area);
}

SPH_INLINE float sph_kernel_w(const sph_kernel *k, float r)
{
    if (r >= k->h) return 0.0f;
    float s = k->sigma;
    switch (k->kind) {
    case SPH_KERNEL_POLY6: {
        float d = k->h2 - r * r;
        return s * d * d * d;
    }
    case SPH_KERNEL_SPIKY: {
        float d = k->h - r;
        return s * d * d * d;
    }
    case SPH_KERNEL_VISCOSITY: {
        if (r < SPH_KERNEL_R_MIN * k->h) r = SPH_KERNEL_R_MIN * k->h;
        float q = r * k->inv_h;
        /* both shapes are >= 0 but vanish near h through cancellation, which
         * float arithmetic can overshoot by an ulp: clamp at 0 */
        if (k->dim == 2) return s * fmaxf(0.0f, 0.25f * q * q - q * q * q / 9.0f - logf(q) / 6.0f - 5.0f / 36.0f);
        return s * fmaxf(0.0f, -0.5f * q * q * q + q * q + 0.5f / q - 1.0f);
    }
    case SPH_KERNEL_CUBIC: {
        float q = r * k->inv_h;
        if (q <= 0.5f) return s * (6.0f * (q * q * q - q * q) + 1.0f);
        float d = 1.0f - q;
        return s * 2.0f * d * d * d;
    }
    case SPH_KERNEL_WENDLAND: {
        float q = r * k->inv_h, d = 1.0f - q;
        return s * d * d * d * d * (1.0f + 4.0f * q);
    }
    default: return 0.0f;
    }
}

SPH_INLINE float sph_kernel_dw(const sph_kernel *k, float r)
{
    if (r >= k->h || r <= 0.0f) return 0.0f;
    float s = k->sigma, ih = k->inv_h;
    switch (k->kind) {
    case SPH_KERNEL_POLY6: {
        float d = k->h2 - r * r;
        return -6.0f * s * r * d * d;
    }
    case SPH_KERNEL_SPIKY: {
        float d = k->h - r;
        return -3.0f * s * d * d;
    }
    case SPH_KERNEL_VISCOSITY: {
        float q = r * ih;
        if (k->dim == 2) return s * ih * (0.5f * q - q * q / 3.0f - 1.0f / (6.0f * q));
        return s * ih * (-1.5f * q * q + 2.0f * q - 0.5f / (q * q));
    }
    case SPH_KERNEL_CUBIC: {
        float q = r * ih;
        if (q <= 0.5f) return s * ih * (18.0f * q * q - 12.0f * q);
        float d = 1.0f - q;
        return -6.0f * s * ih * d * d;
    }
    case SPH_KERNEL_WENDLAND: {
        float q = r * ih, d = 1.0f - q;
        return -20.0f * s * ih * q * d * d * d;
    }
    default: return 0.0f;
    }
}

SPH_INLINE float sph_kernel_lap(const sph_kernel *k, float r)
{
    if (r >= k->h) return 0.0f;
    float s = k->sigma, ih = k->inv_h, ih2 = ih * ih, dm1 = (float)(k->dim - 1);
    switch (k->kind) {
    case SPH_KERNEL_POLY6: { /* W'' = -6s(h^2-r^2)(h^2-5r^2), W'/r = -6s(h^2-r^2)^2 */
        float d = k->h2 - r * r;
        return -6.0f * s * d * (k->h2 - 5.0f * r * r + dm1 * d);
    }
    case SPH_KERNEL_SPIKY: { /* W'' = 6s(h-r), W' = -3s(h-r)^2 */
        if (r < SPH_KERNEL_R_MIN * k->h) r = SPH_KERNEL_R_MIN * k->h;
        float d = k->h - r;
        return 6.0f * s * d - dm1 * 3.0f * s * d * d / r;
    }
    case SPH_KERNEL_VISCOSITY: { /* 45/(pi h^6) (h - r) in 3D, 40/(pi h^5) (h - r) in 2D */
        float q = r * ih;
        /* W'' + 2 W'/r: the 1/q^3 terms cancel exactly, leaving 6 (1 - q);
         * written out, they would cancel in float and lose every digit near 0 */
        (void)dm1;
        return k->dim == 2 ? s * ih2 * (1.0f - q) : s * ih2 * 6.0f * (1.0f - q);
    }
    case SPH_KERNEL_CUBIC: {
        float q = r * ih;
        if (q <= 0.5f) return s * ih2 * ((36.0f * q - 12.0f) + dm1 * (18.0f * q - 12.0f));
        float d = 1.0f - q;
        float d1_over_q = q > 0.0f ? -6.0f * d * d / q : 0.0f;
        return s * ih2 * (12.0f * d + dm1 * d1_over_q);
    }
    case SPH_KERNEL_WENDLAND: {
        float q = r * ih, d = 1.0f - q;
        return -20.0f * s * ih2 * d * d * ((1.0f - 4.0f * q) + dm1 * d);
    }
    default: return 0.0f;
    }
}

#endif
