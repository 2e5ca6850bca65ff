/* The start-up channel flows (validate poiseuille, couette): fluid at rest
 * between no-slip walls of wall particles at y = 0 and y = L, periodic along
 * x (12 spacings). At each sample time the fluid particles are grouped in
 * their lattice rows (R rows across), and each row's mean u is compared with
 * the exact u at the row's mean y; the error is the worst row's
 * |u - u_exact| / scale. */
#include "val_channel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sph_walls.h"

const double val_channel_times[VAL_CHANNEL_TIMES] = {0.0225, 0.045, 0.1125, 0.225, 1.0};

typedef struct chan_obs {
    const val_channel *ch;
    int rows, next;           /* rows across; the next sample */
    double s;                 /* [m] spacing */
    double times[VAL_CHANNEL_TIMES];
    double *y, *u;            /* [sample][row]: mean y [m], mean u [m/s] */
    double err[VAL_CHANNEL_TIMES]; /* [1] worst row per sample */
    int taken;
    int samples; /* how many of val_channel_times: all, or --quick's start-up ones */
} chan_obs;

static void observe(void *vctx, const sph_sim *sim)
{
    chan_obs *o = vctx;
    if (o->next >= o->samples || sim->t < o->times[o->next] - 1e-9) return;
    const sph_particles *P = &sim->P;
    const int k = o->next++;
    double *y = o->y + (size_t)k * o->rows, *u = o->u + (size_t)k * o->rows;
    int cnt[512] = {0};
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(P, i)) continue;
        double py = P->pos[1][i] - sim->def.domain_min[1];
        int row = (int)floor(py / o->s);
        if (row < 0) row = 0;
        if (row >= o->rows) row = o->rows - 1;
        y[row] += py;
        u[row] += P->vel[0][i];
        cnt[row]++;
    }
    double scale = o->ch->scale(&sim->def), worst = 0;
    for (int r = 0; r < o->rows; r++) {
        if (!cnt[r]) {
            y[r] = u[r] = NAN;
            worst = INFINITY; /* an empty row: the fluid left its lattice */
            continue;
        }
        y[r] /= cnt[r];
        u[r] /= cnt[r];
        worst = fmax(worst, fabs(u[r] - o->ch->exact(&sim->def, y[r], sim->t)) / scale);
    }
    o->err[k] = worst;
    o->taken = k + 1;
}

