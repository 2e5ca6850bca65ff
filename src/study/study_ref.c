/* The scene-based reference problems and one measured run (docs/accuracy.md).
 *
 *   density          a block at rest, effects = density: interior particles
 *                    (at least h from every free face) should read rho0.
 *   density-surface  the same block: a particle at distance d < h from one
 *                    free face misses the share psi(d) of its support (the
 *                    kernel's integral beyond the face, sph_kernel_wall), so
 *                    it should read rho0 (1 - psi(d)).
 *   hydrostatic      a tank (walls, gravity) that settles: p = rho0 g (H - y),
 *                    H the depth the fluid's mass gives.
 *   taylor-green     the periodic vortex: E_kin decays as exp(-4 nu k^2 t).
 *   compression      any flow with pressure (a dam break): how far the
 *                    density rises above the density the pressure holds
 *                    at rest (each step's largest, averaged over time),
 *                    and what the pressure solve costs per simulated second.
 *
 * The time of a run is the time spent in sph_sim_step; the observation the
 * metric makes after each step is not counted. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "sph_walls.h"

const char *const study_metric_names[STUDY_METRIC_COUNT] = {
#define STUDY_METRIC_NAME(id, name, about) name,
    STUDY_METRICS(STUDY_METRIC_NAME)
#undef STUDY_METRIC_NAME
};
const char *const study_metric_about[STUDY_METRIC_COUNT] = {
#define STUDY_METRIC_ABOUT(id, name, about) about,
    STUDY_METRICS(STUDY_METRIC_ABOUT)
#undef STUDY_METRIC_ABOUT
};

int study_metric_find(const char *name)
{
    for (int m = 0; m < STUDY_METRIC_COUNT; m++)
        if (strcmp(name, study_metric_names[m]) == 0) return m;
    return -1;
}

int study_metric_extras(study_metric m, const char *names[STUDY_MAX_EXTRA])
{
    static const char *const density[] = {"interior_max", "surface_error", "surface_ratio", "surface_ratio_exact"};
    static const char *const surface[] = {"interior_error", "surface_max", "surface_ratio", "surface_ratio_exact"};
    static const char *const hydro[] = {"particle_rms", "scatter", "depth", "layers"};
    static const char *const tg[] = {"rate_fit", "rate_exact", "rate_error_signed", "mode_rate_error"};
    static const char *const comp[] = {"run_max", "mean_error", "steps_per_sim_s", "iterations_per_step",
                                       "ms_per_sim_s"};
    const char *const *src = m == STUDY_METRIC_DENSITY           ? density
                             : m == STUDY_METRIC_DENSITY_SURFACE ? surface
                             : m == STUDY_METRIC_HYDROSTATIC     ? hydro
                             : m == STUDY_METRIC_COMPRESSION     ? comp
                                                                 : tg;
    const int n = m == STUDY_METRIC_COMPRESSION ? 5 : 4;
    for (int i = 0; i < STUDY_MAX_EXTRA; i++) names[i] = i < n ? src[i] : NULL;
    return n;
}

static bool has_tg_block(const sph_scene_def *def)
{
    for (int b = 0; b < def->n_blocks; b++)
        if (def->blocks[b].field == SPH_VFIELD_TAYLOR_GREEN) return true;
    return false;
}

/* Every block spans the domain's width (x, and z in 3D) and sits on its floor. */
static bool is_tank(const sph_scene_def *def)
{
    if (def->n_blocks == 0) return false;
    for (int b = 0; b < def->n_blocks; b++) {
        const sph_block_def *k = &def->blocks[b];
        for (int d = 0; d < def->dim; d++) {
            if (d == 1) continue;
            double tol = 1e-4 * (def->domain_max[d] - def->domain_min[d]);
            if (fabs(k->min[d] - def->domain_min[d]) > tol || fabs(k->max[d] - def->domain_max[d]) > tol)
                return false;
        }
    }
    double lowest = INFINITY;
    for (int b = 0; b < def->n_blocks; b++) lowest = fmin(lowest, def->blocks[b].min[1]);
    return fabs(lowest - def->domain_min[1]) <= 1e-4 * (def->domain_max[1] - def->domain_min[1]);
}

