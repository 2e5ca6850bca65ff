/* sphlab check SCENE.ini: validate a scene and show the pipeline it resolves to. */
#include <string.h>

#include "app.h"

void app_print_pipeline(FILE *f, const sph_sim *sim)
{
    char about[160];
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

void app_check_report(FILE *f, const char *path, const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    fprintf(f, "scene %s: %s, %dD, %u particles in %d block%s, h = %g m\n", path, *def->name ? def->name : "(unnamed)",
            def->dim, sim->n, def->n_blocks, def->n_blocks == 1 ? "" : "s", def->h);
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
    fprintf(f, "ok\n");
}

static const app_cmd_spec spec = {
    .name = "check",
    .cmd = APP_CMD(check),
    .synopsis = "usage: sphlab check SCENE.ini [--set section.key=value ...]\n"
                "Validates the scene and prints the passes it runs, in order, with their variants,\n"
                "and the passes left out with the reason.\n",
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
        app_opts_usage(&spec, stderr);
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
    app_check_report(stdout, o.path, sim);
    sph_sim_destroy(sim);
    return 0;
}
