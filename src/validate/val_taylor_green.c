/* validate taylor-green: the periodic vortex at Re = 100
 * (scenes/validate/taylor-green.ini) against its exact decay, with PySPH's
 * definitions (pysph/examples/taylor_green.py, post_process):
 *   max-speed error  |max_i |v_i| - U e^{bt}| / (U e^{bt}),
 *   L1 error         mean_i ||v_i| - |v_exact(x_i)|| / mean_i |v_exact(x_i)|,
 *   kinetic energy   1/2 sum_i m_i |v_i|^2 against the same sum of the exact field,
 * b = -8 pi^2 nu / L^2. Each is taken about every 0.01 s; the figures are the
 * worst over the run. The observed order of the L1 error is
 * log(L1_coarse / L1_fine) / log(R_fine / R_coarse). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "validate_run.h"

#define T_END 2.0   /* [s] */
#define TARGET_RES 50

typedef struct tg_obs {
    double next, U, nu, L, x0, y0;
    val_series vmax, vmax_exact, ke, ke_exact, l1, linf;
    double worst_linf, worst_l1;
    bool oom;
} tg_obs;

static void observe(void *vctx, const sph_sim *sim)
{
    tg_obs *o = vctx;
    if (sim->t < o->next - 1e-12) return;
    o->next = sim->t + 0.01;
    const sph_particles *P = &sim->P;
    double vmax = 0, ke = 0, ke_e = 0, l1 = 0, mean_e = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        double ve[2];
        val_tg_velocity(P->pos[0][i] - o->x0, P->pos[1][i] - o->y0, sim->t, o->U, o->nu, o->L, ve);
        double vx = P->vel[0][i], vy = P->vel[1][i], m = P->mass[i];
        double sp = sqrt(vx * vx + vy * vy), sp_e = sqrt(ve[0] * ve[0] + ve[1] * ve[1]);
        vmax = fmax(vmax, sp);
        ke += 0.5 * m * sp * sp;
        ke_e += 0.5 * m * sp_e * sp_e;
        l1 += fabs(sp - sp_e);
        mean_e += sp_e;
    }
    double vmax_e = o->U * val_tg_decay(o->nu, o->L, sim->t);
    double linf = fabs(vmax - vmax_e) / vmax_e, l1r = mean_e > 0 ? l1 / mean_e : 0;
    o->worst_linf = fmax(o->worst_linf, linf);
    o->worst_l1 = fmax(o->worst_l1, l1r);
    bool ok = val_series_add(&o->vmax, sim->t, vmax) && val_series_add(&o->vmax_exact, sim->t, vmax_e) &&
              val_series_add(&o->ke, sim->t, ke) && val_series_add(&o->ke_exact, sim->t, ke_e) &&
              val_series_add(&o->l1, sim->t, l1r) && val_series_add(&o->linf, sim->t, linf);
    o->oom |= !ok;
}

static void obs_free(tg_obs *o)
{
    val_series_free(&o->vmax), val_series_free(&o->vmax_exact), val_series_free(&o->ke);
    val_series_free(&o->ke_exact), val_series_free(&o->l1), val_series_free(&o->linf);
}

