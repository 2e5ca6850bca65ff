/* The HUD's lines and the inspector's rows, as text (see sph_overlay.h). */
#include <ctype.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "overlay_internal.h"
#include "sph_hash_health.h"
#include "sph_search.h"
#include "sph_walls.h"

/* ---- HUD ----------------------------------------------------------------- */

double sph_density_error(const sph_sim *sim)
{
    const double held = sph_density_held(sim, NULL); /* [kg/m^dim] */
    /* rho as the start measured it, or as the density pass last wrote it; not between a reorder and that pass */
    if (!sim->P.rho || !sim->n || !(held > 0) || !(sim->fields_fresh & SPH_BIT(RHO))) return NAN;
    if (sim->backend) { /* reduced on the device where the host copy is stale: no field read back */
        sph_stats s;
        sph_sim_stats(sim, &s);
        return s.rho_max > 0 ? (s.rho_max - held) / held : NAN;
    }
    /* wall particles left out: their sums near the fluid read above it (a particle wall's
     * own density says nothing of the fluid's compression) */
    float mx = -INFINITY;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i) && sim->P.rho[i] > mx) mx = sim->P.rho[i];
    return mx > -INFINITY ? ((double)mx - held) / held : NAN;
}

/* Whether a scene's name already says its dimension ("dam break 2D"), so the
 * HUD's first line does not say it twice. */
static bool names_dimension(const char *name, int dim)
{
    const char want = dim == 3 ? '3' : '2';
    for (const char *p = name; *p; p++)
        if (p[0] == want && (p[1] == 'D' || p[1] == 'd') && (p == name || !isalnum((unsigned char)p[-1])) &&
            !isalnum((unsigned char)p[2]))
            return true;
    return false;
}

