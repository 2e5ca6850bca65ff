/* Folders for outputs (io.h): the one mkdir -p of sphlab. */
#include "io.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The folders this process made, in order, so that a command that fails can
 * take back the ones it left empty (sph_dirs_made_remove_empty). */
enum { MAX_MADE = 64 };
static char g_made[MAX_MADE][SPH_IO_PATH];
static int g_n_made;

void sph_dirs_made_remove_empty(void)
{
    /* the deepest first: a parent is empty only once its children are gone;
     * rmdir refuses a folder that holds anything, which is the test wanted */
    while (g_n_made > 0) rmdir(g_made[--g_n_made]);
}

bool sph_mkdir_p(const char *dir, char *err, size_t n)
{
    char p[SPH_IO_PATH];
    if (!*dir || strlen(dir) >= sizeof p) {
        if (err && n) snprintf(err, n, "'%s': not a usable directory name", dir);
        return false;
    }
    snprintf(p, sizeof p, "%s", dir);
    /* each component in turn, the last one included; one that exists is fine */
    for (char *s = p + 1;; s++) {
        if (*s != '/' && *s != '\0') continue;
        char keep = *s;
        *s = '\0';
        if (mkdir(p, 0777) == 0) {
            if (g_n_made < MAX_MADE) snprintf(g_made[g_n_made++], SPH_IO_PATH, "%s", p);
        } else if (errno != EEXIST) {
            if (err && n) snprintf(err, n, "%s: cannot create the directory: %s", p, strerror(errno));
            return false;
        }
        *s = keep;
        if (!keep) break;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        if (err && n) snprintf(err, n, "%s: not a directory", dir);
        return false;
    }
    return true;
}

bool sph_output_dir(const char *dir, char *err, size_t n)
{
    if (!sph_mkdir_p(dir, err, n)) return false;
    /* a file made and removed: access(2) says yes to root on a folder where
     * nothing can be made (/proc/self) */
    char probe[SPH_IO_PATH + 32];
    snprintf(probe, sizeof probe, "%s/.sphlab-probe-XXXXXX", dir);
    int fd = mkstemp(probe);
    if (fd < 0) {
        if (err && n) snprintf(err, n, "%s: cannot write there: %s", dir, strerror(errno));
        return false;
    }
    close(fd);
    unlink(probe);
    return true;
}

bool sph_parent_dir(const char *path, char *err, size_t n)
{
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path) return true; /* the current folder, or the root */
    char dir[SPH_IO_PATH];
    if ((size_t)(slash - path) >= sizeof dir) {
        if (err && n) snprintf(err, n, "%s: path too long", path);
        return false;
    }
    memcpy(dir, path, (size_t)(slash - path));
    dir[slash - path] = '\0';
    char why[SPH_IO_PATH + 100] = "";
    if (sph_mkdir_p(dir, why, sizeof why)) return true;
    if (err && n) snprintf(err, n, "%s: its folder: %s", path, why); /* the file asked for, then what failed */
    return false;
}
