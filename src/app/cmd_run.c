/* sphlab run SCENE.ini: simulate, then print per-pass timings and a summary. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "../io/vtk.h"
#include "sph_obstacles.h"
#include "sph_hash_health.h"
#include "sph_walls.h"

static const app_cmd_spec spec = {
    .name = "run",
    .cmd = APP_CMD(run),
    .synopsis = "usage: sphlab run SCENE.ini [options]\n",
    .footer = "exit status: 0 done; 1 bad scene or output; 2 bad command line (a bad --set too); 4 the watchdog stopped the run\n"
              "(a non-finite or runaway value: the report names the step, pass and particle; --dump keeps that state);\n"
              "5 the scene does not fit in memory\n",
    .max_pos = 1,
    .extra_pos = "more than one scene file",
};

void app_stats_header(FILE *f, const sph_sim *sim)
{
    fprintf(f, "step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed");
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p]) fprintf(f, ",%s_ms", sph_passes[p]->name);
    for (int k = 0; k < sim->def.n_obstacles; k++) /* the fluid's force on each obstacle [N or N/m] */
        for (int d = 0; d < sim->dim; d++) fprintf(f, ",obstacle_%s_f%c", sim->def.obstacles[k].name, "xyz"[d]);
    if (sph_scene_pressure_solver(&sim->def)) /* the pressure solver's step: iterations, error reached */
        fprintf(f, ",iterations,density_error,div_iterations,divergence_error,capped,stopped");
    if (sim->def.skin > 0) /* Verlet lists: how often they were built, and what kept them (sph_skin.c) */
        fprintf(f, ",list_builds,skin_moved");
    sph_hash_health hh;
    sph_sim_hash_health(sim, false, &hh);
    if (hh.has_table) /* the figures of docs/performance.md's "Hash health" */
        fprintf(f, ",hash_keys,hash_load,hash_occupied,hash_colliding,hash_longest_run,hash_candidates,hash_share");
    fprintf(f, "\n");
}

void app_stats_row(FILE *f, const sph_sim *sim, double dt)
{
    sph_stats s;
    sph_sim_stats(sim, &s);
    fprintf(f, "%llu,%.9g,%.9g,%u,%.9g", (unsigned long long)sim->step, sim->t, dt, s.n, s.ekin);
    if (sim->P.rho) /* no density computed (no effect needs it): empty cells, not a density of 0 */
        fprintf(f, ",%.9g,%.9g,%.9g", s.rho_min, s.rho_mean, s.rho_max);
    else
        fprintf(f, ",,,");
    fprintf(f, ",%.9g", s.max_speed);
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p]) fprintf(f, ",%.6f", sim->timing[p].last_ms);
    if (sim->def.n_obstacles) {
        double force[SPH_MAX_OBSTACLES][3];
        sph_obstacle_forces(sim, force);
        for (int k = 0; k < sim->def.n_obstacles; k++)
            for (int d = 0; d < sim->dim; d++) fprintf(f, ",%.9g", force[k][d]);
    }
    if (sph_scene_pressure_solver(&sim->def))
        fprintf(f, ",%d,%.6g,%d,%.6g,%llu,%llu", sim->solver.iterations, sim->solver.density_error,
                sim->solver.div_iterations, sim->solver.divergence_error, (unsigned long long)sim->solver.capped,
                (unsigned long long)sim->solver.stopped);
    if (sim->def.skin > 0)
        fprintf(f, ",%llu,%.6g", (unsigned long long)sim->S.builds, (double)sim->S.skin_moved);
    sph_hash_health hh;
    sph_sim_hash_health(sim, false, &hh);
    if (hh.has_table) {
        fprintf(f, ",%u,%.6g,%u,%u,%u,%.6g,", hh.table_size, hh.load_factor, hh.occupied, hh.colliding,
                hh.longest_run, hh.candidates);
        /* the share needs the true neighbours, which the GL backend does not count (it builds no lists):
         * an empty cell, not "nan", which CSV readers take for a number */
        if (!isnan(hh.share)) fprintf(f, "%.6g", hh.share);
    }
    fprintf(f, "\n");
}


