#include "sph_kernel.h"
#include "sph_sim.h"

#include <math.h>
#include <string.h>

const char *const sph_kernel_names[SPH_KERNEL_COUNT] = {
#define SPH_KERNEL_NAME(id, name, about) name,
    SPH_KERNELS(SPH_KERNEL_NAME)
#undef SPH_KERNEL_NAME
};

const char *const sph_kernel_about[SPH_KERNEL_COUNT] = {
#define SPH_KERNEL_ABOUT(id, name, about) about,
    SPH_KERNELS(SPH_KERNEL_ABOUT)
#undef SPH_KERNEL_ABOUT
};

/* Normalisation constants for support radius h, from integrating each shape
 * over the disc (2D) or ball (3D) of radius h. */
static double kernel_sigma(sph_kernel_kind kind, int dim, double h)
{
    const double pi = 3.14159265358979323846;
    int three = dim == 3;
    switch (kind) {
    case SPH_KERNEL_POLY6: return three ? 315.0 / (64.0 * pi * pow(h, 9)) : 4.0 / (pi * pow(h, 8));
    case SPH_KERNEL_SPIKY: return three ? 15.0 / (pi * pow(h, 6)) : 10.0 / (pi * pow(h, 5));
    case SPH_KERNEL_VISCOSITY: return three ? 15.0 / (2.0 * pi * pow(h, 3)) : 40.0 / (pi * h * h); /* 2D: 40/(pi h^5) * h^3 */
    case SPH_KERNEL_CUBIC: return three ? 8.0 / (pi * pow(h, 3)) : 40.0 / (7.0 * pi * h * h);
    case SPH_KERNEL_WENDLAND: return three ? 21.0 / (2.0 * pi * pow(h, 3)) : 7.0 / (pi * h * h);
    default: return 0.0;
    }
}

/* Second moment M2 = integral of r^2 W dV, by Simpson's rule on the radius.
 * The velocity-smoothing viscosity uses it to turn a kernel average into a
 * Laplacian: <v> - v ~ (M2 / 2d) lap v. */
static float kernel_second_moment(const sph_kernel *k)
{
    const double pi = 3.14159265358979323846;
    const int n = 2000;
    double dr = k->h / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double r = i * dr;
        double shell = k->dim == 3 ? 4.0 * pi * r * r : 2.0 * pi * r;
        double f = r * r * sph_kernel_w(k, (float)r) * shell;
        sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return (float)(sum * dr / 3.0);
}

/* The wall tables. The plane integral at distance x from the centre is
 *   3D: A(x) = 2 pi int_x^h W(r) r dr  (rings of radius sqrt(r^2 - x^2))
 *   2D: A(x) = 2 int_0^sqrt(h^2-x^2) W(sqrt(x^2 + y^2)) dy
 * and psi(d) = int_d^h A(x) dx, both integrated on a fine grid in double. */
static void kernel_wall_tables(sph_kernel *k)
{
    enum { FINE = 16 * SPH_WALL_TABLE, STEPS = 512 };
    const double pi = 3.14159265358979323846, h = k->h, dx = h / FINE;
    double A[FINE + 1];
    for (int i = 0; i <= FINE; i++) {
        double x = i * dx, sum = 0;
        if (k->dim == 3) {
            double dr = (h - x) / STEPS;
            for (int s = 0; s < STEPS; s++) {
                double r = x + (s + 0.5) * dr;
                sum += sph_kernel_w(k, (float)r) * r * dr;
            }
            sum *= 2 * pi;
        } else {
            double ymax = sqrt(fmax(h * h - x * x, 0)), dy = ymax / STEPS;
            for (int s = 0; s < STEPS; s++) {
                double y = (s + 0.5) * dy;
                sum += sph_kernel_w(k, (float)sqrt(x * x + y * y)) * dy;
            }
            sum *= 2;
        }
        A[i] = sum;
    }
    double psi = 0; /* integrate from h down to 0 */
    for (int i = FINE; i >= 0; i--) {
        if (i < FINE) psi += 0.5 * (A[i] + A[i + 1]) * dx;
        if (i % 16 == 0) {
            k->wall_psi[i / 16] = (float)psi;
            k->wall_area[i / 16] = (float)A[i];
        }
    }
}

/* The hidden share as a particle sum. A first-row particle of a lattice
 * block sits s/2 from the wall; its density sum covers the rows at 0, s,
 * 2s, ... from it, where an interior particle also has the rows at -s, -2s,
 * ...: those are what the wall must stand for, node by node, for the row to
 * read what the interior reads (the interior's own lattice sum is not
 * exactly 1: docs/accuracy.md, section 2). The integral psi(d) stands for
 * them only in the limit s/h -> 0: at h = 2 s the first row read 1.5 to
 * 3.9 % above the interior. So the hidden share at distance d is
 *   H(d) = s^dim sum_{k >= 0} sum_{m} W(|(d + s/2 + k s, m s)|),
 * m over the tangential lattice (a line in 2D, a plane in 3D) through the
 * particle: the midpoint rule on cells of volume s^dim, the quadrature the
 * density sum itself is, and the integral psi(d) as s -> 0. It is the
 * fixed-ghost lattice of the fluid continued behind the wall (ghost
 * particles: Colagrossi & Landrini 2003, J. Comput. Phys. 191, 448-475),
 * summed once per distance instead of stored as particles; the share enters
 * as gamma does in the unified semi-analytical walls (Ferrand et al. 2013,
 * Int. J. Numer. Meth. Fluids 71, 446-472, eq. 11), but evaluated with the
 * particles' quadrature instead of exactly. */