int study_metric_guess(const sph_scene_def *def)
{
    unsigned e = def->effects;
    if (has_tg_block(def)) return STUDY_METRIC_TAYLOR_GREEN;
    if ((e & SPH_EFFECT(GRAVITY)) && (e & SPH_EFFECT(PRESSURE)) && (e & SPH_EFFECT(WALLS)) && is_tank(def))
        return STUDY_METRIC_HYDROSTATIC;
    if ((e & SPH_EFFECT(DENSITY)) && !(e & SPH_EFFECT(PRESSURE)) && def->n_blocks == 1) return STUDY_METRIC_DENSITY;
    return -1;
}

bool study_metric_check(study_metric m, const sph_scene_def *def, char *why, size_t n)
{
    unsigned e = def->effects;
    why[0] = '\0';
    switch (m) {
    case STUDY_METRIC_DENSITY:
    case STUDY_METRIC_DENSITY_SURFACE:
        if (!sph_scene_needs_density(def))
            snprintf(why, n, "the %s metric needs density: list density in [scene] effects", study_metric_names[m]);
        else if (def->n_blocks != 1)
            snprintf(why, n, "the %s metric measures one block; the scene has %d", study_metric_names[m],
                     def->n_blocks);
        break;
    case STUDY_METRIC_HYDROSTATIC:
        if (!(e & SPH_EFFECT(GRAVITY)) || !(e & SPH_EFFECT(PRESSURE)) || !(e & SPH_EFFECT(WALLS)))
            snprintf(why, n, "the hydrostatic metric needs a tank: effects gravity, pressure and walls");
        else if (def->gravity[0] != 0 || def->gravity[1] >= 0 || (def->dim == 3 && def->gravity[2] != 0))
            snprintf(why, n, "the hydrostatic metric needs gravity straight down, along -y (gravity = 0 -g)");
        else if (def->periodic & 2u)
            snprintf(why, n, "the hydrostatic metric needs a floor: y must not be periodic");
        break;
    case STUDY_METRIC_TAYLOR_GREEN: {
        double lx = (double)def->domain_max[0] - def->domain_min[0], ly = (double)def->domain_max[1] - def->domain_min[1];
        if (!has_tg_block(def))
            snprintf(why, n, "the taylor-green metric needs a block with field = taylor-green");
        else if ((def->periodic & 3u) != 3u)
            snprintf(why, n, "the taylor-green metric needs [domain] periodic = x y");
        else if (fabs(lx - ly) > 1e-6 * lx)
            snprintf(why, n, "the taylor-green metric needs a square domain (x length %g m, y length %g m)", lx, ly);
        else if (!(e & SPH_EFFECT(VISCOSITY)) || !(def->viscosity > 0))
            snprintf(why, n, "the taylor-green metric needs viscosity (effect viscosity, [physics] viscosity > 0)");
        else if (e & (SPH_EFFECT(GRAVITY) | SPH_EFFECT(WALLS) | SPH_EFFECT(INTERACTION)))
            snprintf(why, n, "the taylor-green metric needs a free vortex: no gravity, walls or interaction effect");
        break;
    }
    case STUDY_METRIC_COMPRESSION:
        if (!(e & SPH_EFFECT(PRESSURE)))
            snprintf(why, n, "the compression metric needs pressure: list pressure in [scene] effects");
        break;
    default: snprintf(why, n, "unknown metric"); break;
    }
    return why[0] == '\0';
}

void study_result_timed(study_metric m, study_result *r)
{
    if (m == STUDY_METRIC_COMPRESSION) r->extra[4] = r->t_end > 0 ? r->wall_ms / r->t_end : NAN;
}

/* ---- what a metric records during a run ----------------------------------- */

typedef struct line_fit { /* least squares y = a + b t */
    double n, st, sy, stt, sty;
} line_fit;

static void fit_add(line_fit *f, double t, double y)
{
    if (!isfinite(y)) return;
    f->n += 1;
    f->st += t;
    f->sy += y;
    f->stt += t * t;
    f->sty += t * y;
}

static double fit_slope(const line_fit *f)
{
    double den = f->n * f->stt - f->st * f->st;
    return f->n >= 2 && den > 0 ? (f->n * f->sty - f->st * f->sy) / den : NAN;
}

