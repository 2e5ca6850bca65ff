/* The study's knobs (--vary KEY=V1,V2,...), their combinations, the Pareto
 * front of error against time, and study.csv. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"

static bool is_derived(const char *key)
{
    return strcmp(key, "h_over_spacing") == 0 || strcmp(key, "kernel") == 0;
}

/* Parts of a '+'-joined key or value: a linked knob sets several scene keys
 * together (KEY1+KEY2=A1+B1,A2+B2), so that a study can list settings that
 * are not a product (the equation of state at three stiffnesses, a solver
 * at two tolerances). */
static int count_parts(const char *s)
{
    int n = 1;
    for (; *s; s++) n += *s == '+';
    return n;
}

/* Part i of a '+'-joined text into out. */
static void part_of(const char *s, int i, char *out, size_t n)
{
    for (; i > 0 && s; i--) {
        s = strchr(s, '+');
        if (s) s++;
    }
    if (!s) s = "";
    size_t len = strcspn(s, "+");
    if (len >= n) len = n - 1;
    memcpy(out, s, len);
    out[len] = '\0';
}

bool study_plan_add(study_plan *p, const char *arg, char *why, size_t n)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg) {
        snprintf(why, n, "--vary '%.100s': expected KEY=V1,V2,... (e.g. fluid.spacing=0.04,0.02)", arg);
        return false;
    }
    if (p->n_knobs == STUDY_MAX_KNOBS) {
        snprintf(why, n, "--vary '%.100s': at most %d knobs", arg, STUDY_MAX_KNOBS);
        return false;
    }
    study_knob *k = &p->knob[p->n_knobs];
    memset(k, 0, sizeof *k);
    size_t kl = (size_t)(eq - arg);
    while (kl > 0 && isspace((unsigned char)arg[kl - 1])) kl--;
    const char *ks = arg;
    while (isspace((unsigned char)*ks)) ks++, kl--;
    if (kl == 0 || kl >= sizeof k->key) {
        snprintf(why, n, "--vary '%.100s': expected KEY=V1,V2,... with a key of 1 to %zu characters", arg,
                 sizeof k->key - 1);
        return false;
    }
    memcpy(k->key, ks, kl);
    k->key[kl] = '\0';
    const int parts = count_parts(k->key);
    for (int i = 0; i < parts && parts > 1; i++) {
        char one[96];
        part_of(k->key, i, one, sizeof one);
        if (!one[0] || is_derived(one) || !strchr(one, '.')) {
            snprintf(why, n, "--vary %s: a linked knob joins scene keys (section.key) by '+'; '%s' is not one", k->key,
                     one);
            return false;
        }
    }
    if (!is_derived(k->key) && !strchr(k->key, '.')) {
        snprintf(why, n,
                 "--vary %s: unknown knob (accepted: a scene key as section.key, e.g. kernels.h, fluid.spacing, "
                 "time.cfl; or h_over_spacing, kernel)",
                 k->key);
        return false;
    }
    for (int i = 0; i < p->n_knobs; i++)
        if (strcmp(p->knob[i].key, k->key) == 0) {
            snprintf(why, n, "--vary %s: given twice (put all its values in one list)", k->key);
            return false;
        }
    const char *v = eq + 1;
    for (;;) {
        const char *end = strchr(v, ',');
        size_t len = end ? (size_t)(end - v) : strlen(v);
        while (len > 0 && isspace((unsigned char)*v)) v++, len--;
        while (len > 0 && isspace((unsigned char)v[len - 1])) len--;
        if (len == 0) {
            snprintf(why, n, "--vary %s: %s (want a comma-separated list of values, e.g. %s=A,B)", k->key,
                     k->n == 0 && !end ? "empty list" : "empty value in the list", k->key);
            return false;
        }
        if (k->n == STUDY_MAX_VALUES) {
            snprintf(why, n, "--vary %s: more than %d values", k->key, STUDY_MAX_VALUES);
            return false;
        }
        if (len >= sizeof k->value[0]) {
            snprintf(why, n, "--vary %s: value '%.*s...' longer than %zu characters", k->key, 20, v,
                     sizeof k->value[0] - 1);
            return false;
        }
        memcpy(k->value[k->n], v, len);
        k->value[k->n][len] = '\0';
        if (parts > 1 && count_parts(k->value[k->n]) != parts) {
            snprintf(why, n, "--vary %s: value '%s' has %d part%s joined by '+', the knob %d keys", k->key,
                     k->value[k->n], count_parts(k->value[k->n]), count_parts(k->value[k->n]) == 1 ? "" : "s", parts);
            return false;
        }
        for (int i = 0; i < k->n; i++)
            if (strcmp(k->value[i], k->value[k->n]) == 0) {
                snprintf(why, n, "--vary %s: value '%s' given twice", k->key, k->value[i]);
                return false;
            }
        k->n++;
        if (!end) break;
        v = end + 1;
    }
    p->n_knobs++;
    return true;
}