int val_channel_run(const val_ctx *c, const val_problem *p, const val_channel *ch)
{
    chan_obs obs[VAL_MAX_RES];
    memset(obs, 0, sizeof obs);
    sph_scene_def defs[VAL_MAX_RES];
    bool ok = true;
    int done = 0;
    for (int r = 0; r < c->nres && ok; r++) {
        sph_scene_def *def = &defs[r];
        const double L = 1.0; /* [m] the scenes' channel width */
        double s = L / c->res[r];
        /* checked once the length is set: the file's 1.2 m is shorter than 3 h below 8 rows */
        if (!val_scene_unchecked(ch->scene, s, def)) {
            ok = false;
            break;
        }
        /* 12 spacings along x, whatever the resolution */
        def->domain_max[0] = def->blocks[0].max[0] = (float)(def->domain_min[0] + 12 * s);
        sph_error err;
        if (sph_scene_validate(def, &err) != SPH_ERR_OK) {
            fprintf(stderr, "sphlab validate: %s (at spacing %g m)\n", err.msg, s);
            ok = false;
            break;
        }
        chan_obs *o = &obs[r];
        o->ch = ch;
        o->rows = c->res[r];
        o->s = s;
        for (int k = 0; k < VAL_CHANNEL_TIMES; k++) o->times[k] = val_channel_times[k];
        /* --quick: the start-up only, at the full run's own start-up times (so its figures are the ones the
         * full run prints first; earlier samples would see a wall layer sqrt(nu t) thinner than a spacing) */
        o->samples = c->quick ? VAL_CHANNEL_TIMES - 1 : VAL_CHANNEL_TIMES;
        o->y = calloc((size_t)VAL_CHANNEL_TIMES * o->rows, sizeof *o->y);
        o->u = calloc((size_t)VAL_CHANNEL_TIMES * o->rows, sizeof *o->u);
        if (!o->y || !o->u || o->rows > 512) {
            fprintf(stderr, "sphlab validate: out of memory\n");
            ok = false;
            done = r + 1;
            break;
        }
        char label[64];
        snprintf(label, sizeof label, "%s %d across", p->name, c->res[r]);
        ok = val_run(c, label, def, o->times[o->samples - 1], observe, o) && o->taken == o->samples;
        done = r + 1;
    }
    char file[96];
    snprintf(file, sizeof file, "%s.csv", ch->base);
    FILE *f = ok ? val_csv(c, file) : NULL;
    ok = ok && f;
    if (f) {
        fprintf(f, "resolution,t,y,u,u_exact\n");
        for (int r = 0; r < done; r++)
            for (int k = 0; k < obs[r].taken; k++)
                for (int w = 0; w < obs[r].rows; w++) {
                    double y = obs[r].y[(size_t)k * obs[r].rows + w], u = obs[r].u[(size_t)k * obs[r].rows + w];
                    fprintf(f, "%d,%.5f,%.6f,%.6g,%.6g\n", c->res[r], obs[r].times[k], y, u,
                            ch->exact(&defs[r], y, obs[r].times[k]));
                }
        ok = val_csv_close(c, f, file);
    }
    /* the verdict: start-up samples within startup_tol, the last within steady_tol, at every resolution */
    bool pass = done > 0;
    char trend[700] = "";
    for (int r = 0; r < done; r++) {
        double worst = 0; /* beside its cost: the run's worst sample */
        for (int k = 0; k < obs[r].taken; k++) worst = fmax(worst, obs[r].err[k]);
        val_cost_error(r, worst);
        val_append(trend, sizeof trend, "%sR=%d:", r ? "; " : "", c->res[r]);
        for (int k = 0; k < obs[r].taken; k++) {
            bool last = k == VAL_CHANNEL_TIMES - 1 && !c->quick;
            pass &= obs[r].err[k] <= (last ? ch->steady_tol : ch->startup_tol);
            val_append(trend, sizeof trend, " %.1f%%", 100 * obs[r].err[k]);
        }
    }
    /* the chart: the finest run's profiles (u against y) at every sample, with the exact ones */
    if (ok && done) {
        const chan_obs *o = &obs[done - 1];
        enum { NE = 101 };
        double ey[VAL_CHANNEL_TIMES][NE], eu[VAL_CHANNEL_TIMES][NE];
        plot_lines pl;
        memset(&pl, 0, sizeof pl);
        val_append(pl.title, sizeof pl.title, "%s (%d particles across)", ch->title, c->res[done - 1]);
        val_append(pl.subtitle, sizeof pl.subtitle, "worst row |u - u#dexact#u| / scale at each time:");
        for (int k = 0; k < o->taken; k++)
            val_append(pl.subtitle, sizeof pl.subtitle, " %.2f%%", 100 * o->err[k]);
        snprintf(pl.xlabel, sizeof pl.xlabel, "y/L [-]");
        pl.np = 1;
        pl.xlo = 0;
        pl.xhi = 1;
        snprintf(pl.p[0].ylabel, sizeof pl.p[0].ylabel, "u [m/s]");
        for (int k = 0; k < o->taken && pl.p[0].n + 2 <= PLOT_MAX_SERIES; k++) {
            for (int i = 0; i < NE; i++) {
                ey[k][i] = i / (NE - 1.0);
                eu[k][i] = ch->exact(&defs[done - 1], ey[k][i], o->times[k]);
            }
            if (k % 2 == 1 && k != o->taken - 1) continue; /* 8 series at most: three times drawn */
            plot_series *e = &pl.p[0].s[pl.p[0].n++], *s = &pl.p[0].s[pl.p[0].n++];
            snprintf(e->label, sizeof e->label, "exact t = %.3g s", o->times[k]);
            snprintf(s->label, sizeof s->label, "sphlab t = %.3g s", o->times[k]);
            e->x = ey[k], e->y = eu[k], e->n = NE, e->style = k, e->reference = true; /* its run's colour */
            s->x = o->y + (size_t)k * o->rows, s->y = o->u + (size_t)k * o->rows, s->n = (size_t)o->rows;
            s->style = k;
        }
        ok = val_chart(c, ch->base, &pl);
    }
    for (int r = 0; r < done; r++) free(obs[r].y), free(obs[r].u);
    const double scale_shown = done ? ch->scale(&defs[0]) : NAN; /* the spacing does not change it */
    /* the times the errors were sampled at (--quick: the start-up's) */
    char when[160] = "";
    for (int k = 0; k < (done ? obs[0].samples : VAL_CHANNEL_TIMES); k++)
        val_append(when, sizeof when, "%s%.4g", k ? ", " : "", done ? obs[0].times[k] : val_channel_times[k]);
    return val_verdict(c, p, ok, pass,
                       "worst row |u - u_exact| / %s (%.4g m/s) at t = %s s%s: %s (target: <= %g %% during "
                       "start-up, <= %g %% at steady state)",
                       ch->scale_name, scale_shown, when, c->quick ? " (--quick: the start-up only)" : "", trend,
                       100 * ch->startup_tol, 100 * ch->steady_tol);
}
