/* Output files of one `sphlab plot` command: every file is written to a
 * temporary beside its final name and renamed only when all are complete, so
 * a failure leaves no half-written chart or CSV behind. */
#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "plot.h"

enum { MAX_STAGED = 64 };

typedef struct staged {
    char tmp[1200], final[1100];
} staged;

static staged g_staged[MAX_STAGED];
static int g_n;

bool plot_out_dir(const char *dir)
{
    char path[1024];
    if (!*dir || strlen(dir) >= sizeof path - 1) {
        fprintf(stderr, "sphlab plot: --out '%s': not a usable directory name\n", dir);
        return false;
    }
    snprintf(path, sizeof path, "%s", dir);
    /* make each missing component, like mkdir -p */
    for (char *p = path + 1;; p++) {
        if (*p == '/' || *p == '\0') {
            char keep = *p;
            *p = '\0';
            if (mkdir(path, 0777) != 0 && errno != EEXIST) {
                fprintf(stderr, "sphlab plot: --out %s: cannot make directory %s: %s\n", dir, path, strerror(errno));
                return false;
            }
            *p = keep;
            if (!keep) break;
        }
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "sphlab plot: --out %s: not a directory\n", dir);
        return false;
    }
    return true;
}

const char *plot_out_stage(const char *dir, const char *file)
{
    if (g_n == MAX_STAGED) {
        fprintf(stderr, "sphlab plot: more than %d output files\n", MAX_STAGED);
        return NULL;
    }
    staged *s = &g_staged[g_n];
    const char *dot = strrchr(file, '.');
    int base_len = dot ? (int)(dot - file) : (int)strlen(file);
    int n1 = snprintf(s->final, sizeof s->final, "%s/%s", dir, file);
    int n2 = snprintf(s->tmp, sizeof s->tmp, "%s/.%.*s.%ld.tmp%s", dir, base_len, file, (long)getpid(),
                      dot ? dot : "");
    if (n1 < 0 || n2 < 0 || (size_t)n1 >= sizeof s->final || (size_t)n2 >= sizeof s->tmp) {
        fprintf(stderr, "sphlab plot: %s/%s: path too long\n", dir, file);
        return NULL;
    }
    for (int i = 0; i < g_n; i++)
        if (strcmp(g_staged[i].final, s->final) == 0) {
            fprintf(stderr, "sphlab plot: %s: two outputs of this command have this name (see --name)\n", s->final);
            return NULL;
        }
    FILE *f = fopen(s->tmp, "wb");
    if (!f) {
        fprintf(stderr, "sphlab plot: %s: cannot write in %s: %s\n", s->final, dir, strerror(errno));
        return NULL;
    }
    fclose(f);
    g_n++;
    return s->tmp;
}

FILE *plot_out_stage_csv(const char *dir, const char *file)
{
    const char *tmp = plot_out_stage(dir, file);
    if (!tmp) return NULL;
    FILE *f = fopen(tmp, "w");
    if (!f) fprintf(stderr, "sphlab plot: %s/%s: cannot write: %s\n", dir, file, strerror(errno));
    return f;
}

bool plot_out_close_csv(FILE *f, const char *dir, const char *file)
{
    bool bad = ferror(f) != 0;
    bad |= fclose(f) != 0;
    if (bad) fprintf(stderr, "sphlab plot: %s/%s: write failed: %s\n", dir, file, strerror(errno));
    return !bad;
}

bool plot_out_commit(bool quiet)
{
    for (int i = 0; i < g_n; i++) {
        if (rename(g_staged[i].tmp, g_staged[i].final) != 0) {
            fprintf(stderr, "sphlab plot: %s: cannot rename the temporary into place: %s\n", g_staged[i].final,
                    strerror(errno));
            for (int j = i; j < g_n; j++) remove(g_staged[j].tmp);
            g_n = 0;
            return false;
        }
        if (!quiet) printf("wrote %s\n", g_staged[i].final);
    }
    g_n = 0;
    return true;
}

void plot_out_abort(void)
{
    for (int i = 0; i < g_n; i++) remove(g_staged[i].tmp);
    g_n = 0;
}