long study_plan_count(const study_plan *p)
{
    long c = 1;
    for (int k = 0; k < p->n_knobs; k++) {
        c *= p->knob[k].n;
        if (c > STUDY_MAX_COMBOS) return STUDY_MAX_COMBOS + 1;
    }
    return c;
}

void study_plan_combo(const study_plan *p, long c, int idx[STUDY_MAX_KNOBS])
{
    for (int k = p->n_knobs - 1; k >= 0; k--) {
        idx[k] = (int)(c % p->knob[k].n);
        c /= p->knob[k].n;
    }
    for (int k = p->n_knobs; k < STUDY_MAX_KNOBS; k++) idx[k] = 0;
}

/* The core's message names the option --set; here the value came from --vary. */
static void core_message(char *why, size_t n, const char *key, const char *value, const sph_error *err)
{
    const char *msg = err->msg;
    if (strncmp(msg, "--set: ", 7) == 0) msg += 7;
    snprintf(why, n, "--vary %s=%s: %s", key, value, msg);
}

bool study_plan_apply_why(const study_plan *p, long c, sph_scene_def *def, char *why, size_t n, bool *usage)
{
    *usage = false;
    int idx[STUDY_MAX_KNOBS];
    study_plan_combo(p, c, idx);
    sph_error err;
    for (int k = 0; k < p->n_knobs; k++) {
        const study_knob *kn = &p->knob[k];
        if (is_derived(kn->key)) continue;
        for (int part = 0, parts = count_parts(kn->key); part < parts; part++) {
            char key[96], value[64], assign[200];
            part_of(kn->key, part, key, sizeof key);
            if (parts > 1) part_of(kn->value[idx[k]], part, value, sizeof value);
            else snprintf(value, sizeof value, "%s", kn->value[idx[k]]);
            snprintf(assign, sizeof assign, "%s=%s", key, value);
            if (sph_scene_set(def, assign, &err) != SPH_ERR_OK) {
                *usage = true;
                core_message(why, n, key, value, &err);
                return false;
            }
        }
    }
    for (int k = 0; k < p->n_knobs; k++) {
        const study_knob *kn = &p->knob[k];
        const char *v = kn->value[idx[k]];
        if (strcmp(kn->key, "kernel") == 0) {
            const char *which[3] = {"kernels.density", "kernels.pressure", "kernels.viscosity"};
            for (int w = 0; w < 3; w++) {
                char assign[200];
                snprintf(assign, sizeof assign, "%s=%s", which[w], v);
                if (sph_scene_set(def, assign, &err) != SPH_ERR_OK) {
                    *usage = true;
                    core_message(why, n, kn->key, v, &err);
                    return false;
                }
            }
        }
    }
    for (int k = 0; k < p->n_knobs; k++) {
        const study_knob *kn = &p->knob[k];
        const char *v = kn->value[idx[k]];
        if (strcmp(kn->key, "h_over_spacing") == 0) {
            char *end;
            double r = strtod(v, &end);
            if (end == v || *end || !isfinite(r) || r <= 0 || r > 100) {
                snprintf(why, n, "--vary h_over_spacing=%s: want a number above 0 and up to 100 (h = value x spacing)",
                         v);
                *usage = true;
                return false;
            }
            if (def->n_blocks == 0) {
                snprintf(why, n, "--vary h_over_spacing: the scene has no fluid block, so no spacing");
                return false;
            }
            double s = INFINITY;
            for (int b = 0; b < def->n_blocks; b++) s = fmin(s, def->blocks[b].spacing);
            char assign[200];
            snprintf(assign, sizeof assign, "kernels.h=%.9g", r * s);
            if (sph_scene_set(def, assign, &err) != SPH_ERR_OK) {
                *usage = true;
                core_message(why, n, kn->key, v, &err);
                return false;
            }
        }
    }
    if (sph_scene_validate(def, &err) != SPH_ERR_OK) {
        char combo[400] = "";
        size_t len = 0;
        for (int k = 0; k < p->n_knobs && len < sizeof combo; k++)
            len += (size_t)snprintf(combo + len, sizeof combo - len, "%s%s=%s", k ? " " : "", p->knob[k].key,
                                    p->knob[k].value[idx[k]]);
        snprintf(why, n, "combination %s: %s", combo, err.msg);
        return false;
    }
    return true;
}