void app_dump_write(FILE *f, const sph_sim *sim)
{
    const sph_particles *P = &sim->P;
    sph_sim_sync(sim, SPH_SYNC_ALL);
    /* rows in id order, whatever order the data are stored in */
    uint32_t *order = malloc((size_t)(sim->n ? sim->n : 1) * sizeof *order);
    if (!order) {
        fprintf(stderr, "sphlab: out of memory for the dump\n");
        return;
    }
    for (uint32_t i = 0; i < sim->n; i++) order[P->id[i]] = i;
    /* the first columns are fixed (id, position, velocity, density, pressure:
     * the one the step applied, whichever pass made it, sph_sim_pressure; 0
     * where none did); then every other field the scene computes, in the
     * registry's order, a vector as NAME_x,NAME_y,NAME_z */
    fprintf(f, "id,x,y,z,vx,vy,vz,rho,p");
    const char axis[3] = {'x', 'y', 'z'};
    for (int fi = 0; fi < SPH_FIELD_COUNT; fi++) {
        if (fi == SPH_FIELD_POS || fi == SPH_FIELD_VEL || fi == SPH_FIELD_RHO || fi == SPH_FIELD_P ||
            !P->field[fi][0])
            continue;
        if (sph_field_infos[fi].vector)
            for (int d = 0; d < 3; d++) fprintf(f, ",%s_%c", sph_field_infos[fi].name, axis[d]);
        else
            fprintf(f, ",%s", sph_field_infos[fi].name);
    }
    fputc('\n', f);
    /* positions are absolute: the simulation frame's plus sim->origin, with the digits a far one needs */
    const bool far = sph_sim_shifted(sim);
    for (uint32_t k = 0; k < sim->n; k++) {
        uint32_t i = order[k];
        double x[3] = {0, 0, 0};
        float v[3] = {0, 0, 0};
        for (int d = 0; d < sim->dim; d++) {
            x[d] = sph_sim_abs(sim, d, P->pos[d][i]);
            v[d] = P->vel[d][i];
        }
        fprintf(f, far ? "%u,%.15g,%.15g,%.15g" : "%u,%.9g,%.9g,%.9g", P->id[i], x[0], x[1], x[2]);
        fprintf(f, ",%.9g,%.9g,%.9g", v[0], v[1], v[2]);
        if (P->rho) /* no density (no effect needs it), so no pressure: empty cells, not 0 */
            fprintf(f, ",%.9g,%.9g", P->rho[i], sph_sim_pressure(sim, i));
        else
            fprintf(f, ",,");
        for (int fi = 0; fi < SPH_FIELD_COUNT; fi++) {
            if (fi == SPH_FIELD_POS || fi == SPH_FIELD_VEL || fi == SPH_FIELD_RHO || fi == SPH_FIELD_P ||
                !P->field[fi][0])
                continue;
            int nc = sph_field_infos[fi].vector ? 3 : 1;
            if (fi == SPH_FIELD_PRED) { /* a position too */
                for (int d = 0; d < nc; d++)
                    fprintf(f, far ? ",%.15g" : ",%.9g", d < sim->dim ? sph_sim_abs(sim, d, P->field[fi][d][i]) : 0.0);
                continue;
            }
            for (int d = 0; d < nc; d++) fprintf(f, ",%.9g", d < sim->dim || nc == 1 ? P->field[fi][d][i] : 0.0f);
        }
        fputc('\n', f);
    }
    free(order);
}

void app_run_report(FILE *out, const sph_sim *sim, double wall_ms)
{
    double total = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) total += sim->timing[p].total_ms;
    double steps = sim->step ? (double)sim->step : 1;
    fprintf(out, "%-16s %8s %12s %10s %7s\n", "pass", "calls", "total ms", "ms/step", "share");
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (!sim->in_pipeline[p]) continue;
        const sph_pass_timing *t = &sim->timing[p];
        fprintf(out, "%-16s %8llu %12.2f %10.4f %6.1f%%\n", sph_passes[p]->name, (unsigned long long)t->calls, t->total_ms,
               t->total_ms / steps, total > 0 ? 100.0 * t->total_ms / total : 0.0);
    }
    fprintf(out, "%-16s %8s %12.2f %10.4f %6.1f%%\n", "all passes", "", total, total / steps, 100.0);
    sph_stats s;
    sph_sim_stats(sim, &s);
    const char *e_unit = sim->dim == 2 ? "J/m" : "J";
    const char *r_unit = sim->dim == 2 ? "kg/m^2" : "kg/m^3";
    if (sim->backend)
        fprintf(out, "\nparticles       %u (%dD), backend %s: %s\npass times      %s\n", s.n, sim->dim,
                sim->backend->name, sim->backend->device,
                sim->backend->timing ? sim->backend->timing : "the host clock around each pass");
    else
        fprintf(out, "\nparticles       %u (%dD), %d thread%s\n", s.n, sim->dim, sim->threads, sim->threads == 1 ? "" : "s");
    uint32_t walls = 0;
    for (uint32_t i = 0; sim->P.fixed && i < sim->n; i++) walls += sph_is_wall(&sim->P, i);
    if (walls) /* the lines below are the fluid's (sph_sim_stats leaves the wall particles out) */
        fprintf(out, "                %u fluid, %u wall particles; energy, density and speed below: the fluid's\n",
                sim->n - walls, walls);
    fprintf(out, "steps           %llu\n", (unsigned long long)sim->step);
    fprintf(out, "simulated time  %.6g s (last dt %.3g s)\n", sim->t, sim->dt);
    fprintf(out, "kinetic energy  %.6g %s\n", s.ekin, e_unit);
    if (sim->P.rho)
        fprintf(out, "density         min %.6g  mean %.6g  max %.6g %s\n", s.rho_min, s.rho_mean, s.rho_max, r_unit);
    else
        fprintf(out, "density         not computed (no effect needs it)\n");
    fprintf(out, "max speed       %.6g m/s\n", s.max_speed);
    if (sph_scene_pressure_solver(&sim->def)) { /* the solves that ended short, said where a reader looks */
        char restarts[96] = ""; /* solver_chebyshev: how often the guard sent a solve back to plain corrections */
        if (sim->def.solver_chebyshev > 0)
            snprintf(restarts, sizeof restarts, ", %llu went on plain after a rise under the Chebyshev blend",
                     (unsigned long long)sim->solver.restarts);
        fprintf(out,
                "pressure solves %llu capped at solver_max_iterations = %d, %llu stopped where their error rose%s; the "
                "last step's density error %.3g %% (tolerance %.3g %%); %.1f density iterations per step\n",
                (unsigned long long)sim->solver.capped, sim->def.solver_max_iterations,
                (unsigned long long)sim->solver.stopped, restarts, 100.0 * sim->solver.density_error,
                100.0 * sim->def.solver_tolerance,
                sim->step ? (double)sim->solver.iterations_run / (double)sim->step : 0.0);
    }
    fprintf(out, "wall time       %.3f s: %.1f steps/s, %.3g particle-steps/s\n", wall_ms / 1e3,
           sim->step / (wall_ms / 1e3), (double)s.n * sim->step / (wall_ms / 1e3));
}

