/* The watchdog: after every pass, the fields the pass wrote are checked for
 * the first non-finite value or runaway (a speed or density beyond what the
 * scene can produce). The step stops there, with the state kept as it was
 * when found, so it can be dumped and shown. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "sph_sim.h"

bool sph_sim_field(const sph_sim *sim, sph_field_id id, sph_field *out)
{
    if ((int)id < 0 || id >= SPH_FIELD_COUNT) return false;
    sph_sim_sync(sim, SPH_SYNC_FIELD(id));
    const sph_field_info *info = &sph_field_infos[id];
    float *const *arrays = sim->P.field[id];
    if (!arrays[0]) return false;
    memset(out, 0, sizeof *out);
    out->name = info->name;
    out->unit = sph_field_unit(id, sim->dim);
    out->about = info->about;
    out->ncomp = info->vector ? sim->dim : 1;
    for (int d = 0; d < out->ncomp; d++) out->c[d] = arrays[d];
    return true;
}

sph_mask sph_sim_mask_present(const sph_sim *sim, sph_mask m)
{
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if ((m & SPH_FIELD_BIT(f)) && !sim->P.field[f][0]) m &= ~SPH_FIELD_BIT(f);
    return m;
}

static void raise_alarm(sph_sim *sim, int pass, uint32_t i, int field, int comp, float value, const char *what)
{
    sph_alarm *a = &sim->alarm;
    a->raised = true;
    a->step = sim->step;
    a->pass = a->checked_after = pass;
    a->particle = i;
    a->field = field;
    a->comp = comp;
    a->value = value;
    snprintf(a->what, sizeof a->what, "%s", what);
}

/* Index of the first particle whose field is bad, or n. */
static uint32_t first_bad(const sph_sim *sim, const sph_field *f, sph_field_check check)
{
    const int n = (int)sim->n, nc = f->ncomp;
    const float vb2 = sim->speed_bound * sim->speed_bound, rb = sim->density_bound;
    int first = n;
#pragma omp parallel for schedule(static) reduction(min : first) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        float s2 = 0;
        bool bad = false;
        for (int c = 0; c < nc; c++) {
            float v = f->c[c][i];
            bad |= !isfinite(v);
            s2 += v * v;
        }
        if (check == SPH_CHECK_SPEED) bad |= s2 > vb2;
        if (check == SPH_CHECK_DENSITY) bad |= !(f->c[0][i] > 0.0f) || f->c[0][i] > rb;
        if (bad && i < first) first = i;
    }
    return (uint32_t)first;
}

/* Of the particles past the bound, the one to name: the first non-finite one
 * (where a blow-up shows first), else the fastest, else the density furthest
 * out of its bounds. The first bad one in memory order is an arbitrary one of
 * them, and a user who looks finds others faster. Only when the alarm is
 * raised, so a serial scan. */
static uint32_t worst_bad(const sph_sim *sim, const sph_field *f, sph_field_check check, uint32_t first)
{
    uint32_t worst = first;
    float worst_score = -INFINITY;
    for (uint32_t i = first; i < sim->n; i++) {
        float s2 = 0;
        for (int c = 0; c < f->ncomp; c++) {
            if (!isfinite(f->c[c][i])) return i;
            s2 += f->c[c][i] * f->c[c][i];
        }
        /* a density at or below 0 is worse than any too large one */
        float score = check == SPH_CHECK_SPEED     ? s2
                      : check == SPH_CHECK_DENSITY ? (f->c[0][i] > 0.0f ? f->c[0][i] : INFINITY)
                                                   : -INFINITY;
        if (score > worst_score) worst_score = score, worst = i;
    }
    return worst;
}