bool study_plan_apply(const study_plan *p, long c, sph_scene_def *def, char *why, size_t n)
{
    bool usage;
    return study_plan_apply_why(p, c, def, why, n, &usage);
}

int study_pareto(const double *time, const double *error, int n, bool *front)
{
    int count = 0;
    for (int i = 0; i < n; i++) {
        front[i] = isfinite(time[i]) && isfinite(error[i]) && time[i] > 0 && error[i] >= 0;
        if (!front[i]) continue;
        for (int j = 0; j < n && front[i]; j++) {
            if (j == i || !(isfinite(time[j]) && isfinite(error[j]) && time[j] > 0 && error[j] >= 0)) continue;
            if (time[j] <= time[i] && error[j] <= error[i] && (time[j] < time[i] || error[j] < error[i]))
                front[i] = false;
        }
        count += front[i];
    }
    return count;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double study_median(const double *v, int n)
{
    double *s = malloc((size_t)(n > 0 ? n : 1) * sizeof *s);
    if (!s) return NAN;
    int m = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i])) s[m++] = v[i];
    double r = NAN;
    if (m) {
        qsort(s, (size_t)m, sizeof *s, cmp_double);
        r = m % 2 ? s[m / 2] : 0.5 * (s[m / 2 - 1] + s[m / 2]);
    }
    free(s);
    return r;
}

/* A value for the CSV: quoted if it holds a comma, a quote or a space. */
static void csv_text(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\" \t")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

bool study_write_csv(FILE *f, const study_plan *p, study_metric m, const study_row *rows, int n)
{
    const char *extra[STUDY_MAX_EXTRA];
    int ne = study_metric_extras(m, extra);
    fputs("combo", f);
    for (int k = 0; k < p->n_knobs; k++) {
        fputc(',', f);
        csv_text(f, p->knob[k].key);
    }
    fputs(",particles,steps,t_end,error,ms_per_step,total_s,pareto,stopped", f);
    for (int e = 0; e < ne; e++) fprintf(f, ",%s", extra[e]);
    fputc('\n', f);
    for (int i = 0; i < n; i++) {
        const study_row *r = &rows[i];
        fprintf(f, "%d", i + 1);
        for (int k = 0; k < p->n_knobs; k++) {
            fputc(',', f);
            csv_text(f, p->knob[k].value[r->idx[k]]);
        }
        fprintf(f, ",%u,%llu,%.9g,%.9g,%.9g,%.9g,%d,%d", r->r.particles, (unsigned long long)r->r.steps, r->r.t_end,
                r->r.error, r->ms_per_step, r->total_s, r->front ? 1 : 0, r->r.stopped ? 1 : 0);
        for (int e = 0; e < ne; e++) fprintf(f, ",%.9g", r->r.extra[e]);
        fputc('\n', f);
    }
    return !ferror(f);
}

bool study_knob_inert(const study_plan *p, const study_row *rows, long n, int k)
{
    if (k < 0 || k >= p->n_knobs || p->knob[k].n < 2) return false;
    long pairs = 0;
    for (long a = 0; a < n; a++) {
        const study_row *ra = &rows[a];
        if (ra->r.stopped || !isfinite(ra->r.error)) continue;
        for (long b = a + 1; b < n; b++) {
            const study_row *rb = &rows[b];
            bool others_same = ra->idx[k] != rb->idx[k];
            for (int o = 0; o < p->n_knobs && others_same; o++)
                if (o != k && ra->idx[o] != rb->idx[o]) others_same = false;
            if (!others_same || rb->r.stopped || !isfinite(rb->r.error)) continue;
            if (ra->r.particles != rb->r.particles || ra->r.steps != rb->r.steps ||
                memcmp(&ra->r.error, &rb->r.error, sizeof ra->r.error) != 0)
                return false;
            pairs++;
        }
    }
    return pairs > 0;
}
