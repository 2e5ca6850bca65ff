/* sphlab: a teaching tool for SPH fluid simulation. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app.h"
#include "commands.h"
#include "../gpu/gpu.h"

static void usage(FILE *f)
{
    fputs("usage: sphlab COMMAND [options]\n\ncommands:\n", f);
#define SPH_COMMAND_HELP(name, args, about) fprintf(f, "  %-10s %-10s %s\n", #name, args, about);
    SPH_COMMANDS(SPH_COMMAND_HELP)
#undef SPH_COMMAND_HELP
    fputs("\n`sphlab COMMAND --help` describes a command's options.\n", f);
}

int cmd_keys(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    const char *last = "";
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (strcmp(k->section, last) != 0) {
            printf("%s[%s%s]\n", i ? "\n" : "", k->section, strcmp(k->section, "fluid") == 0 ? " NAME" : "");
            last = k->section;
        }
        printf("  %-18s default %-34s %s%s%s\n", k->name, *k->def ? k->def : "(empty)", k->unit && *k->unit ? "[" : "",
               k->unit ? k->unit : "", k->unit && *k->unit ? "] " : "");
        printf("  %-18s %s\n", "", k->help);
    }
    return 0;
}

int app_load_scene_status(const app_scene_opts *o, sph_scene_def *def)
{
    sph_error err;
    *def = sph_default_scene_def();
    sph_io_add_input(o->path); /* no output of the command may overwrite its scene */
    if (sph_scene_load(o->path, def, &err) == SPH_ERR_OK) {
        for (int i = 0; i < o->n_sets; i++)
            if (sph_scene_set(def, o->sets[i], &err) != SPH_ERR_OK) goto fail;
        if (sph_scene_validate(def, &err) == SPH_ERR_OK) {
            char warning[512];
            if (sph_scene_warning(def, warning, sizeof warning)) fprintf(stderr, "sphlab: warning: %s\n", warning);
            return 0;
        }
    }
fail:
    fprintf(stderr, "sphlab: %s\n", err.msg);
    return err.code == SPH_ERR_USAGE ? 2 : 1; /* a malformed --set is a command-line error */
}

bool app_opt_is(const char *a, const char *name)
{
    size_t n = strlen(name);
    return strncmp(a, name, n) == 0 && (a[n] == '\0' || a[n] == '=');
}

const char *app_opt_value(const char *cmd, int argc, char **argv, int *i, const char *name)
{
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (a[n] == '=') return a + n + 1;
    if (*i + 1 < argc) return argv[++*i];
    fprintf(stderr, "sphlab %s: %s needs a value\n", cmd, name);
    return NULL;
}

bool app_scene_add_set(app_scene_opts *o, const char *set)
{
    if (o->n_sets == APP_MAX_SETS) {
        fprintf(stderr, "sphlab: more than %d --set options\n", APP_MAX_SETS);
        return false;
    }
    o->sets[o->n_sets++] = set;
    return true;
}

bool app_backend_valid(const char *cmd, const char *value)
{
    if (strcmp(value, "cpu") == 0 || strcmp(value, "gl") == 0) return true;
    fprintf(stderr, "sphlab %s: --backend '%s': accepted: cpu, gl\n", cmd, value);
    return false;
}

bool app_scene_add_backend(app_scene_opts *o, const char *value)
{
    return !value || app_scene_add_set(o, strcmp(value, "gl") == 0 ? "compute.backend=gl" : "compute.backend=cpu");
}

bool app_load_scene(const app_scene_opts *o, sph_scene_def *def)
{
    return app_load_scene_status(o, def) == 0;
}

bool app_parse_int(const char *opt, const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = s ? strtol(s, &end, 10) : 0;
    if (!s || end == s || *end || errno) {
        fprintf(stderr, "sphlab: %s '%s': not a whole number\n", opt, s ? s : "");
        return false;
    }
    if (v < lo || v > hi) {
        fprintf(stderr, "sphlab: %s %ld: out of range (accepted: %ld to %ld)\n", opt, v, lo, hi);
        return false;
    }
    *out = v;
    return true;
}

bool app_parse_double(const char *opt, const char *s, double lo, double hi, double *out)
{
    char *end;
    double v = s ? strtod(s, &end) : 0;
    if (!s || end == s || *end) {
        fprintf(stderr, "sphlab: %s '%s': not a number\n", opt, s ? s : "");
        return false;
    }
    if (!isfinite(v) || v < lo || v > hi) {
        fprintf(stderr, "sphlab: %s %s: out of range (accepted: %g to %g)\n", opt, s, lo, hi);
        return false;
    }
    *out = v;
    return true;
}

bool app_out_open(app_out *o, const char *path)
{
    char err[SPH_IO_PATH + 200];
    if (sph_out_open(o, path, err, sizeof err)) return true;
    fprintf(stderr, "sphlab: %s\n", err);
    return false;
}

bool app_out_commit(app_out *o)
{
    char err[SPH_IO_PATH + 200];
    if (sph_out_commit(o, err, sizeof err)) return true;
    fprintf(stderr, "sphlab: %s\n", err);
    return false;
}

void app_out_abort(app_out *o)
{
    sph_out_abort(o);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    sph_gpu_register(); /* scenes may ask for [compute] backend = gl */
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return 0;
    }
#define SPH_COMMAND_RUN(name, args, about) \
    if (strcmp(cmd, #name) == 0) return cmd_##name(argc - 1, argv + 1);
    SPH_COMMANDS(SPH_COMMAND_RUN)
#undef SPH_COMMAND_RUN
    fprintf(stderr, "sphlab: unknown command '%s'\n", cmd);
    usage(stderr);
    return 2;
}
