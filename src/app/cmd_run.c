/* sphlab run SCENE.ini: simulate, then print per-pass timings and a summary. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "../render/vtk.h"

static void usage(FILE *f)
{
    fputs("usage: sphlab run SCENE.ini [options]\n"
          "  --steps N           run N steps (default: the scene's duration or steps)\n"
          "  --time T            run until T simulated seconds\n"
          "  --set S.K=V         override scene key K of section S (repeatable)\n"
          "  --stats FILE.csv    one row per step: step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed,\n"
          "                      then the milliseconds of each pass in the pipeline\n"
          "  --dump FILE.csv     final particles: id,x,y,z,vx,vy,vz,rho,p\n"
          "  --vtk DIR           particles and all their fields as DIR/particles_NNNNN.vtk (ParaView)\n"
          "  --every K           with --vtk: a file every K steps, the first at step 0 (default 10)\n"
          "  --threads N         worker threads (default: one per core)\n"
          "  --backend cpu|gl    where the passes run (overrides [compute] backend): gl runs them as\n"
          "                      OpenGL 4.3 compute shaders (the GPU, or Mesa's llvmpipe without one)\n"
          "  --quiet             no progress line, no tables\n"
          "  --help              this text\n"
          "exit status: 0 done; 1 bad scene or output; 2 bad command line; 4 the watchdog stopped the run\n"
          "(a non-finite or runaway value: the report names the step, pass and particle; --dump keeps that state)\n",
          f);
}

void app_stats_header(FILE *f, const sph_sim *sim)
{
    fprintf(f, "step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed");
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p]) fprintf(f, ",%s_ms", sph_passes[p]->name);
    fprintf(f, "\n");
}

void app_stats_row(FILE *f, const sph_sim *sim, double dt)
{
    sph_stats s;
    sph_sim_stats(sim, &s);
    fprintf(f, "%llu,%.9g,%.9g,%u,%.9g,%.9g,%.9g,%.9g,%.9g", (unsigned long long)sim->step, sim->t, dt, s.n, s.ekin,
            s.rho_min, s.rho_mean, s.rho_max, s.max_speed);
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p]) fprintf(f, ",%.6f", sim->timing[p].last_ms);
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
    fprintf(f, "id,x,y,z,vx,vy,vz,rho,p\n");
    for (uint32_t k = 0; k < sim->n; k++) {
        uint32_t i = order[k];
        float x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
        for (int d = 0; d < sim->dim; d++) {
            x[d] = P->pos[d][i];
            v[d] = P->vel[d][i];
        }
        fprintf(f, "%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", P->id[i], x[0], x[1], x[2], v[0], v[1], v[2],
                P->rho ? P->rho[i] : 0.0f, P->p ? P->p[i] : 0.0f);
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
        fprintf(out, "\nparticles       %u (%dD), backend %s: %s\n", s.n, sim->dim, sim->backend->name, sim->backend->device);
    else
        fprintf(out, "\nparticles       %u (%dD), %d thread%s\n", s.n, sim->dim, sim->threads, sim->threads == 1 ? "" : "s");
    fprintf(out, "steps           %llu\n", (unsigned long long)sim->step);
    fprintf(out, "simulated time  %.6g s (last dt %.3g s)\n", sim->t, sim->dt);
    fprintf(out, "kinetic energy  %.6g %s\n", s.ekin, e_unit);
    if (sim->P.rho)
        fprintf(out, "density         min %.6g  mean %.6g  max %.6g %s\n", s.rho_min, s.rho_mean, s.rho_max, r_unit);
    else
        fprintf(out, "density         not computed (no effect needs it)\n");
    fprintf(out, "max speed       %.6g m/s\n", s.max_speed);
    fprintf(out, "wall time       %.3f s: %.1f steps/s, %.3g particle-steps/s\n", wall_ms / 1e3,
           sim->step / (wall_ms / 1e3), (double)s.n * sim->step / (wall_ms / 1e3));
}

int cmd_run(int argc, char **argv)
{
    app_scene_opts o = {0};
    long steps = -1, threads = 0;
    double until = -1;
    const char *stats_path = NULL, *dump_path = NULL, *vtk_dir = NULL;
    long vtk_every = 10;
    bool quiet = false;
    const char *backend = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            quiet = true;
        } else if (app_opt_is(a, "--steps")) {
            if (!(v = app_opt_value("run", argc, argv, &i, "--steps")) || !app_parse_int("--steps", v, 0, 2000000000L, &steps))
                return 2;
        } else if (app_opt_is(a, "--time")) {
            if (!(v = app_opt_value("run", argc, argv, &i, "--time")) || !app_parse_double("--time", v, 0, 1e6, &until))
                return 2;
        } else if (app_opt_is(a, "--threads")) {
            if (!(v = app_opt_value("run", argc, argv, &i, "--threads")) || !app_parse_int("--threads", v, 1, SPH_MAX_THREADS, &threads))
                return 2;
        } else if (app_opt_is(a, "--backend")) {
            if (!(backend = app_opt_value("run", argc, argv, &i, "--backend")) || !app_backend_valid("run", backend)) return 2;
        } else if (app_opt_is(a, "--set")) {
            if (!(v = app_opt_value("run", argc, argv, &i, "--set")) || !app_scene_add_set(&o, v)) return 2;
        } else if (app_opt_is(a, "--stats")) {
            if (!(stats_path = app_opt_value("run", argc, argv, &i, "--stats"))) return 2;
        } else if (app_opt_is(a, "--dump")) {
            if (!(dump_path = app_opt_value("run", argc, argv, &i, "--dump"))) return 2;
        } else if (app_opt_is(a, "--vtk")) {
            if (!(vtk_dir = app_opt_value("run", argc, argv, &i, "--vtk"))) return 2;
        } else if (app_opt_is(a, "--every")) {
            if (!(v = app_opt_value("run", argc, argv, &i, "--every")) || !app_parse_int("--every", v, 1, 2000000000L, &vtk_every))
                return 2;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "sphlab run: unknown option '%s'\n", a);
            usage(stderr);
            return 2;
        } else if (!o.path) {
            o.path = a;
        } else {
            fprintf(stderr, "sphlab run: more than one scene file ('%s')\n", a);
            return 2;
        }
    }
    if (!o.path) {
        usage(stderr);
        return 2;
    }
    if (steps >= 0 && until >= 0) {
        fprintf(stderr, "sphlab run: give --steps or --time, not both\n");
        return 2;
    }
    if (!app_scene_add_backend(&o, backend)) return 2; /* after the --set options, so it wins */
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
        return 1;
    }
    if (stats.f) app_stats_header(stats.f, sim);
    bool progress = !quiet && isatty(STDERR_FILENO);
    bool warned = false;
    char warning[512];
    double t0 = sph_now_ms(), last_shown = t0;
    bool vtk_ok = true;
    for (;;) {
        if (vtk_dir && sim->step % (uint64_t)vtk_every == 0 &&
            !(vtk_ok = sph_vtk_write_frame(sim, vtk_dir, (unsigned)(sim->step / (uint64_t)vtk_every), vtk_err, sizeof vtk_err))) {
            fprintf(stderr, "sphlab run: %s\n", vtk_err);
            break;
        }
        if (!warned && sph_sim_dt_warning(sim, warning, sizeof warning)) {
            fprintf(stderr, "%ssphlab: warning: %s\n", progress ? "\r" : "", warning);
            warned = true; /* once: the condition names the step where it first broke */
        }
        if (until >= 0 ? sim->t >= until - 1e-12 : (long)sim->step >= steps) break;
        sph_sim_step(sim);
        if (sim->alarm.raised) break;
        if (stats.f) app_stats_row(stats.f, sim, sim->dt);
        double now = sph_now_ms();
        if (progress && now - last_shown > 200) {
            last_shown = now;
            double done = until >= 0 ? sim->t / until : (double)sim->step / (double)steps;
            double eta = done > 0 ? (now - t0) / 1e3 * (1 - done) / done : 0;
            fprintf(stderr, "\r  step %llu  t = %.4f s  %3.0f%%  %.0f steps/s  ETA %.0f s   ",
                    (unsigned long long)sim->step, sim->t, 100 * done, sim->step / ((now - t0) / 1e3), eta);
        }
    }
    double wall = sph_now_ms() - t0;
    if (progress) fprintf(stderr, "\r%78s\r", "");
    if (sim->alarm.raised) {
        char report[4096];
        sph_sim_alarm_report(sim, report, sizeof report);
        fprintf(stderr, "sphlab: %s", report);
    }
    if (dump.f) app_dump_write(dump.f, sim);
    bool stats_ok = app_out_commit(&stats), dump_ok = app_out_commit(&dump); /* both, even if one fails */
    bool ok = stats_ok && dump_ok && vtk_ok;
    if (!quiet) app_run_report(stdout, sim, wall);
    int code = !ok ? 1 : sim->alarm.raised ? 4 : 0;
    sph_sim_destroy(sim);
    return code;
}