typedef struct probe {
    study_metric m;
    /* taylor-green */
    line_fit fit_e, fit_a;
    double k; /* [1/m] wave number 2 pi / L */
    /* hydrostatic: sums over the window, per particle id */
    double *sum_p, *sum_x[3];
    long samples;
    /* compression: over the steps */
    double comp_max;     /* [1] largest rho/rho_held - 1 */
    double comp_max_dt;  /* [s] sum of dt x the step's largest compression */
    double comp_mean_dt; /* [s] sum of dt x the step's mean compression */
    double comp_t;       /* [s] sum of dt */
    double iterations;   /* [1] pressure-solver iterations, both solves */
} probe;

static void probe_free(probe *pr)
{
    free(pr->sum_p);
    for (int d = 0; d < 3; d++) free(pr->sum_x[d]);
}

/* E_kin, and the amplitude of the Taylor-Green mode: the projection of the
 * velocities on the unit vortex at the particles' positions. */
static void tg_sample(probe *pr, const sph_sim *sim)
{
    /* on a backend sim->P is a host copy, refreshed on demand: read stale, the GL study saw no decay */
    sph_sim_sync(sim, SPH_SYNC_FIELD(SPH_FIELD_POS) | SPH_SYNC_FIELD(SPH_FIELD_VEL) | SPH_SYNC_FIELD(SPH_FIELD_MASS));
    const sph_particles *P = &sim->P;
    double ekin = 0, num = 0, den = 0, k = pr->k;
    double x0 = sim->def.domain_min[0], y0 = sim->def.domain_min[1];
    for (uint32_t i = 0; i < sim->n; i++) {
        double vx = P->vel[0][i], vy = P->vel[1][i], m = P->mass[i];
        double v2 = vx * vx + vy * vy;
        if (sim->dim == 3) v2 += (double)P->vel[2][i] * P->vel[2][i];
        ekin += 0.5 * m * v2;
        double kx = k * (P->pos[0][i] - x0), ky = k * (P->pos[1][i] - y0);
        double ux = sin(kx) * cos(ky), uy = -cos(kx) * sin(ky);
        num += m * (vx * ux + vy * uy);
        den += m * (ux * ux + uy * uy);
    }
    fit_add(&pr->fit_e, sim->t, ekin > 0 ? log(ekin) : NAN);
    double a = den > 0 ? num / den : 0;
    fit_add(&pr->fit_a, sim->t, a > 0 ? log(a) : NAN);
}

static bool probe_begin(probe *pr, study_metric m, const sph_sim *sim, char *why, size_t n)
{
    memset(pr, 0, sizeof *pr);
    pr->m = m;
    if (m == STUDY_METRIC_TAYLOR_GREEN) {
        pr->k = 2.0 * 3.14159265358979323846 / ((double)sim->def.domain_max[0] - sim->def.domain_min[0]);
        tg_sample(pr, sim); /* t = 0 */
    } else if (m == STUDY_METRIC_HYDROSTATIC) {
        size_t cnt = sim->n ? sim->n : 1;
        pr->sum_p = calloc(cnt, sizeof *pr->sum_p);
        bool ok = pr->sum_p != NULL;
        for (int d = 0; d < sim->dim; d++) ok &= (pr->sum_x[d] = calloc(cnt, sizeof *pr->sum_x[d])) != NULL;
        if (!ok) {
            probe_free(pr);
            snprintf(why, n, "out of memory for the hydrostatic averages");
            return false;
        }
    }
    return true;
}

/* The compression of the step just taken, summed at the positions it
 * reached against the density the pressure holds at rest: rho0 for the
 * equation of state, the initial lattice's sum for the solvers
 * (sph_sim_compression; docs/accuracy.md, "Incompressible pressure
 * solvers"). Particles below it (the free surface's deficiency) count as 0
 * in the mean: it measures compression only. The density pass's rho is
 * not it: summed at x + dt v before the pressure acts, it read a solver's
 * 0.1 % as 0.7 to 0.9 %. */
static void compression_sample(probe *pr, const sph_sim *sim)
{
    double mx, mean;
    sph_sim_compression(sim, &mx, &mean);
    pr->comp_max = fmax(pr->comp_max, mx);
    pr->comp_mean_dt += sim->dt * mean;
    pr->comp_max_dt += sim->dt * fmax(mx, 0.0);
    pr->comp_t += sim->dt;
    if (sim->def.pressure_solver != SPH_PSOLVER_EOS)
        pr->iterations += sim->solver.iterations + sim->solver.div_iterations;
}