/* The second-moment tables (wall_lat_tn, wall_lat_tt) of the lattice at spacing s [m]. */
static void kernel_wall_moments(sph_kernel *k, double s)
{
    const double h = k->h, cell = k->dim == 3 ? s * s * s : s * s;
    const int reach = (int)ceil(h / s) + 1;
    for (int i = 0; i <= SPH_WALL_TABLE; i++) {
        const double d = h * i / SPH_WALL_TABLE;
        double tn = 0, tt = 0;
        for (int row = 0; d + (row + 0.5) * s < h; row++) {
            const double y = d + (row + 0.5) * s;
            for (int a = -reach; a <= reach; a++)
                for (int b = k->dim == 3 ? -reach : 0; b <= (k->dim == 3 ? reach : 0); b++) {
                    const double t2 = (a * a + b * b) * s * s, r = sqrt(y * y + t2);
                    if (r >= h) continue;
                    const double g = -sph_kernel_dw(k, (float)r) / r;
                    tn += g * y * y;
                    tt += g * (a * s) * (a * s);
                }
        }
        k->wall_lat_tn[i] = (float)(tn * cell);
        k->wall_lat_tt[i] = (float)(tt * cell);
    }
}

void sph_kernel_wall_lattice(sph_kernel *k, float spacing)
{
    const int nc = SPH_WALL_CORNER + 1, step = SPH_WALL_TABLE / SPH_WALL_CORNER;
    /* Beyond SPH_WALL_LATTICE_MAX spacings per h the lattice's share is the
     * integral's within 6e-4 (poly6, cubic, Wendland, spiky; 2D and 3D,
     * measured), while summing it costs (h/s)^dim per table point: a scene
     * with h = 300 spacings took minutes to start. Use the integral there. */
    if (!(spacing > 0.0f) || k->h > SPH_WALL_LATTICE_MAX * spacing) {
        /* the integral's within the lattice's error; a coarser lattice where no spacing is known (every
         * kernel made passes here: kept cheap) */
        kernel_wall_moments(k, k->h / (spacing > 0.0f ? SPH_WALL_LATTICE_MAX : 8));
        memcpy(k->wall_lat_psi, k->wall_psi, sizeof k->wall_psi);
        memcpy(k->wall_lat_area, k->wall_area, sizeof k->wall_area);
        k->wall_lat_full = 1.0f;
        for (int a = 0; a < nc; a++)
            for (int b = 0; b < nc; b++) {
                k->wall_corner[a * nc + b] = k->wall_psi[a * step] * k->wall_psi[b * step];
                k->wall_corner_slope[a * nc + b] = k->wall_area[a * step] * k->wall_psi[b * step];
            }
        return;
    }
    const double s = spacing, h = k->h, cell = k->dim == 3 ? s * s * s : s * s;
    const int reach = (int)ceil(h / s) + 1; /* nodes each side */
    double full = 0;
    for (int a = -reach; a <= reach; a++)
        for (int b = -reach; b <= reach; b++)
            for (int c = k->dim == 3 ? -reach : 0; c <= (k->dim == 3 ? reach : 0); c++)
                full += sph_kernel_w(k, (float)(s * sqrt((double)(a * a + b * b + c * c))));
    k->wall_lat_full = (float)(full * cell);
    kernel_wall_moments(k, s);
    for (int i = 0; i <= SPH_WALL_TABLE; i++) {
        const double d = h * i / SPH_WALL_TABLE;
        double psi = 0, area = 0;
        for (int row = 0;; row++) {
            const double y = d + 0.5 * s + row * s; /* normal distance of the row */
            if (y >= h) break;
            for (int a = -reach; a <= reach; a++)
                for (int b = k->dim == 3 ? -reach : 0; b <= (k->dim == 3 ? reach : 0); b++) {
                    const double t2 = (a * a + b * b) * s * s, r = sqrt(y * y + t2);
                    if (r >= h) continue;
                    psi += sph_kernel_w(k, (float)r);
                    area -= sph_kernel_dw(k, (float)r) * (y / r); /* -dW/dd: W falls as the row recedes */
                }
        }
        k->wall_lat_psi[i] = (float)(psi * cell);
        k->wall_lat_area[i] = (float)(area * cell);
    }
    /* beyond two walls: rows along both normals, a line of nodes along the third axis in 3D */
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++) {
            const double d1 = h * a / SPH_WALL_CORNER, d2 = h * b / SPH_WALL_CORNER;
            double psi = 0, slope = 0;
            for (int r1 = 0; d1 + (r1 + 0.5) * s < h; r1++)
                for (int r2 = 0; d2 + (r2 + 0.5) * s < h; r2++) {
                    const double y1 = d1 + (r1 + 0.5) * s, y2 = d2 + (r2 + 0.5) * s;
                    for (int c = k->dim == 3 ? -reach : 0; c <= (k->dim == 3 ? reach : 0); c++) {
                        const double r = sqrt(y1 * y1 + y2 * y2 + c * c * s * s);
                        if (r >= h) continue;
                        psi += sph_kernel_w(k, (float)r);
                        slope -= sph_kernel_dw(k, (float)r) * (y1 / r);
                    }
                }
            k->wall_corner[a * nc + b] = (float)(psi * cell);
            k->wall_corner_slope[a * nc + b] = (float)(slope * cell);
        }
}