int sph_hud_lines(const sph_sim *sim, const sph_hud_info *info, char lines[][128], int max_lines)
{
    int k = 0;
#define HUD_LINE(...) \
    if (k < max_lines) snprintf(lines[k++], 128, __VA_ARGS__)
    const char *name = sim->def.name[0] ? sim->def.name : "scene";
    HUD_LINE("%s%s   %u particles", name, names_dimension(name, sim->dim) ? "" : sim->dim == 3 ? "   3D" : "   2D",
             sim->n);
    HUD_LINE("step %llu   t = %.4f s   dt = %.3g ms%s", (unsigned long long)sim->step, sim->t, 1e3 * sim->dt,
             info && info->paused ? "   PAUSED" : "");
    double e = sph_density_error(sim);
    if (e == e) {
        const char *r0;
        const double held = sph_density_held(sim, &r0);
        const bool solver = strcmp(r0, "rho_rest") == 0;
        /* the density pass sums at x + dt v: under a solver that is before its pressure acts, so it reads above
         * the tolerance the solver's own row says was met (solver_reached.c, docs/accuracy.md section 8) */
        if (solver) {
            HUD_LINE("fluid's density before the pressure, at x + dt v: (rho_max - rho_rest)/rho_rest = %+.2f %%, "
                     "rho_rest = %.5g",
                     100 * e, held); /* the next row names the solver */
        } else {
            HUD_LINE("fluid's density error (rho_max - %s)/%s = %+.2f %%, %s = %.5g (%s)", r0, r0, 100 * e, r0, held,
                     sim->def.eos_rest == SPH_EOSREST_LATTICE ? "eos_rest = lattice" : "rest_density");
        }
    } else if (sim->P.rho && sim->in_pipeline[SPH_PASS_DENSITY]) {
        HUD_LINE("density error: rho is in the particles' old order since the reorder; the density pass writes it "
                 "next");
    } else if (sim->P.rho) {
        HUD_LINE("density error: not computed yet");
    } else {
        HUD_LINE("density not computed (no effect needs it)");
    }
    if (sim->def.pressure_solver != SPH_PSOLVER_EOS && sim->def.effects & SPH_EFFECT(PRESSURE)) {
        const sph_solver_state *so = &sim->solver;
        char why[160];
        HUD_LINE("dt: %s", sph_time_step_reason(sim, why, sizeof why));
        if (sim->def.pressure_solver == SPH_PSOLVER_DFSPH) {
            HUD_LINE("dfsph last step: %d divergence + %d density iterations, error %.3f %% (tol %.3g %%), %llu capped, "
                     "%llu stopped rising",
                     so->div_iterations, so->iterations, 100 * so->density_error, 100 * sim->def.solver_tolerance,
                     (unsigned long long)so->capped, (unsigned long long)so->stopped);
        } else {
            HUD_LINE("pcisph last step: %d iteration%s, density error %.3f %% (tol %.3g %%), %llu capped, %llu stopped "
                     "rising",
                     so->iterations, so->iterations == 1 ? "" : "s", 100 * so->density_error,
                     100 * sim->def.solver_tolerance,
                     (unsigned long long)so->capped, (unsigned long long)so->stopped);
        }
        if (so->iteration > 0) {
            HUD_LINE("this step: %s iteration %d, error %.3f %%",
                     sim->def.pressure_solver == SPH_PSOLVER_PCISPH ? "pcisph"
                     : so->phase == 1                                ? "density"
                                                                     : "divergence",
                     so->iteration, 100 * so->error);
        }
    }
    double drift = sph_sim_energy_drift(sim);
    const char *worker = sph_sim_work_done_by(sim); /* a force from outside: the energy is not conserved */
    if (worker) {
        if (drift == drift) HUD_LINE("energy drift: not shown while %s does work on the fluid", worker);
    } else if (sim->def.effects & SPH_EFFECT(COHESION) || sim->def.surface_tension != SPH_STENSION_NONE) {
        /* the energy summed (kinetic, gravity, compression) leaves out the
         * surface's: a drop rounding itself turns surface energy into motion,
         * which a drift would show as an error */
        if (drift == drift) HUD_LINE("energy drift: not shown (surface energy is not counted)");
    } else if (sim->def.damping_time > 0 && sim->t < sim->def.damping_time) {
        if (drift == drift) HUD_LINE("energy drift: not shown while damping (%.2f of %.2f s)", sim->t,
                                     (double)sim->def.damping_time);
    } else if (drift == drift) {
        HUD_LINE("energy drift since step 1 = %+.2f %%", 100 * drift);
    }
    char off[100] = "";
    int on = 0, total = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (!sim->in_pipeline[p]) continue;
        total++;
        if (sim->enabled[p]) {
            on++;
        } else {
            size_t len = strlen(off);
            snprintf(off + len, sizeof off - len, " %s", sph_passes[p]->name);
        }
    }
    if (on == total) {
        HUD_LINE("passes: all %d on", total);
    } else {
        HUD_LINE("passes: %d of %d on; off:%s", on, total, off);
    }
    if (info && info->steps_per_s >= 0) { /* times change from run to run: shown only when asked for */
        int window = 0;
        double ms = sph_sim_step_ms(sim, &window);
        char fps[32] = "";
        if (info->frames_per_s > 0) snprintf(fps, sizeof fps, "   %.0f frames/s", info->frames_per_s);
        if (ms == ms) {
            HUD_LINE("%.3g ms/step (median of %d)   %.0f steps/s%s", ms, window, info->steps_per_s, fps);
        } else {
            HUD_LINE("%.0f steps/s%s", info->steps_per_s, fps);
        }
        for (int x = 0; x < info->n_extra && info->extra; x++) HUD_LINE("%s", info->extra[x]);
    }
    sph_hash_health hh;
    sph_sim_hash_health(sim, false, &hh);
    if (!hh.has_table) {
        if (sim->in_pipeline[SPH_PASS_NEIGHBOURS]) HUD_LINE("%s", hh.why);
    } else {
        HUD_LINE("hash: %u keys, load %.2f, %u occupied, %u colliding (%.0f %%), longest run %u", hh.table_size,
                 hh.load_factor, hh.occupied, hh.colliding, hh.occupied ? 100.0 * hh.colliding / hh.occupied : 0.0,
                 hh.longest_run);
        if (hh.share == hh.share) {
            HUD_LINE("search: %.1f candidates per particle, %.0f %% within h", hh.candidates, 100 * hh.share);
        } else {
            HUD_LINE("search: %.1f candidates per particle", hh.candidates);
        }
    }
    if (info && info->last_pass >= 0 && info->last_pass < SPH_PASS_COUNT) {
        const sph_pass *p = sph_passes[info->last_pass];
        char wrote[256]; /* a HUD line holds about 64 characters: a longer list ends " ..." at a word */
        sph_mask_names(sph_sim_mask_present(sim, p->writes), wrote, (int)sizeof wrote);
        if (strlen(wrote) > 60) {
            wrote[57] = '\0';
            char *cut = strrchr(wrote, ' ');
            memcpy(cut ? cut : wrote + 53, " ...", 5);
        }
        HUD_LINE("ran pass %s: wrote %.60s; next: %s", p->name, wrote, /* wrote: cut at 60 above */
                 sim->next_pass == 0 ? "a new step" : sph_passes[sim->next_pass]->name);
    }
    if (info && info->message && *info->message) HUD_LINE("%s", info->message);