/* After each step; done: the fraction of the run completed. */
static void probe_step(probe *pr, const sph_sim *sim, double done)
{
    if (pr->m == STUDY_METRIC_COMPRESSION) {
        compression_sample(pr, sim);
    } else if (pr->m == STUDY_METRIC_TAYLOR_GREEN) {
        tg_sample(pr, sim);
    } else if (pr->m == STUDY_METRIC_HYDROSTATIC && done > 0.5) {
        /* the measurement window: the second half of the run (every field the pressure may come from) */
        sph_sim_sync(sim, SPH_SYNC_ALL);
        const sph_particles *P = &sim->P;
        for (uint32_t i = 0; i < sim->n; i++) {
            uint32_t id = P->id[i];
            pr->sum_p[id] += sph_sim_pressure(sim, i); /* p of the equation of state or of the solver */
            for (int d = 0; d < sim->dim; d++) pr->sum_x[d][id] += P->pos[d][i];
        }
        pr->samples++;
    }
}

/* ---- the errors ----------------------------------------------------------- */

static void measure_density(const sph_sim *sim, study_metric m, study_result *out)
{
    const sph_scene_def *def = &sim->def;
    const sph_block_def *blk = &def->blocks[0];
    const sph_particles *P = &sim->P;
    const float h = def->h, s = blk->spacing;
    const double rho0 = def->rest_density;
    const bool walls_count = sph_scene_wall_volume(def) || sph_scene_wall_particles(def);
    /* the block's lattice fills [min, min + nodes s] on each axis; a face is
     * free unless a wall that counts (volume model) or a periodic axis is there */
    double lo[3], hi[3];
    bool free_lo[3], free_hi[3];
    for (int d = 0; d < sim->dim; d++) {
        lo[d] = blk->min[d];
        hi[d] = blk->min[d] + (double)sph_block_nodes(def, 0, d) * s;
        double tol = 1e-3 * s;
        bool per = (def->periodic >> d) & 1u;
        free_lo[d] = !per && !(walls_count && fabs(lo[d] - def->domain_min[d]) < tol);
        free_hi[d] = !per && !(walls_count && fabs(hi[d] - def->domain_max[d]) < tol);
    }
    double in_sum = 0, in_max = 0, sf_sum = 0, sf_max = 0, ratio = 0, ratio_exact = 0;
    long in_n = 0, sf_n = 0, row_n = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(P, i)) continue; /* wall particles (wall_model = particles) are no part of the block */
        int near = 0;
        double dist = INFINITY;
        for (int d = 0; d < sim->dim; d++) {
            double x = P->pred[0] ? P->pred[d][i] : P->pos[d][i];
            if (free_lo[d] && x - lo[d] < h) near++, dist = fmin(dist, x - lo[d]);
            if (free_hi[d] && hi[d] - x < h) near++, dist = fmin(dist, hi[d] - x);
        }
        double r = P->rho[i] / rho0;
        if (near == 0) {
            double e = r - 1.0;
            in_sum += e * e;
            in_max = fmax(in_max, fabs(e));
            in_n++;
        } else if (near == 1) {
            float area;
            double want = 1.0 - sph_kernel_wall(&sim->k_density, (float)fmax(dist, 0.0), &area);
            double e = r - want;
            sf_sum += e * e;
            sf_max = fmax(sf_max, fabs(e));
            sf_n++;
            if (dist < s) { /* the outermost row */
                ratio += r;
                ratio_exact += want;
                row_n++;
            }
        }
    }
    double in_rms = in_n ? sqrt(in_sum / in_n) : NAN, sf_rms = sf_n ? sqrt(sf_sum / sf_n) : NAN;
    double rr = row_n ? ratio / row_n : NAN, rre = row_n ? ratio_exact / row_n : NAN;
    if (m == STUDY_METRIC_DENSITY) {
        out->error = in_rms;
        out->extra[0] = in_n ? in_max : NAN;
        out->extra[1] = sf_rms;
    } else {
        out->error = sf_rms;
        out->extra[0] = in_rms;
        out->extra[1] = sf_n ? sf_max : NAN;
    }
    out->extra[2] = rr;
    out->extra[3] = rre;
    if (!in_n && m == STUDY_METRIC_DENSITY)
        snprintf(out->note, sizeof out->note, "no particle is h = %g m inside the block: make it larger", h);
    if (!sf_n && m == STUDY_METRIC_DENSITY_SURFACE)
        snprintf(out->note, sizeof out->note, "no particle near exactly one free face: the block has no free surface");
}