void sph_watchdog_check(sph_sim *sim, int pass)
{
    sph_mask bits = sph_passes[pass]->writes;
    for (int f = 0; f < SPH_FIELD_COUNT && !sim->alarm.raised; f++) {
        sph_field fd;
        if (!(bits & SPH_FIELD_BIT(f)) || !sph_sim_field(sim, (sph_field_id)f, &fd)) continue;
        const sph_field_check check = sph_field_infos[f].check;
        uint32_t i = first_bad(sim, &fd, check);
        if (i >= sim->n) continue;
        i = worst_bad(sim, &fd, check, i);
        char what[256];
        int comp = 0;
        for (int c = 0; c < fd.ncomp; c++)
            if (!isfinite(fd.c[c][i])) comp = c;
        float value = fd.c[comp][i];
        if (!isfinite(value)) {
            snprintf(what, sizeof what, "%s is not finite", fd.name);
        } else if (check == SPH_CHECK_SPEED) {
            float s2 = 0;
            for (int c = 0; c < fd.ncomp; c++) s2 += fd.c[c][i] * fd.c[c][i];
            value = sqrtf(s2);
            snprintf(what, sizeof what,
                     "speed %.4g m/s is above the bound %.4g m/s, 4 times the speed the scene can make plus 1 m/s "
                     "(that speed %.3g m/s: a fall %.3g m/s, the blocks, the passes' forces, cohesion and surface "
                     "tension, compression)",
                     value, sim->speed_bound, sim->speed_scale, sim->speed_fall);
        } else {
            snprintf(what, sizeof what, "%s %.4g is outside (0, %.4g], the bound the scene implies", fd.about,
                     value, sim->density_bound);
        }
        raise_alarm(sim, pass, i, f, comp, value, what);
    }
}

/* Energy: kinetic + gravitational + internal may only fall (viscosity and
 * wall damping remove it) except for the scheme's own error. A gain of half
 * its step-0 scale (plus that of 0.5 m/s over the whole mass, for a scene
 * that starts with almost none) is a runaway even when every speed is below
 * its bound. A pass whose force does work from outside (sph_pass.does_work:
 * the mouse) and a live change of parameters, which changes the internal
 * energy, move the reference. With a backend the state is
 * downloaded for this, so it is checked every 64 steps only. On the CPU it
 * runs every step, a serial pass over the particles: about 0.5 ms a step at
 * 55,000 particles (5 %), not counted in any pass and off in `sphlab bench`. */
void sph_watchdog_energy(sph_sim *sim, int pass)
{
    if (sim->alarm.raised || (sim->backend && sim->step % 64 != 0)) return;
    sph_stats s;
    sph_sim_stats(sim, &s);
    const double e = sph_stats_energy(&s);
    double mass = 0;
    for (uint32_t i = 0; i < sim->n; i++) mass += sim->P.mass[i];
    if (!isfinite(sim->energy_start) || sph_sim_work_done_by(sim)) {
        sim->energy_start = e;
        sim->energy_scale = fmax(sim->energy_scale, fabs(s.ekin) + fabs(s.epot) + fabs(s.eint));
        return;
    }
    const double allowed = 0.5 * (sim->energy_scale + 0.5 * mass * 0.25);
    if (!(e - sim->energy_start > allowed) && isfinite(e)) return;
    uint32_t fastest = 0;
    float v2max = -1;
    for (uint32_t i = 0; i < sim->n; i++) {
        float v2 = 0;
        for (int d = 0; d < sim->dim; d++) v2 += sim->P.vel[d][i] * sim->P.vel[d][i];
        if (v2 > v2max) v2max = v2, fastest = i;
    }
    char what[256]; /* raise_alarm keeps 256 */
    const char *u = sim->dim == 2 ? "J/m" : "J"; /* a 2D scene's energy is per metre of depth, as run's summary */
    snprintf(what, sizeof what,
             "total energy %.4g %s grew by %.3g %s since step 0 (bound %.3g %s: half its scale %.3g %s); fastest "
             "particle shown",
             e, u, e - sim->energy_start, u, allowed, u, sim->energy_scale, u);
    raise_alarm(sim, pass, fastest, SPH_FIELD_VEL, 0, sqrtf(fmaxf(v2max, 0.0f)), what);
}

static void append(char *out, size_t n, size_t *used, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static void append(char *out, size_t n, size_t *used, const char *fmt, ...)
{
    if (*used >= n) return;
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(out + *used, n - *used, fmt, ap);
    va_end(ap);
    if (k > 0) *used += (size_t)k;
    if (*used > n) *used = n;
}

static void particle_values(const sph_sim *sim, uint32_t i, char *out, size_t n, size_t *used)
{
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        sph_field fd;
        if (f == SPH_FIELD_MASS || !sph_sim_field(sim, (sph_field_id)f, &fd)) continue;
        append(out, n, used, " %s=", fd.name);
        if (fd.ncomp > 1) append(out, n, used, "(");
        for (int c = 0; c < fd.ncomp; c++) append(out, n, used, "%s%.5g", c ? ", " : "", fd.c[c][i]);
        if (fd.ncomp > 1) append(out, n, used, ")");
    }
}