sph_kernel sph_kernel_make(sph_kernel_kind kind, int dim, float h)
{
    sph_kernel k;
    memset(&k, 0, sizeof k);
    k.kind = kind;
    k.dim = dim == 2 ? 2 : 3;
    k.h = h;
    k.h2 = h * h;
    k.inv_h = 1.0f / h;
    k.sigma = (float)kernel_sigma(kind, k.dim, h);
    k.m2 = kernel_second_moment(&k);
    kernel_wall_tables(&k);
    sph_kernel_wall_lattice(&k, 0.0f);
    return k;
}

int sph_kernel_find(const char *name)
{
    for (int i = 0; i < SPH_KERNEL_COUNT; i++)
        if (strcmp(name, sph_kernel_names[i]) == 0) return i;
    return -1;
}

/* The finest spacing of the scene's blocks [m], 0 without blocks. */
float sph_scene_finest_spacing(const sph_scene_def *def)
{
    float s = 0;
    for (int b = 0; b < def->n_blocks; b++)
        if (s == 0 || def->blocks[b].spacing < s) s = def->blocks[b].spacing;
    return s;
}

/* A sum over a full neighbourhood of the finest lattice, spacing s > 0:
 * sum_j m W^rho(r_j), or with a kernel b sum_j m^2 W'a(r_j) W'b(r_j) (j != i),
 * a = b if same, else the density kernel. */
static double lattice_sum(const sph_sim *sim, float s, const sph_kernel *b, bool same)
{
    const sph_scene_def *def = &sim->def;
    const int dim = sim->dim, r = (int)ceilf(def->h / s);
    const double m = def->rest_density * (dim == 3 ? (double)s * s * s : (double)s * s);
    double sum = 0;
    for (int z = dim == 3 ? -r : 0; z <= (dim == 3 ? r : 0); z++)
        for (int y = -r; y <= r; y++)
            for (int x = -r; x <= r; x++) {
                float d = s * sqrtf((float)(x * x + y * y + z * z));
                if (!(d < def->h)) continue;
                if (!b)
                    sum += m * sph_kernel_w(&sim->k_density, d);
                else if (d > 0)
                    sum += m * m * sph_kernel_dw(same ? b : &sim->k_density, d) * sph_kernel_dw(b, d);
            }
    return sum;
}

/* The density a particle of the scene's finest lattice reads at rest, with
 * its whole support inside the fluid: rho0 (1 + e), where e is the
 * summation's own excess on a lattice (+1.46 % for poly6 at h = 2 s in 2D,
 * +1.2 % for the 3D bench scene). The pressure solvers hold it, and the
 * equation of state with eos_rest = lattice: holding rho0 instead would
 * expand every block by e at its first step. Computed from the density
 * kernel and the lattice, nothing fitted. */
float sph_sim_lattice_rest_density(const sph_sim *sim)
{
    const float s = sph_scene_finest_spacing(&sim->def);
    return s > 0 ? (float)lattice_sum(sim, s, NULL, false) : sim->def.rest_density;
}

/* sum_j m_j^2 grad W^rho_ij . grad W^p_ij over the finest lattice's full
 * neighbourhood [kg^2/m^(2 dim + 2)]: DFSPH's alpha denominator for a
 * particle whose neighbourhood is full (the sum of gradients is 0 there),
 * the prototype particle of Solenthaler & Pajarola 2009 (section 3.2). */
float sph_sim_lattice_dots(const sph_sim *sim)
{
    const float s = sph_scene_finest_spacing(&sim->def);
    return s > 0 ? (float)lattice_sum(sim, s, &sim->k_pressure, false) : 0.0f;
}

/* sum_j m_j^2 |grad W^p_ij|^2 over the same neighbourhood: the least denominator of
 * DFSPH's divergence factor, whose divergence and push both take the pressure kernel. */
float sph_sim_lattice_dots_pressure(const sph_sim *sim)
{
    const float s = sph_scene_finest_spacing(&sim->def);
    return s > 0 ? (float)lattice_sum(sim, s, &sim->k_pressure, true) : 0.0f;
}