int val_run_taylor_green(const val_ctx *c, const val_problem *p)
{
    tg_obs obs[VAL_MAX_RES];
    memset(obs, 0, sizeof obs);
    bool ok = true;
    int done = 0;
    const double t_end = c->quick ? 0.2 : T_END;
    for (int r = 0; r < c->nres && ok; r++) {
        sph_scene_def def;
        if (!val_scene("taylor-green.ini", 1.0 / c->res[r], &def)) {
            ok = false;
            break;
        }
        tg_obs *o = &obs[r];
        o->U = def.blocks[0].velocity[0];
        o->nu = def.viscosity;
        o->L = (double)def.domain_max[0] - def.domain_min[0];
        o->x0 = def.domain_min[0];
        o->y0 = def.domain_min[1];
        char label[64];
        snprintf(label, sizeof label, "taylor-green %d x %d", c->res[r], c->res[r]);
        ok = val_run(c, label, &def, t_end, observe, o) && !o->oom;
        done = r + 1;
    }
    FILE *f = ok ? val_csv(c, "taylor-green.csv") : NULL;
    ok = ok && f;
    if (f) {
        /* l1: PySPH's L1 of the speed over the exact field's mean speed; max_speed_error: |max_speed /
         * max_speed_exact - 1|, the verdict's "max-speed" (at t = 0 it is the lattice's sampling of the field:
         * no particle sits where the speed is U; 3.7 % at 16^2). It was named linf, which it is not. */
        fprintf(f, "resolution,t,max_speed,max_speed_exact,ekin,ekin_exact,l1,max_speed_error\n");
        for (int r = 0; r < done; r++) {
            const tg_obs *o = &obs[r];
            for (size_t i = 0; i < o->vmax.n; i++)
                fprintf(f, "%d,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", c->res[r], o->vmax.x[i], o->vmax.y[i],
                        o->vmax_exact.y[i], o->ke.y[i], o->ke_exact.y[i], o->l1.y[i], o->linf.y[i]);
        }
        ok = val_csv_close(c, f, "taylor-green.csv");
    }
    char trend[1000] = "";
    for (int r = 0; r < done; r++) val_cost_error(r, obs[r].worst_l1); /* the L1 of the speed, beside its cost */
    for (int r = 0; r < done; r++) {
        /* the part of the max-speed error there at t = 0, where the lattice misses the field's peak (16^2: 3.73
         * of 3.87 %): said, or a student reads the sampling as the scheme's error growing with resolution */
        const val_series *e0 = &obs[r].linf;
        const double at0 = e0->n > 0 && e0->x[0] == 0.0 ? e0->y[0] : 0.0;
        char start[96] = "";
        if (at0 >= 0.001)
            snprintf(start, sizeof start, " (%.2f%% of it at t = 0: no particle sits on the speed's peak)", 100 * at0);
        val_append(trend, sizeof trend, "%s%d^2: max-speed %.2f%%%s L1 %.2f%%", r ? ", " : "", c->res[r],
                   100 * obs[r].worst_linf, start, 100 * obs[r].worst_l1);
        if (r > 0)
            val_append(trend, sizeof trend, " (order %.2f)",
                       val_order(c->res[r - 1], obs[r - 1].worst_l1, c->res[r], obs[r].worst_l1));
    }
    if (ok) {
        plot_lines ch;
        memset(&ch, 0, sizeof ch);
        snprintf(ch.title, sizeof ch.title, "Taylor-Green vortex, Re = 100: decay and errors");
        for (int r = 0; r < done; r++)
            val_append(ch.subtitle, sizeof ch.subtitle, "%s%d#u2#d: max speed %.0f%%, L1 %.0f%%", r ? "; " : "worst: ",
                       c->res[r], 100 * obs[r].worst_linf, 100 * obs[r].worst_l1);
        snprintf(ch.xlabel, sizeof ch.xlabel, "t [s]");
        ch.np = 2;
        snprintf(ch.p[0].ylabel, sizeof ch.p[0].ylabel, "max speed [m/s]");
        snprintf(ch.p[1].ylabel, sizeof ch.p[1].ylabel, "L1 error of the speed [-]");
        plot_series *e = &ch.p[0].s[ch.p[0].n++];
        snprintf(e->label, sizeof e->label, "exact U exp(-8#gp#u2#d t/Re)");
        e->x = obs[done - 1].vmax_exact.x, e->y = obs[done - 1].vmax_exact.y, e->n = obs[done - 1].vmax_exact.n;
        e->style = 7;
        for (int r = 0; r < done && r < PLOT_MAX_SERIES - 1; r++) {
            const tg_obs *o = &obs[r];
            const val_series *src[2] = {&o->vmax, &o->l1};
            for (int k = 0; k < 2; k++) {
                plot_series *s = &ch.p[k].s[ch.p[k].n++];
                snprintf(s->label, sizeof s->label, "%d#u2#d particles", c->res[r] % 100000);
                s->x = src[k]->x, s->y = src[k]->y, s->n = src[k]->n, s->style = r;
            }
        }
        ok = val_chart(c, "taylor-green", &ch);
    }
    /* the verdict: the targets at 50^2 (or the run nearest it), L1 falling with R */
    int at = 0;
    for (int r = 1; r < done; r++)
        if (abs(c->res[r] - TARGET_RES) < abs(c->res[at] - TARGET_RES)) at = r;
    bool pass = done > 0 && obs[at].worst_linf <= 0.05 && obs[at].worst_l1 <= 0.10;
    bool falling = true;
    for (int r = 1; r < done; r++)
        if (c->res[r] > c->res[r - 1]) falling &= obs[r].worst_l1 < obs[r - 1].worst_l1;
    pass &= falling;
    char judged[64];
    snprintf(judged, sizeof judged, "%d^2%s", done ? c->res[at] : 0,
             done && c->res[at] != TARGET_RES ? ", the run nearest 50^2" : "");
    int rc = val_verdict(c, p, ok, pass,
                         "%s (targets at %s: max-speed <= 5 %%, L1 <= 10 %%; L1 falling with resolution: %s)", trend,
                         judged, done < 2 ? "one resolution, not checked" : falling ? "yes" : "no");
    for (int r = 0; r < done; r++) obs_free(&obs[r]);
    return rc;
}