#undef HUD_LINE
    return k;
}

static void vec_text(char *out, size_t n, float *const v[3], int dim, uint32_t i)
{
    if (!v[0]) {
        snprintf(out, n, "-");
        return;
    }
    float a[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) a[d] = v[d][i];
    if (dim == 3)
        snprintf(out, n, "(%.4g, %.4g, %.4g), |%.4g|", a[0], a[1], a[2], sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
    else
        snprintf(out, n, "(%.4g, %.4g), |%.4g|", a[0], a[1], sqrtf(a[0] * a[0] + a[1] * a[1]));
}

int sph_inspect_lines(const sph_sim *sim, uint32_t i, char lines[][128], int max_lines)
{
    if (i >= sim->n) return 0;
    const sph_particles *P = &sim->P;
    const int dim = sim->dim;
    int k = 0;
    char buf[96];
#define INSPECT(...) \
    if (k < max_lines) snprintf(lines[k++], 128, __VA_ARGS__)
    INSPECT("particle %u (index %u)", P->id[i], i);
    if (sph_sim_shifted(sim)) { /* the absolute position, not the simulation frame's (sim->origin) */
        double x[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) x[d] = sph_sim_abs(sim, d, P->pos[d][i]);
        if (dim == 3) {
            INSPECT("x  (%.10g, %.10g, %.10g) m", x[0], x[1], x[2]);
        } else {
            INSPECT("x  (%.10g, %.10g) m", x[0], x[1]);
        }
    } else {
        vec_text(buf, sizeof buf, P->pos, dim, i);
        INSPECT("x  %s m", buf);
    }
    vec_text(buf, sizeof buf, P->vel, dim, i);
    INSPECT("v  %s m/s", buf);
    int32_t c[3];
    sph_overlay_cell_of(sim, i, c);
    if (sim->in_pipeline[SPH_PASS_HASH]) {
        uint32_t h = sph_ov_cell_hash(sim, c), T = sim->S.table_size ? sim->S.table_size : 1;
        if (dim == 3) {
            INSPECT("cell (%d, %d, %d)  hash %u  key %u", c[0], c[1], c[2], h, h % T);
        } else {
            INSPECT("cell (%d, %d)  hash %u  key %u", c[0], c[1], h, h % T);
        }
    } else if (dim == 3) {
        INSPECT("cell (%d, %d, %d)  (no hash: search = brute)", c[0], c[1], c[2]);
    } else {
        INSPECT("cell (%d, %d)  (no hash: search = brute)", c[0], c[1]);
    }
    if (sph_ov_lists_built(sim)) INSPECT("neighbours %u", sim->S.nbr_start[i + 1] - sim->S.nbr_start[i]);
    /* the registry's computed fields that have an inspector row */
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        const sph_field_info *fi = &sph_field_infos[f];
        if (fi->kind == SPH_KIND_STATE || !*fi->label || !P->field[f][0]) continue;
        if (!(sim->fields_fresh & SPH_FIELD_BIT(f))) { /* another particle's value since the reorder */
            int q = sim->next_pass;
            while (q < SPH_PASS_COUNT &&
                   !(sim->in_pipeline[q] && sim->enabled[q] && (sph_passes[q]->writes & SPH_FIELD_BIT(f))))
                q++;
            if (q < SPH_PASS_COUNT) {
                INSPECT("%-3s -  (left in the old order by the reorder; the %s pass writes it next)", fi->label,
                        sph_passes[q]->name);
            } else {
                INSPECT("%-3s -  (left in the old order by the reorder; no pass of this step writes it)", fi->label);
            }
            continue;
        }
        if (fi->vector) {
            vec_text(buf, sizeof buf, P->field[f], dim, i);
            INSPECT("%-12s %s %s", fi->label, buf, sph_field_unit(f, dim));
        } else {
            INSPECT("%-3s %.6g %s", fi->label, P->field[f][0][i], sph_field_unit(f, dim));
        }
    }
    if (sim->def.effects & SPH_EFFECT(GRAVITY)) {
        const float *g = sim->def.gravity;
        if (dim == 3) {
            INSPECT("a gravity    (%.4g, %.4g, %.4g) m/s^2", g[0], g[1], g[2]);
        } else {
            INSPECT("a gravity    (%.4g, %.4g) m/s^2", g[0], g[1]);
        }
    }
#undef INSPECT
    return k;
}
