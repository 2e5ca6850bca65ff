/* The export framework of `sphlab lesson N --export DIR`: paths, the logs in
 * DIR/logs/, the few commands that run as child processes of this binary
 * (render, view, hardcases: lesson.h says why), the lesson's
 * comparison charts through the plot module, its CSV files, and the list of
 * figures. Nothing is read back from a command's printed text. */
#define _DEFAULT_SOURCE /* realpath */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lesson.h"
#include "../io/io.h"

#define LX_MAX_ARGS 96

const char *lx_fmt(const char *fmt, ...)
{
    static char buf[64][512]; /* room for a caption in both languages */
    static int slot;
    char *b = buf[slot++ % 64];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(b, sizeof buf[0], fmt, ap);
    va_end(ap);
    return b;
}

const char *lx_src(lx *x, const char *file)
{
    /* stable for the whole export: lessons keep these paths across many calls */
    char path[sizeof x->srcs[0]];
    snprintf(path, sizeof path, "%.900s/%.100s", x->folder, file);
    for (int i = 0; i < x->nsrc; i++)
        if (strcmp(x->srcs[i], path) == 0) return x->srcs[i];
    if (x->nsrc == (int)(sizeof x->srcs / sizeof x->srcs[0])) x->nsrc = 0;
    memcpy(x->srcs[x->nsrc], path, sizeof path);
    return x->srcs[x->nsrc++];
}

const char *lx_abs(const char *path)
{
    static char buf[4][4096];
    static int slot;
    char *b = buf[slot++ % 4];
    if (!realpath(path, b)) snprintf(b, sizeof buf[0], "%s", path);
    return b;
}

const char *lx_out(lx *x, const char *file)
{
    static char buf[16][1200];
    static int slot;
    char *b = buf[slot++ % 16];
    snprintf(b, sizeof buf[0], "%s/%s", x->dir, file);
    return b;
}

void lx_md(lx *x, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(x->mdf, fmt, ap);
    va_end(ap);
}

void lx_fig(lx *x, const char *file, const char *what)
{
    if (x->nfig < (int)(sizeof x->figs / sizeof x->figs[0]))
        snprintf(x->figs[x->nfig++], sizeof x->figs[0], "`%s`: %s", file, what);
}

void lx_missing(lx *x, const char *fmt, ...)
{
    if (x->nmissing >= (int)(sizeof x->missing / sizeof x->missing[0])) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(x->missing[x->nmissing++], sizeof x->missing[0], fmt, ap);
    va_end(ap);
    if (!x->quiet) fprintf(stderr, "sphlab lesson %d: missing: %s\n", x->L->num, x->missing[x->nmissing - 1]);
}

char *lx_read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n - 1, f)) > 0;) {
        n += got;
        if (cap - n < 2) {
            char *b = realloc(buf, cap * 2);
            if (!b) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = b;
            cap *= 2;
        }
    }
    fclose(f);
    if (buf) buf[n] = '\0';
    return buf;
}

void lx_md_text(lx *x, const char *text, int max_lines)
{
    lx_md(x, "```\n");
    int lines = 0;
    for (const char *line = text, *next; *line && lines < max_lines; line = next, lines++) {
        next = strchr(line, '\n');
        next = next ? next + 1 : line + strlen(line);
        if (strncmp(line, "wrote ", 6) == 0) { /* the commands' lists of files: the report has its own */
            lines--;
            continue;
        }
        lx_md(x, "%.*s", (int)(next - line), line);
        if (next[-1] != '\n') lx_md(x, "\n");
    }
    lx_md(x, "```\n\n");
}

void lx_md_file(lx *x, const char *path, int max_lines)
{
    char *text = lx_read_file(path);
    if (!text) return;
    lx_md_text(x, text, max_lines);
    free(text);
}

/* ---- subprocesses --------------------------------------------------------- */

