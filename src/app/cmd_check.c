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
    fprintf(f, "ok\n");
}

static void usage(FILE *f)
{
    fputs("usage: sphlab check SCENE.ini [--set section.key=value ...]\n"
          "Validates the scene and prints the passes it runs, in order, with their variants,\n"
          "and the passes left out with the reason.\n",
          f);
}

int cmd_check(int argc, char **argv)
{
    app_scene_opts o = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--set") == 0 || strncmp(a, "--set=", 6) == 0) {
            const char *v = a[5] == '=' ? a + 6 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v) {
                fprintf(stderr, "sphlab: --set needs section.key=value\n");
                return 2;
            }
            if (!app_scene_add_set(&o, v)) return 2;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "sphlab check: unknown option '%s'\n", a);
            usage(stderr);
            return 2;
        } else if (!o.path) {
            o.path = a;
        } else {
            fprintf(stderr, "sphlab check: more than one scene file ('%s')\n", a);
            return 2;
        }
    }
    if (!o.path) {
        usage(stderr);
        return 2;
    }
    sph_scene_def def;
    int status = app_load_scene_status(&o, &def);
    if (status) return status;
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(&def, 1, &sim, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab: %s\n", err.msg);
        return 1;
    }
    app_check_report(stdout, o.path, sim);
    sph_sim_destroy(sim);
    return 0;
}