static void measure_hydrostatic(const sph_sim *sim, const probe *pr, study_result *out)
{
    const sph_scene_def *def = &sim->def;
    const int dim = sim->dim;
    const double rho0 = def->rest_density, g = -(double)def->gravity[1], h = def->h;
    const double floor_y = def->domain_min[1];
    double width = (double)def->domain_max[0] - def->domain_min[0];
    if (dim == 3) width *= (double)def->domain_max[2] - def->domain_min[2];
    double mass = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i)) mass += sim->P.mass[i]; /* the fluid's: wall particles are outside the box */
    const double H = floor_y + mass / (rho0 * width); /* the free surface the fluid's mass gives */
    const double depth = H - floor_y, scale = rho0 * g * depth;
    out->extra[2] = depth;
    if (pr->samples == 0 || !(depth > 2 * h)) {
        snprintf(out->note, sizeof out->note,
                 pr->samples ? "the fluid (%.3g m deep) is not deeper than 2 h = %.3g m: no interior layer"
                             : "no step in the measurement window",
                 depth, 2 * h);
        return;
    }
    /* the depth comes from float masses: 0.3 m deep at h = 0.06 read 0.299999982, and 2.9999997 layers floored to 2 */
    int layers = (int)floor((depth - 2 * h) / h + 1e-6);
    if (layers < 1) layers = 1;
    if (layers > 4096) layers = 4096;
    const double lh = (depth - 2 * h) / layers;
    out->extra[3] = layers;
    double *lp = calloc((size_t)layers, sizeof *lp), *ly = calloc((size_t)layers, sizeof *ly);
    long *ln = calloc((size_t)layers, sizeof *ln);
    int *layer_of = malloc((size_t)(sim->n ? sim->n : 1) * sizeof *layer_of);
    if (!lp || !ly || !ln || !layer_of) {
        snprintf(out->note, sizeof out->note, "out of memory");
        goto done;
    }
    const double inv = 1.0 / (double)pr->samples;
    for (uint32_t id = 0; id < sim->n; id++) {
        layer_of[id] = -1;
        double y = pr->sum_x[1][id] * inv;
        bool inside = y >= floor_y + h && y <= H - h;
        for (int d = 0; d < dim; d++) {
            if (d == 1) continue;
            double x = pr->sum_x[d][id] * inv;
            inside &= x >= def->domain_min[d] + h && x <= def->domain_max[d] - h;
        }
        if (!inside) continue;
        int l = (int)((y - floor_y - h) / lh);
        if (l >= layers) l = layers - 1;
        if (l < 0) l = 0;
        layer_of[id] = l;
        lp[l] += pr->sum_p[id] * inv;
        ly[l] += y;
        ln[l]++;
    }
    double se = 0, sc = 0, sp = 0;
    long m = 0;
    for (int l = 0; l < layers; l++) {
        if (!ln[l]) continue;
        lp[l] /= ln[l];
        ly[l] /= ln[l];
        double e = (lp[l] - rho0 * g * (H - ly[l])) / scale;
        se += ln[l] * e * e;
        m += ln[l];
    }
    for (uint32_t id = 0; id < sim->n; id++) {
        int l = layer_of[id];
        if (l < 0) continue;
        double p = pr->sum_p[id] * inv, y = pr->sum_x[1][id] * inv;
        double c = (p - lp[l]) / scale, e = (p - rho0 * g * (H - y)) / scale;
        sc += c * c;
        sp += e * e;
    }
    if (m) {
        out->error = sqrt(se / m);
        out->extra[0] = sqrt(sp / m);
        out->extra[1] = sqrt(sc / m);
    } else {
        snprintf(out->note, sizeof out->note, "no particle in the interior (h from the walls, h below the surface)");
    }
done:
    free(lp);
    free(ly);
    free(ln);
    free(layer_of);
}