void sph_sim_alarm_report(const sph_sim *sim, char *out, size_t n)
{
    const sph_alarm *a = &sim->alarm;
    size_t used = 0;
    out[0] = '\0';
    if (!a->raised) return;
    sph_sim_sync(sim, SPH_SYNC_ALL); /* values and neighbours come from the host copy */
    uint32_t i = a->particle;
    if (a->checked_after != a->pass) /* a backend's one scan a step: the pass that wrote the field is not known */
        append(out, n, &used,
               "watchdog: step %llu (t = %.6g s, dt = %.3g s), found after pass '%s' (the %s backend is checked once "
               "a step, there): particle %u (id %u): %s\n",
               (unsigned long long)a->step, sim->t, sim->dt, sph_passes[a->checked_after]->name,
               sim->backend ? sim->backend->name : "device", i, sim->P.id[i], a->what);
    else
        append(out, n, &used, "watchdog: step %llu (t = %.6g s, dt = %.3g s), after pass '%s': particle %u (id %u): %s\n",
               (unsigned long long)a->step, sim->t, sim->dt, sph_passes[a->pass]->name, i, sim->P.id[i], a->what);
    append(out, n, &used, "  values:");
    particle_values(sim, i, out, n, &used);
    append(out, n, &used, "\n");
    const sph_search_data *S = &sim->S;
    if (S->nbr_start) {
        const sph_nbr_row row = sph_nbr_row_of(S, i);
        append(out, n, &used, "  %u neighbours%s\n", row.n, row.n > 8 ? " (first 8)" : "");
        for (uint32_t k = 0; k < row.n && k < 8; k++) {
            uint32_t j = sph_nbr_at(&row, k);
            float r2 = 0;
            for (int d = 0; d < sim->dim; d++) {
                float dx = sim->P.pred[d][j] - sim->P.pred[d][i];
                if (sim->period[d] > 0) dx -= sim->period[d] * rintf(dx * sim->inv_period[d]);
                r2 += dx * dx;
            }
            append(out, n, &used, "    %u: r=%.4g m", j, sqrtf(r2));
            particle_values(sim, j, out, n, &used);
            append(out, n, &used, "\n");
        }
    }
    if (sim->def.pressure_solver != SPH_PSOLVER_EOS && (sim->def.effects & SPH_EFFECT(PRESSURE))) {
        /* the solvers' dt follows the flow speed, which is 0 at the start: [time] dt is then the only cap */
        append(out, n, &used,
               "  the state is kept as it was when this was found (--dump writes it). Usual causes with "
               "pressure_solver = %s: a time step too long for the solve (its dt follows the flow speed, capped by "
               "[time] dt = %g s: try a smaller [time] dt or cfl, now %g), a solver_tolerance too loose (now %g), "
               "or particles forced together.\n",
               sph_pressure_solver_names[sim->def.pressure_solver], (double)sim->def.dt, (double)sim->def.cfl,
               (double)sim->def.solver_tolerance);
        if (sim->solver.capped || sim->solver.stopped)
            /* a solve that ends short of its tolerance leaves its error to the next step: the runaway often
             * starts there (a 240,000-particle 3D dam break: capped from step 3, its error rising after 300
             * iterations) */
            append(out, n, &used,
                   "  the solves ended short of their tolerance before this: %llu at solver_max_iterations = %d, %llu "
                   "where their error rose (over %llu steps; the last step's density error %.3g %%, the tolerance "
                   "%g %%). More iterations help only while the error still falls; a smaller dt helps both.\n",
                   (unsigned long long)sim->solver.capped, sim->def.solver_max_iterations,
                   (unsigned long long)sim->solver.stopped, (unsigned long long)a->step,
                   100.0 * sim->solver.density_error, 100.0 * sim->def.solver_tolerance);
    } else {
        append(out, n, &used,
               "  the state is kept as it was when this was found (--dump writes it). Usual causes: a time step "
               "above the CFL limit (try [time] cfl = 0.4), a stiffness too high for dt, or particles forced "
               "together.\n");
    }
}
