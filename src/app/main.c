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
#include "app_threads.h"
#include "sph_names.h"

static void usage(FILE *f)
{
    fputs("usage: sphlab COMMAND [options]\n\ncommands:\n", f);
#define SPH_COMMAND_HELP(name, args, about) fprintf(f, "  %-10s %-10s %s\n", #name, args, about);
    SPH_COMMANDS(SPH_COMMAND_HELP)
#undef SPH_COMMAND_HELP
    fputs("\n`sphlab COMMAND --help` (or `sphlab help COMMAND`) describes a command's options;\n"
          "`sphlab help --markdown` prints them all as docs/commands.md.\n",
          f);
}

/* Each section once, in the order it first appears: the table may hold a
 * section's keys in more than one run (keys added at its end). */
static bool keys_section_first(int i)
{
    for (int j = 0; j < i; j++)
        if (strcmp(sph_scene_keys[j].section, sph_scene_keys[i].section) == 0) return false;
    return true;
}

static void keys_print_section(const char *sec, bool first)
{
    bool named = strcmp(sec, "fluid") == 0 || strcmp(sec, "obstacle") == 0; /* [fluid pool], [obstacle rock] */
    printf("%s[%s%s]\n", first ? "" : "\n", sec, named ? " NAME" : "");
    for (int j = 0; j < sph_scene_key_count; j++) {
        const sph_key *k = &sph_scene_keys[j];
        if (strcmp(k->section, sec) != 0) continue;
        printf("  %-18s default %-34s %s%s%s\n", k->name, *k->def ? k->def : "(empty)",
               k->unit && *k->unit ? "[" : "", k->unit ? k->unit : "", k->unit && *k->unit ? "] " : "");
        printf("  %-18s %s\n", "", k->help);
    }
}

/* "physics", "[physics]" or "fluid NAME" -> the section's table name, or NULL */
static const char *keys_section_named(const char *arg)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%s", arg[0] == '[' ? arg + 1 : arg);
    size_t n = strcspn(buf, "] ");
    buf[n] = '\0';
    for (int i = 0; i < sph_scene_key_count; i++)
        if (strcmp(sph_scene_keys[i].section, buf) == 0) return sph_scene_keys[i].section;
    return NULL;
}

int cmd_keys(int argc, char **argv)
{
    for (int a = 1; a < argc; a++)
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            printf("usage: sphlab keys [SECTION ...]\n"
                   "  every scene key with its default, unit and meaning; with SECTIONs (physics, [physics]),\n"
                   "  only theirs\nsections:");
            for (int i = 0; i < sph_scene_key_count; i++)
                if (keys_section_first(i)) printf(" %s", sph_scene_keys[i].section);
            printf("\n");
            return 0;
        }
    const char *want[64];
    int n_want = 0;
    for (int a = 1; a < argc && n_want < 64; a++) {
        const char *sec = keys_section_named(argv[a]);
        if (!sec && argv[a][0] == '-') {
            fprintf(stderr, "sphlab keys: unknown option '%s'\nsee `sphlab keys --help`\n", argv[a]);
            return 2;
        }
        char as_key[400];
        sph_scene_key_sections(argv[a], NULL, as_key, sizeof as_key);
        if (!sec && *as_key) { /* a key's name where a section was wanted: where it is */
            const char *dot = strchr(as_key, '.');
            fprintf(stderr, "sphlab keys: no section '%s'; '%s' is a key: %s (sphlab keys %.*s lists it)\n", argv[a],
                    argv[a], as_key, (int)(dot - as_key), as_key);
            return 2;
        }
        if (!sec) {
            const char *near = NULL;
            for (int i = 0; i < sph_scene_key_count && !near; i++)
                if (keys_section_first(i) && sph_name_near(argv[a], sph_scene_keys[i].section))
                    near = sph_scene_keys[i].section;
            fprintf(stderr, "sphlab keys: no section '%s'", argv[a]);
            if (near) fprintf(stderr, " (did you mean %s?)", near);
            fprintf(stderr, "\nsee `sphlab keys --help` for the sections\n");
            return 2;
        }
        want[n_want++] = sec;
    }
    bool first = true;
    for (int i = 0; i < sph_scene_key_count; i++) {
        if (!keys_section_first(i)) continue;
        const char *sec = sph_scene_keys[i].section;
        bool shown = n_want == 0;
        for (int w = 0; w < n_want && !shown; w++) shown = want[w] == sec;
        if (!shown) continue;
        keys_print_section(sec, first);
        first = false;
    }
    return 0;
}

