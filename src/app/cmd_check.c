/* sphlab check SCENE.ini: validate a scene and show the pipeline it resolves to. */
#include <string.h>

#include "app.h"
#include "sph_obstacles.h"
#include "../io/io.h"
#include "sph_hash_health.h"

void app_print_pipeline(FILE *f, const sph_sim *sim)
{
    char about[512]; /* the longest description (a Laplacian with negative weights, the solvers with walls) fits */
    int k = 0;
    fprintf(f, "pipeline (in order):\n");
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (!sim->in_pipeline[p]) continue;
        sph_passes[p]->describe(&sim->def, about, sizeof about);
        fprintf(f, "  %2d. %-15s %s\n", ++k, sph_passes[p]->name, about);
    }
    int skipped = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (sim->in_pipeline[p]) continue;
        if (!skipped++) fprintf(f, "left out:\n");
        fprintf(f, "      %-15s %s\n", sph_passes[p]->name, sph_passes[p]->skip_reason(&sim->def));
    }
}

void app_print_hash_health(FILE *f, const sph_sim *sim)
{
    sph_hash_health hh;
    if (!sph_sim_hash_health(sim, true, &hh) || !hh.has_table) {
        fprintf(f, "hash health: %s\n", hh.why);
        return;
    }
    fprintf(f, "hash health (%s positions; docs/performance.md defines the figures):\n",
            sim->timing[SPH_PASS_HASH].calls ? "predicted" : "initial");
    fprintf(f, "  table size         %u keys\n", hh.table_size);
    /* no "N particles" here: the first line's particle count is what scripts read */
    fprintf(f, "  load factor        %.3f (particles / keys = %u / %u)\n", hh.load_factor, hh.particles, hh.table_size);
    fprintf(f, "  occupied keys      %u (%.1f %% of the keys)\n", hh.occupied,
            hh.table_size ? 100.0 * hh.occupied / hh.table_size : 0.0);
    fprintf(f, "  colliding keys     %u (%.1f %% of the occupied: particles of several cells)\n", hh.colliding,
            hh.occupied ? 100.0 * hh.colliding / hh.occupied : 0.0);
    fprintf(f, "  longest run        %u (the most particles on one key)\n", hh.longest_run);
    fprintf(f, "  candidates         %.2f per particle (entries read in the 3^%d cell walk)\n", hh.candidates, sim->dim);
    fprintf(f, "  true neighbours    %.2f per particle (%.1f %% of the candidates are within h)\n", hh.neighbours,
            100 * hh.share);
}

void app_check_report(FILE *f, const char *path, const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    /* the blocks' particles, and the walls' apart: "192 particles in 1 block" counted couette's 72 wall
     * particles in its block */
    const double in_blocks = sph_scene_particle_count(def);
    fprintf(f, "scene %s: %s, %dD, %.0f particles in %d block%s", path, *def->name ? def->name : "(unnamed)", def->dim,
            fmin(in_blocks, (double)sim->n), def->n_blocks, def->n_blocks == 1 ? "" : "s");
    if (sim->n > in_blocks) fprintf(f, " and %.0f wall particles", (double)sim->n - in_blocks);
    fprintf(f, ", h = %g m\n", def->h);
    if (!def->n_obstacles && sim->n > (uint32_t)sph_scene_particle_count(def)) { /* the domain's wall particles */
        double fluid = sph_scene_particle_count(def);
        fprintf(f, "particles: %.0f fluid, %.0f wall (domain box)\n", fluid, (double)sim->n - fluid);
    }
    if (def->n_obstacles) {
        double fluid = sph_scene_particle_count(def);
        fprintf(f, "particles: %.0f fluid, %.0f wall (domain box and obstacles); %.0f fluid nodes of the blocks fall "
                "inside obstacles and are not created\n", fluid, (double)sim->n - fluid, sph_obstacles_fluid_dropped(def));
        for (int k = 0; k < def->n_obstacles; k++) {
            const sph_obstacle_def *o = &def->obstacles[k];
            fprintf(f, "obstacle %s: %s, %.0f wall particles, %s-slip\n", o->name, sph_shape_names[o->shape],
                    sph_obstacle_wall_count(def, k), o->slip == SPH_SLIP_FREE ? "free" : "no");
        }
    }
    fprintf(f, "effects:");
    if (!def->effects) fprintf(f, " none");
    for (int e = 0; e < SPH_EFFECT_COUNT; e++)
        if (def->effects & (1u << e)) fprintf(f, " %s", sph_effect_names[e]);
    fprintf(f, "\n");
    app_print_pipeline(f, sim);
    sph_mem_estimate e;
    sph_mem_limit lim;
    sph_memory_estimate(def, &e); /* its frame (relative coordinates) changes no size */
    sph_memory_limit(&lim);
    char items[400], lb[32];
    fprintf(f, "memory: %s; limit %s (%s)\n", sph_memory_list(&e, items, sizeof items),
            sph_memory_text(lim.bytes, lb, sizeof lb), lim.source);
    app_print_hash_health(f, sim);
    fprintf(f, "ok\n");
}

static const app_cmd_spec spec = {
    .name = "check",
    .cmd = APP_CMD(check),
    .synopsis = "usage: sphlab check SCENE.ini [--set section.key=value ...] [--save-scene FILE.ini]\n"
                "Validates the scene and prints the passes it runs, in order, with their variants,\n"
                "and the passes left out with the reason; then the hash table's health at the initial\n"
                "positions (size, load, occupied and colliding keys, longest run, candidates per particle\n"
                "and the share within h), or why there is none.\n",
    .max_pos = 1,
    .extra_pos = "more than one scene file",
};

int cmd_check(int argc, char **argv)
{
    app_opts opt;
    app_opts_init(&opt);
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    app_scene_opts o;
    if (!app_scene_from_opts(&o, &opt)) return 2;
    if (!o.path) {
        app_opts_usage_error(&spec, "no scene file");
        return 2;
    }
    sph_scene_def def;
    int status = app_load_scene_status(&o, &def);
    if (status) return status;
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(&def, 1, &sim, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab: %s\n", err.msg);
        return app_error_status(err.code);
    }
    /* saved before the report: a scene that cannot be saved must not end
     * with the report's "ok" above the error */
    char msg[1200];
    if (opt.save_scene && !sph_io_save_scene(opt.save_scene, &def, msg, sizeof msg)) {
        fprintf(stderr, "sphlab check: --save-scene %s\n", msg);
        sph_sim_destroy(sim);
        return 1;
    }
    app_check_report(stdout, o.path, sim);
    sph_sim_destroy(sim);
    if (opt.save_scene) printf("saved %s\n", opt.save_scene);
    return 0;
}