void lx_md_args(lx *x, const char *const *argv)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m) return;
    lx_print_args(m, argv);
    fclose(m);
    lx_md(x, "%s\n```\n\n", buf);
    free(buf);
}

void lx_print_args(FILE *f, const char *const *argv)
{
    for (int i = 0; argv[i]; i++) {
        const char *a = argv[i];
        bool quote = !*a || strpbrk(a, " \t\n'\"$\\*?") != NULL;
        if (!quote) {
            fprintf(f, "%s%s", i ? " " : "", a);
            continue;
        }
        fprintf(f, "%s'", i ? " " : "");
        for (; *a; a++) {
            if (*a == '\n') fputs("\\n", f);
            else if (*a == '\'') fputs("'\\''", f);
            else fputc(*a, f);
        }
        fputc('\'', f);
    }
}

static int spawn(lx *x, const char *log, const char *cwd, const char *env, const char **argv)
{
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0) _exit(125);
        dup2(fd, 1);
        dup2(fd, 2);
        close(fd);
        int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0) {
            dup2(devnull, 0);
            close(devnull);
        }
        /* the command first, as lx_log_open's logs have it: a quiet render's log was empty. A FILE of its own,
         * since stdout's buffer may hold what the parent had not written yet */
        int cfd = dup(1);
        FILE *cmd = cfd >= 0 ? fdopen(cfd, "w") : NULL;
        if (cmd) {
            fputs("$ ", cmd);
            if (env) fprintf(cmd, "%s ", env);
            lx_print_args(cmd, argv);
            fputc('\n', cmd);
            fclose(cmd);
        }
        if (cwd && chdir(cwd) != 0) {
            fprintf(stderr, "sphlab lesson: cannot enter %s: %s\n", cwd, strerror(errno));
            _exit(125);
        }
        if (env) {
            char name[128];
            const char *eq = strchr(env, '=');
            if (eq && (size_t)(eq - env) < sizeof name) {
                memcpy(name, env, (size_t)(eq - env));
                name[eq - env] = '\0';
                setenv(name, eq + 1, 1);
            }
        }
        execv(x->exe, (char *const *)argv);
        fprintf(stderr, "sphlab lesson: cannot run %s: %s\n", x->exe, strerror(errno));
        _exit(126);
    }
    int st;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

/* DIR/logs/NN-LOG.txt (rotating static buffers); says the command on stderr. */
static const char *log_name(lx *x, const char *log, const char *env, const char *const *argv)
{
    static char path[8][1200];
    static int slot;
    char *lp = path[slot++ % 8];
    snprintf(lp, sizeof path[0], "%s/logs/%02d-%s.txt", x->dir, ++x->nlog, log);
    if (!x->quiet) {
        fprintf(stderr, "lesson %d: ", x->L->num);
        if (env) fprintf(stderr, "%s ", env);
        lx_print_args(stderr, argv);
        fputc('\n', stderr);
    }
    return lp;
}

FILE *lx_log_open(lx *x, const char *log, const char *const *argv, const char **log_path)
{
    const char *lp = log_name(x, log, NULL, argv);
    *log_path = lp;
    FILE *f = fopen(lp, "w");
    if (f) {
        fputs("$ ", f);
        lx_print_args(f, argv);
        fputs("\n", f);
    } else { /* the report promises every run's log: a log that cannot be written is a failed file */
        fprintf(stderr, "sphlab lesson %d: cannot write the log %s: %s\n", x->L->num, lp, strerror(errno));
        lx_md(x, "\n**The log `%s` could not be written.**\n\n", lp);
        x->failed++;
    }
    return f;
}

int lx_sphlab(lx *x, const char *log, const char *cwd, const char *env, const char **log_path, ...)
{
    const char *args[LX_MAX_ARGS + 1];
    int n = 0;
    va_list ap;
    va_start(ap, log_path);
    for (const char *a; (a = va_arg(ap, const char *)) && n < LX_MAX_ARGS;) args[n++] = a;
    va_end(ap);
    args[n] = NULL;
    return lx_sphlab_v(x, log, cwd, env, log_path, args);
}