int app_load_scene_status(const app_scene_opts *o, sph_scene_def *def)
{
    sph_error err;
    *def = sph_default_scene_def();
    sph_io_add_input(o->path); /* no output of the command may overwrite its scene */
    if (sph_scene_load(o->path, def, &err) == SPH_ERR_OK) {
        /* the same key twice: the last is used, and said (a key given twice in a file is an error; on the command
         * line an override of an override is fair, but it ran unsaid) */
        for (int i = 1; i < o->n_sets; i++)
            for (int k = 0; k < i; k++) {
                const char *a = o->sets[k], *b = o->sets[i], *ea = strchr(a, '='), *eb = strchr(b, '=');
                if (ea && eb && ea - a == eb - b && strncmp(a, b, (size_t)(ea - a)) == 0) {
                    fprintf(stderr, "sphlab: warning: --set %.*s is given twice ('%s', then '%s'): the last is used\n",
                            (int)(ea - a), a, ea + 1, eb + 1);
                    break;
                }
            }
        for (int i = 0; i < o->n_sets; i++)
            if (sph_scene_set(def, o->sets[i], &err) != SPH_ERR_OK) {
                /* an unknown key or a bad value given with --set is a bad command line, as in `bench` */
                fprintf(stderr, "sphlab: %s\n", err.msg);
                return err.code == SPH_ERR_MEMORY ? SPH_EXIT_MEMORY : 2;
            }
        if (sph_scene_validate(def, &err) == SPH_ERR_OK) {
            sph_scene_warnings_print(def, stderr);
            return 0;
        }
    }
    fprintf(stderr, "sphlab: %s\n", err.msg);
    return app_error_status(err.code);
}

int app_error_status(sph_error_code code)
{
    if (code == SPH_ERR_USAGE) return 2; /* a malformed --set is a command-line error */
    return code == SPH_ERR_MEMORY ? SPH_EXIT_MEMORY : 1;
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

bool app_scene_add_backend(app_scene_opts *o, const char *value)
{
    return !value || app_scene_add_set(o, strcmp(value, "gl") == 0 ? "compute.backend=gl" : "compute.backend=cpu");
}

bool app_scene_from_opts(app_scene_opts *so, const app_opts *o)
{
    memset(so, 0, sizeof *so);
    so->path = o->n_pos ? o->pos[0] : NULL;
    for (int i = 0; i < o->sets.n; i++)
        if (!app_scene_add_set(so, o->sets.v[i])) return false;
    return app_scene_add_backend(so, o->backend);
}

bool app_load_scene(const app_scene_opts *o, sph_scene_def *def)
{
    return app_load_scene_status(o, def) == 0;
}

bool app_out_open(app_out *o, const char *path)
{
    char err[SPH_IO_PATH + 200];
    if (sph_parent_dir(path, err, sizeof err) && sph_out_open(o, path, err, sizeof err)) return true;
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

static int run_command(int argc, char **argv)
{
    /* Worker threads that sleep between parallel regions instead of spinning:
     * sets OMP_WAIT_POLICY=passive and runs sphlab again unless the user set a
     * policy (app_threads.h; docs/performance.md, "Threads on a busy machine"). */
    sph_threads_wait_passive(argv);
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    sph_gpu_register(); /* scenes may ask for [compute] backend = gl */
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        /* sphlab help CMD: that command's --help */
        const char *what = argc > 2 && strcmp(cmd, "help") == 0 ? argv[2] : NULL;
        char help_arg[] = "--help";
        char *help_argv[] = {what ? argv[2] : NULL, help_arg, NULL};
        if (what && strcmp(what, "--markdown") == 0) {
            app_opts_markdown(stdout);
            return 0;
        }
        if (what && strcmp(what, "--options") == 0) {
            app_opts_list(stdout);
            return 0;
        }
#define SPH_COMMAND_HELP(name, args, about) \
    if (what && strcmp(what, #name) == 0) return cmd_##name(2, help_argv);
        SPH_COMMANDS(SPH_COMMAND_HELP)
#undef SPH_COMMAND_HELP
        if (what) {
            fprintf(stderr, "sphlab help: unknown command '%s'\nsee `sphlab help` for the commands\n", what);
            return 2;
        }
        usage(stdout);
        return 0;
    }
    /* a command that fails takes back the output folders it made and left empty */
#define SPH_COMMAND_RUN(name, args, about)                      \
    if (strcmp(cmd, #name) == 0) {                              \
        int rc_ = cmd_##name(argc - 1, argv + 1);               \
        if (rc_ != 0) sph_dirs_made_remove_empty();             \
        return rc_;                                             \
    }
    SPH_COMMANDS(SPH_COMMAND_RUN)
#undef SPH_COMMAND_RUN
    /* the error first, the nearest command for a typo, and a hint, not the whole list */
    static const char *const names[] = {
#define SPH_COMMAND_NAME(name, args, about) #name,
        SPH_COMMANDS(SPH_COMMAND_NAME)
#undef SPH_COMMAND_NAME
    };
    const char *near = NULL;
    int near_d = 1 << 30;
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        int d = sph_edit_distance(cmd, names[k]);
        if (sph_name_near(cmd, names[k]) && d < near_d) {
            near = names[k];
            near_d = d;
        }
    }
    fprintf(stderr, "sphlab: unknown command '%s'", cmd);
    if (near) fprintf(stderr, " (did you mean %s?)", near);
    fprintf(stderr, "\nsee `sphlab help` for the commands\n");
    return 2;
}

/* A table or summary that could not be written (stdout on a full disk, a closed pipe's reader aside) is a
 * failure: `sphlab keys > /dev/full` exited 0 with nothing written. */
int main(int argc, char **argv)
{
    int rc = run_command(argc, argv);
    errno = 0;
    const bool flushed = fflush(stdout) == 0;
    if (!flushed || ferror(stdout)) { /* an earlier write's error is kept by the stream, not by errno */
        fprintf(stderr, "sphlab: writing to standard output: %s\n",
                !flushed && errno ? strerror(errno) : "a write failed");
        return rc ? rc : 1;
    }
    return rc;
}