int cmd_run(int argc, char **argv)
{
    app_opts opt;
    app_opts_init(&opt);
    opt.every = 10;
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    long steps = opt.steps, threads = opt.threads, vtk_every = opt.every;
    double until = opt.time;
    const char *stats_path = opt.stats, *dump_path = opt.dump, *vtk_dir = opt.vtk;
    bool quiet = opt.quiet;
    if (!opt.n_pos) {
        app_opts_usage_error(&spec, "no scene file");
        return 2;
    }
    if (steps >= 0 && until >= 0) {
        fprintf(stderr, "sphlab run: give --steps or --time, not both\n");
        return 2;
    }
    app_scene_opts o;
    if (!app_scene_from_opts(&o, &opt)) return 2;
    sph_scene_def def;
    int status = app_load_scene_status(&o, &def);
    if (status) return status;
    if (stats_path && dump_path && strcmp(stats_path, dump_path) == 0) {
        fprintf(stderr, "sphlab run: --stats and --dump name the same file (%s)\n", stats_path);
        return 2;
    }
    if (steps < 0 && until < 0) {
        if (def.duration > 0)
            until = def.duration;
        else
            steps = def.steps;
    }
    /* Open the outputs before simulating: an unwritable path fails now, not after the run. */
    app_out stats = {0}, dump = {0};
    char vtk_err[1200];
    if (vtk_dir && !sph_output_dir(vtk_dir, vtk_err, sizeof vtk_err)) {
        fprintf(stderr, "sphlab run: %s\n", vtk_err);
        return 1;
    }
    if (stats_path && !app_out_open(&stats, stats_path)) return 1;
    if (dump_path && !app_out_open(&dump, dump_path)) {
        app_out_abort(&stats);
        return 1;
    }
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(&def, (int)threads, &sim, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab: %s\n", err.msg);
        app_out_abort(&stats);
        app_out_abort(&dump);
        return app_error_status(err.code);
    }
    if (until >= 0) sph_sim_end_at(sim, until); /* the last step ends on it */
    if (threads > 0 && sim->backend) /* it was taken without a word */
        fprintf(stderr, "sphlab run: note: --threads %ld has no effect on the %s backend: the device runs the passes\n",
                threads, sim->backend->name);
    if (stats.f) app_stats_header(stats.f, sim);
    bool progress = !quiet && isatty(STDERR_FILENO);
    /* off a terminal (a log, a batch job) a line now and then, not a redrawn one */
    bool log_progress = !quiet && !progress;
    const char *every_ms = getenv("SPHLAB_PROGRESS_MS");
    double log_ms = every_ms && atof(every_ms) > 0 ? atof(every_ms) : 10000;
    bool warned = false;
    char warning[512];
    if (sph_sim_length_warning(sim, until, warning, sizeof warning))
        fprintf(stderr, "sphlab run: warning: %s\n", warning);
    double t0 = sph_now_ms(), last_shown = t0;
    bool vtk_ok = true;
    uint64_t vtk_last = UINT64_MAX; /* the step of the last VTK file */
    for (;;) {
        if (vtk_dir && sim->step % (uint64_t)vtk_every == 0) {
            vtk_last = sim->step;
            if (!(vtk_ok = sph_vtk_write_frame(sim, vtk_dir, (unsigned)(sim->step / (uint64_t)vtk_every), vtk_err,
                                               sizeof vtk_err))) {
                fprintf(stderr, "sphlab run: %s\n", vtk_err);
                break;
            }
        }
        if (!warned && sph_sim_dt_warning(sim, warning, sizeof warning)) {
            fprintf(stderr, "%ssphlab: warning: %s\n", progress ? "\r" : "", warning);
            warned = true; /* once: the condition names the step where it first broke */
        }
        if (until >= 0 ? sph_sim_reached(sim, until) : (long)sim->step >= steps) break;
        sph_sim_step(sim);
        if (stats.f) { /* a watchdog stop too: the state the summary and --dump show gets its row */
            sph_sim_collect_times(sim); /* this step's pass times (a GL backend's timer queries come later) */
            app_stats_row(stats.f, sim, sim->dt);
        }
        if (sim->alarm.raised) break;
        double now = sph_now_ms();
        if ((progress && now - last_shown > 200) || (log_progress && now - last_shown > log_ms)) {
            last_shown = now;
            double done = until >= 0 ? sim->t / until : (double)sim->step / (double)steps;
            double eta = done > 0 ? (now - t0) / 1e3 * (1 - done) / done : 0;
            if (progress)
                fprintf(stderr, "\r  step %llu  t = %.4f s  %3.0f%%  %.0f steps/s  ETA %.0f s   ",
                        (unsigned long long)sim->step, sim->t, 100 * done, sim->step / ((now - t0) / 1e3), eta);
            else
                fprintf(stderr, "sphlab run: step %llu, t = %.6g s, %.1f%%, %.0f steps/s, ETA %.0f s\n",
                        (unsigned long long)sim->step, sim->t, 100 * done, sim->step / ((now - t0) / 1e3), eta);
        }
    }
    double wall = sph_now_ms() - t0;
    /* the state the run ended on, when no file holds it (it fell between two, or the watchdog stopped the run
     * after the step of one): the last state is what a reader wants */
    if (vtk_dir && vtk_ok && vtk_last != sim->step &&
        !(vtk_ok = sph_vtk_write_frame(sim, vtk_dir,
                                       (unsigned)(sim->step / (uint64_t)vtk_every +
                                                  (sim->step % (uint64_t)vtk_every ? 1 : 0)),
                                       vtk_err, sizeof vtk_err)))
        fprintf(stderr, "sphlab run: %s\n", vtk_err);
    sph_sim_collect_times(sim); /* the table counts every step */
    if (progress) fprintf(stderr, "\r%78s\r", "");
    if (sim->alarm.raised) {
        char report[4096];
        sph_sim_alarm_report(sim, report, sizeof report);
        fprintf(stderr, "sphlab: %s", report);
    }
    if (sph_scene_pressure_solver(&sim->def) && !sim->alarm.raised && sim->solver.capped + sim->solver.stopped > 0)
        /* on stderr, -q too: only --stats said it (capped, stopped), and a student took the run for converged */
        fprintf(stderr,
                "sphlab run: warning: %llu pressure solve%s ended short of the tolerance (%llu capped at "
                "solver_max_iterations = %d, %llu stopped where their error rose): those solves end above their "
                "tolerance (solver_tolerance = %g%s); --stats gives each step's errors\n",
                (unsigned long long)(sim->solver.capped + sim->solver.stopped),
                sim->solver.capped + sim->solver.stopped == 1 ? "" : "s", (unsigned long long)sim->solver.capped,
                sim->def.solver_max_iterations, (unsigned long long)sim->solver.stopped,
                (double)sim->def.solver_tolerance,
                sim->def.pressure_solver == SPH_PSOLVER_DFSPH ? ", or divergence_tolerance for dfsph's divergence solve"
                                                              : "");
    if (dump.f) app_dump_write(dump.f, sim);
    bool stats_ok = app_out_commit(&stats), dump_ok = app_out_commit(&dump); /* both, even if one fails */
    bool ok = stats_ok && dump_ok && vtk_ok;
    if (!quiet) app_run_report(stdout, sim, wall);
    if (!quiet) { /* what was written, as the other commands list it (-q: none) */
        if (stats_path && stats_ok) printf("wrote %s\n", stats_path);
        if (dump_path && dump_ok) printf("wrote %s\n", dump_path);
        if (vtk_dir && vtk_ok) printf("wrote %s/ (VTK frames)\n", vtk_dir);
    }
    int code = !ok ? 1 : sim->alarm.raised ? 4 : 0;
    sph_sim_destroy(sim);
    return code;
}