static void measure_taylor_green(const sph_sim *sim, const probe *pr, study_result *out)
{
    double exact = 4.0 * sim->def.viscosity * pr->k * pr->k;
    double rate = -fit_slope(&pr->fit_e), rate_a = -2.0 * fit_slope(&pr->fit_a);
    out->extra[0] = rate;
    out->extra[1] = exact;
    out->extra[2] = rate / exact - 1.0;
    out->extra[3] = rate_a / exact - 1.0;
    out->error = fabs(rate / exact - 1.0);
    if (!isfinite(rate)) snprintf(out->note, sizeof out->note, "fewer than two samples of E_kin: run more steps");
}

bool study_run(const sph_scene_def *def, study_metric m, long steps, double until, int threads,
               study_progress_fn progress, void *ctx, study_result *out, char *why, size_t n)
{
    memset(out, 0, sizeof *out);
    out->error = NAN;
    for (int i = 0; i < STUDY_MAX_EXTRA; i++) out->extra[i] = NAN;
    if (!study_metric_check(m, def, why, n)) return false;
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(def, threads, &sim, &err) != SPH_ERR_OK) {
        snprintf(why, n, "%s", err.msg);
        return false;
    }
    if (until >= 0) sph_sim_end_at(sim, until); /* the last step ends on it */
    probe pr;
    if (!probe_begin(&pr, m, sim, why, n)) {
        sph_sim_destroy(sim);
        return false;
    }
    double wall = 0, shown = sph_now_ms();
    for (;;) {
        if (until >= 0 ? sph_sim_reached(sim, until) : (long)sim->step >= steps) break;
        double t0 = sph_now_ms();
        sph_sim_step(sim);
        double t1 = sph_now_ms();
        wall += t1 - t0;
        if (sim->alarm.raised) break;
        double done = until > 0 ? sim->t / until : steps > 0 ? (double)sim->step / (double)steps : 1.0;
        probe_step(&pr, sim, done);
        if (progress && t1 - shown >= 100) {
            shown = t1;
            progress(ctx, sim, done);
        }
    }
    out->particles = sim->n;
    out->steps = sim->step;
    out->t_end = sim->t;
    out->wall_ms = wall;
    if (sim->alarm.raised) {
        out->stopped = true;
        char report[4096];
        sph_sim_alarm_report(sim, report, sizeof report);
        char *nl = strchr(report, '\n');
        if (nl) *nl = '\0';
        snprintf(out->note, sizeof out->note, "stopped by the watchdog: %.400s", report);
    } else if (m == STUDY_METRIC_DENSITY || m == STUDY_METRIC_DENSITY_SURFACE) {
        sph_sim_sync(sim, SPH_SYNC_ALL); /* a backend's host copy, fresh for the measurement */
        if (sim->step == 0)
            snprintf(out->note, sizeof out->note, "no step ran: density is computed by the first step");
        else
            measure_density(sim, m, out);
    } else if (m == STUDY_METRIC_HYDROSTATIC) {
        sph_sim_sync(sim, SPH_SYNC_ALL);
        measure_hydrostatic(sim, &pr, out);
    } else if (m == STUDY_METRIC_COMPRESSION) {
        if (pr.comp_t > 0 && sim->step > 0) {
            /* the error: each step's largest compression, averaged over time (the run's largest, extra 0,
             * is one particle at one impact) */
            out->error = pr.comp_max_dt / pr.comp_t;
            out->extra[0] = pr.comp_max;
            out->extra[1] = pr.comp_mean_dt / pr.comp_t;
            out->extra[2] = sim->t > 0 ? (double)sim->step / sim->t : NAN;
            out->extra[3] = sim->def.pressure_solver != SPH_PSOLVER_EOS ? pr.iterations / (double)sim->step : 0;
            study_result_timed(m, out);
            if (sim->solver.capped || sim->solver.stopped)
                snprintf(out->note, sizeof out->note,
                         "%llu pressure solve%s capped at solver_max_iterations, %llu stopped where their error "
                         "rose",
                         (unsigned long long)sim->solver.capped, sim->solver.capped == 1 ? "" : "s",
                         (unsigned long long)sim->solver.stopped);
        } else {
            snprintf(out->note, sizeof out->note, "no step ran");
        }
    } else {
        measure_taylor_green(sim, &pr, out);
    }
    probe_free(&pr);
    sph_sim_destroy(sim);
    return true;
}
