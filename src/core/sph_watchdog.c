/* The watchdog: after every pass, the fields the pass wrote are checked for
#include <stdarg.h>
 * the first non-finite value or runaway (a speed or density beyond what the
 * scene can produce). The step stops there, with the state kept as it was
 * when found, so it can be dumped and shown. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sph_sim.h"

static const char *const field_names[SPH_FIELD_COUNT] = {
#define SPH_FIELD_NAME(id, name, unit, ncomp, about) name,
    SPH_FIELDS(SPH_FIELD_NAME)
#undef SPH_FIELD_NAME
};
static const char *const field_units[SPH_FIELD_COUNT] = {
#define SPH_FIELD_UNIT(id, name, unit, ncomp, about) unit,
    SPH_FIELDS(SPH_FIELD_UNIT)
#undef SPH_FIELD_UNIT
};
static const char *const field_about[SPH_FIELD_COUNT] = {
#define SPH_FIELD_ABOUT(id, name, unit, ncomp, about) about,
    SPH_FIELDS(SPH_FIELD_ABOUT)
#undef SPH_FIELD_ABOUT
};
static const int field_ncomp[SPH_FIELD_COUNT] = {
#define SPH_FIELD_NCOMP(id, name, unit, ncomp, about) ncomp,
    SPH_FIELDS(SPH_FIELD_NCOMP)
#undef SPH_FIELD_NCOMP
};

int sph_field_find(const char *name)
{
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (strcmp(name, field_names[f]) == 0) return f;
    return -1;
}

bool sph_sim_field(const sph_sim *sim, sph_field_id id, sph_field *out)
{
    const sph_particles *P = &sim->P;
    if ((int)id >= 0 && id < SPH_FIELD_COUNT) sph_sim_sync(sim, SPH_SYNC_FIELD(id));
    float *const *vec = NULL;
    float *scalar = NULL;
    switch (id) {
    case SPH_FIELD_POS: vec = P->pos; break;
    case SPH_FIELD_VEL: vec = P->vel; break;
    case SPH_FIELD_PRED: vec = P->pred; break;
    case SPH_FIELD_RHO: scalar = P->rho; break;
    case SPH_FIELD_P: scalar = P->p; break;
    case SPH_FIELD_VOL: scalar = P->vol; break;
    case SPH_FIELD_PRHO2: scalar = P->p_rho2; break;
    case SPH_FIELD_ACC_P: vec = P->acc_p; break;
    case SPH_FIELD_ACC_V: vec = P->acc_v; break;
    case SPH_FIELD_ACC_I: vec = P->acc_i; break;
    case SPH_FIELD_MASS: scalar = P->mass; break;
    default: return false;
    }
    memset(out, 0, sizeof *out);
    out->name = field_names[id];
    out->unit = field_units[id];
    out->about = field_about[id];
    if (vec) {
        if (!vec[0]) return false;
        out->ncomp = sim->dim;
        for (int d = 0; d < sim->dim; d++) out->c[d] = vec[d];
    } else {
        if (!scalar) return false;
        out->ncomp = field_ncomp[id];
        out->c[0] = scalar;
    }
    return true;
}

/* Field bits of a pass's `writes` list ("vel pred"); names that are not
 * particle fields (the index, the lists) are not checked. */
unsigned sph_watchdog_fields(const char *writes)
{
    unsigned bits = 0;
    char word[32];
    const char *p = writes;
    while (*p) {
        while (*p == ' ') p++;
        int n = 0;
        while (p[n] && p[n] != ' ') n++;
        if (n > 0 && n < (int)sizeof word) {
            memcpy(word, p, (size_t)n);
            word[n] = '\0';
            int f = sph_field_find(word);
            if (f >= 0) bits |= 1u << f;
        }
        p += n;
    }
    return bits;
}

static void raise_alarm(sph_sim *sim, int pass, uint32_t i, int field, int comp, float value, const char *what)
{
    sph_alarm *a = &sim->alarm;
    a->raised = true;
    a->step = sim->step;
    a->pass = pass;
    a->particle = i;
    a->field = field;
    a->comp = comp;
    a->value = value;
    snprintf(a->what, sizeof a->what, "%s", what);
}

/* Index of the first particle whose field is bad, or n. */
static uint32_t first_bad(const sph_sim *sim, const sph_field *f, int kind)
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
        if (kind == SPH_FIELD_VEL) bad |= s2 > vb2;
        if (kind == SPH_FIELD_RHO) bad |= !(f->c[0][i] > 0.0f) || f->c[0][i] > rb;
        if (bad && i < first) first = i;
    }
    return (uint32_t)first;
}

void sph_watchdog_check(sph_sim *sim, int pass)
{
    unsigned bits = sim->pass_writes[pass];
    for (int f = 0; f < SPH_FIELD_COUNT && !sim->alarm.raised; f++) {
        sph_field fd;
        if (!(bits & (1u << f)) || !sph_sim_field(sim, (sph_field_id)f, &fd)) continue;
        uint32_t i = first_bad(sim, &fd, f);
        if (i >= sim->n) continue;
        char what[200];
        int comp = 0;
        for (int c = 0; c < fd.ncomp; c++)
            if (!isfinite(fd.c[c][i])) comp = c;
        float value = fd.c[comp][i];
        if (!isfinite(value)) {
            snprintf(what, sizeof what, "%s is not finite", fd.name);
        } else if (f == SPH_FIELD_VEL) {
            float s2 = 0;
            for (int c = 0; c < fd.ncomp; c++) s2 += fd.c[c][i] * fd.c[c][i];
            value = sqrtf(s2);
            snprintf(what, sizeof what, "speed %.4g m/s is above the bound %.4g m/s the scene implies", value,
                     sim->speed_bound);
        } else {
            snprintf(what, sizeof what, "density %.4g is outside (0, %.4g], the bound the scene implies", value,
                     sim->density_bound);
        }
        raise_alarm(sim, pass, i, f, comp, value, what);
    }
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
    append(out, n, &used, "watchdog: step %llu (t = %.6g s, dt = %.3g s), after pass '%s': particle %u (id %u): %s\n",
           (unsigned long long)a->step, sim->t, sim->dt, sph_passes[a->pass]->name, i, sim->P.id[i], a->what);
    append(out, n, &used, "  values:");
    particle_values(sim, i, out, n, &used);
    append(out, n, &used, "\n");
    const sph_search_data *S = &sim->S;
    if (S->nbr_start) {
        uint32_t b = S->nbr_start[i], e = S->nbr_start[i + 1];
        append(out, n, &used, "  %u neighbours%s\n", e - b, e - b > 8 ? " (first 8)" : "");
        for (uint32_t k = b; k < e && k < b + 8; k++) {
            uint32_t j = S->nbr[k];
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
    append(out, n, &used,
           "  the state is kept as it was when this was found (--dump writes it). Usual causes: a time step "
           "above the CFL limit (try [time] cfl = 0.4), a stiffness too high for dt, or particles forced together.\n");
}