int lx_sphlab_v(lx *x, const char *log, const char *cwd, const char *env, const char **log_path,
                const char *const *args)
{
    const char *argv[LX_MAX_ARGS + 2];
    int argc = 0;
    argv[argc++] = "sphlab";
    for (int i = 0; args[i] && argc < LX_MAX_ARGS + 1; i++) argv[argc++] = args[i];
    argv[argc] = NULL;

    const char *lp = log_name(x, log, env, argv);
    if (log_path) *log_path = lp;
    int rc = spawn(x, lp, cwd, env, argv);
    if (rc != 0) {
        x->failed++;
        fprintf(stderr, "sphlab lesson %d: this command failed (exit %d); its output is in %s:\n  ", x->L->num, rc,
                lp);
        lx_print_args(stderr, argv);
        fputc('\n', stderr);
        char *text = lx_read_file(lp);
        if (text) {
            size_t n = strlen(text);
            fprintf(stderr, "%s", n > 2000 ? text + n - 2000 : text);
            free(text);
        }
        lx_md(x, "\n**A command failed** (exit %d), see `logs/%s`:\n\n```\n", rc, strrchr(lp, '/') + 1);
        lx_md_args(x, argv); /* the command with paths as given */
    }
    return rc;
}

/* ---- tables --------------------------------------------------------------- */

bool lx_table(lx *x, plot_table *t, const char *path)
{
    if (plot_table_read(t, path)) return true;
    x->failed++;
    lx_md(x, "\n**Could not read `%s`.**\n\n", path);
    return false;
}

const double *lx_col(lx *x, const plot_table *t, const char *name)
{
    int c = plot_table_need(t, name, "needed by the lesson");
    if (c >= 0) return t->col[c];
    x->failed++;
    lx_md(x, "\n**`%s` has no column `%s`.**\n\n", t->path, name);
    return NULL;
}

/* ---- files ---------------------------------------------------------------- */

bool lx_take(lx *x, const char *sub, const char *frame, const char *name)
{
    char from[2400];
    snprintf(from, sizeof from, "%s/%s/%s", x->scratch, sub, frame);
    if (rename(from, lx_out(x, name)) == 0) return true;
    fprintf(stderr, "sphlab lesson %d: expected %s: %s\n", x->L->num, from, strerror(errno));
    lx_md(x, "\n**Missing frame** `%s/%s`.\n\n", sub, frame);
    x->failed++;
    return false;
}

bool lx_chart(lx *x, plot_kind kind, const void *chart, const char *base, int w, int h, const char *what)
{
    if (!plot_chart(kind, chart, x->dir, base, w, h) || !plot_out_commit(true)) {
        plot_out_abort();
        x->failed++;
        lx_md(x, "\n**Chart `%s` could not be drawn.**\n\n", base);
        return false;
    }
    lx_fig(x, lx_fmt("%s.png", base), what);
    lx_fig(x, lx_fmt("%s.pdf", base), "{{@the same chart as PDF|le même graphique en PDF}}");
    return true;
}

FILE *lx_csv_open(lx *x, const char *name)
{
    char err[SPH_IO_PATH + 200];
    FILE *f = sph_out_fopen(lx_out(x, name), err, sizeof err);
    if (!f) {
        fprintf(stderr, "sphlab lesson %d: %s\n", x->L->num, err);
        x->failed++;
    }
    return f;
}

bool lx_csv_close(lx *x, FILE *f, const char *name, const char *what)
{
    if (!f) return false;
    char err[SPH_IO_PATH + 200];
    if (!sph_out_fclose(f, true, err, sizeof err)) {
        fprintf(stderr, "sphlab lesson %d: %s\n", x->L->num, err);
        x->failed++;
        return false;
    }
    lx_fig(x, name, what);
    return true;
}
