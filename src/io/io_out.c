/* The atomic writer (io.h): one implementation of "write to a temporary, then
 * rename" for every output of sphlab, the refusals, and the signal handler
 * that removes the temporaries of an interrupted run. */
#define _DEFAULT_SOURCE /* mkstemps, fchmod */
#include "io.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void say(char *err, size_t n, const char *fmt, const char *path, const char *why)
{
    if (err && n) snprintf(err, n, fmt, path, why);
}

/* ---- the registry of open temporaries ------------------------------------------ */

enum { MAX_OPEN = 128, MAX_INPUTS = 16 };

/* The handler reads `used` and `tmp` only; a slot is filled before it is
 * marked used and unmarked only after its temporary is renamed or removed. */
static struct {
    volatile sig_atomic_t used;
    char tmp[SPH_IO_PATH + 32];
    sph_out *owned; /* the writer behind sph_out_fopen's stream, heap-allocated */
} g_open[MAX_OPEN];

static struct {
    dev_t dev;
    ino_t ino;
    char path[256];
} g_inputs[MAX_INPUTS];
static int g_n_inputs;
static bool g_fsync;
static bool g_caught;

static void on_signal(int sig)
{
    int saved = errno;
    for (int i = 0; i < MAX_OPEN; i++)
        if (g_open[i].used) unlink(g_open[i].tmp);
    sph_dirs_made_remove_empty(); /* rmdir only: safe in a handler */
    static const char msg[] = "\nsphlab: interrupted; partial outputs removed\n";
    ssize_t w = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)w;
    errno = saved;
    signal(sig, SIG_DFL);
    raise(sig); /* delivered as the handler returns: the run dies by its signal */
}

void sph_io_catch_signals(void)
{
    if (g_caught) return;
    g_caught = true;
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction old, sa;
        /* a signal ignored (nohup, a background job) or already handled
         * (SDL's quit event in the window) is left as it is */
        if (sigaction(sigs[i], NULL, &old) != 0 || old.sa_handler != SIG_DFL) continue;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

void sph_io_set_fsync(bool on)
{
    g_fsync = on;
}

bool sph_io_add_input(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return false;
    for (int i = 0; i < g_n_inputs; i++)
        if (g_inputs[i].dev == st.st_dev && g_inputs[i].ino == st.st_ino) return true; /* loaded again */
    if (g_n_inputs == MAX_INPUTS) return false;
    g_inputs[g_n_inputs].dev = st.st_dev;
    g_inputs[g_n_inputs].ino = st.st_ino;
    snprintf(g_inputs[g_n_inputs].path, sizeof g_inputs[0].path, "%s", path);
    g_n_inputs++;
    return true;
}

/* Whether PATH may be replaced: it does not exist, or it is a regular file
 * that is none of the inputs. */
static bool target_ok(const char *path, char *err, size_t n)
{
    struct stat st;
    if (stat(path, &st) != 0) return true; /* missing (or unreachable: mkstemp says why) */
    if (S_ISDIR(st.st_mode)) {
        say(err, n, "%s: is a directory, not a file to write%s", path, "");
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        const char *kind = S_ISCHR(st.st_mode)    ? "a character device"
                           : S_ISBLK(st.st_mode)  ? "a block device"
                           : S_ISFIFO(st.st_mode) ? "a FIFO"
                           : S_ISSOCK(st.st_mode) ? "a socket"
                                                  : "something else";
        say(err, n, "%s: exists and is not a regular file (%s): refusing to replace it", path, kind);
        return false;
    }
    for (int i = 0; i < g_n_inputs; i++)
        if (g_inputs[i].dev == st.st_dev && g_inputs[i].ino == st.st_ino) {
            if (err && n) snprintf(err, n, "%s: is an input of this command (%s): refusing to overwrite it", path, g_inputs[i].path);
            return false;
        }
    return true;
}

/* ---- the writer ---------------------------------------------------------------- */

static void slot_free(sph_out *o)
{
    if (!o->live) return;
    g_open[o->slot].owned = NULL;
    g_open[o->slot].used = 0;
    o->live = false;
}

bool sph_out_open(sph_out *o, const char *path, char *err, size_t n)
{
    memset(o, 0, sizeof *o);
    if (!*path) {
        say(err, n, "'%s': an empty file name%s", path, "");
        return false;
    }
    if (strlen(path) >= sizeof o->path) {
        say(err, n, "%s: path too long%s", path, "");
        return false;
    }
    if (!target_ok(path, err, n)) return false;
    snprintf(o->path, sizeof o->path, "%s", path);
    /* the temporary goes in the target's folder, so the rename stays on one file system */
    const char *slash = strrchr(path, '/');
    int dir_len = slash ? (int)(slash - path) + 1 : 0;
    snprintf(o->tmp, sizeof o->tmp, "%.*s.%s.XXXXXX.tmp", dir_len, path, slash ? slash + 1 : path);
    int slot = 0;
    while (slot < MAX_OPEN && (g_open[slot].used || g_open[slot].owned)) slot++;
    if (slot == MAX_OPEN) {
        say(err, n, "%s: more than %s outputs open at once", path, "128");
        return false;
    }
    sph_io_catch_signals();
    /* the name mkstemps makes is known only once the file exists: block the
     * signals over the creation, so no temporary exists that the handler
     * could not see */
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    sigprocmask(SIG_BLOCK, &block, &old);
    int fd = mkstemps(o->tmp, 4);
    if (fd >= 0) {
        memcpy(g_open[slot].tmp, o->tmp, sizeof o->tmp);
        g_open[slot].used = 1;
        o->slot = slot;
        o->live = true;
    }
    int e = errno;
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (fd < 0) {
        say(err, n, "%s: cannot write: %s", path, strerror(e));
        return false;
    }
    /* mkstemp makes the file 0600; an output gets what fopen would give it */
    mode_t mask = umask(0);
    umask(mask);
    if (fchmod(fd, 0666 & ~mask) != 0 || !(o->f = fdopen(fd, "wb"))) {
        e = errno;
        close(fd);
        unlink(o->tmp);
        slot_free(o);
        say(err, n, "%s: cannot write: %s", path, strerror(e));
        return false;
    }
    return true;
}

/* Flushes, syncs if asked, closes: false with the reason on the first failure. */
static bool close_checked(sph_out *o, char *err, size_t n)
{
    if (!o->f) return true;
    bool ok = fflush(o->f) == 0 && !ferror(o->f);
    int e = errno;
    if (ok && g_fsync && fsync(fileno(o->f)) != 0) {
        ok = false;
        e = errno;
    }
    if (fclose(o->f) != 0 && ok) {
        ok = false;
        e = errno;
    }
    o->f = NULL;
    if (!ok) say(err, n, "%s: write failed: %s", o->path, e ? strerror(e) : "stream error");
    return ok;
}

bool sph_out_release(sph_out *o, char *err, size_t n)
{
    if (close_checked(o, err, n)) return true;
    sph_out_abort(o);
    return false;
}

bool sph_out_commit(sph_out *o, char *err, size_t n)
{
    if (!o->live) return true; /* never opened: nothing to do */
    /* the target is checked again: something may have appeared there meanwhile */
    if (!close_checked(o, err, n) || !target_ok(o->path, err, n)) {
        sph_out_abort(o);
        return false;
    }
    if (rename(o->tmp, o->path) != 0) {
        say(err, n, "%s: cannot rename the temporary into place: %s", o->path, strerror(errno));
        sph_out_abort(o);
        return false;
    }
    slot_free(o);
    return true;
}

void sph_out_abort(sph_out *o)
{
    if (o->f) fclose(o->f);
    o->f = NULL;
    if (!o->live) return;
    unlink(o->tmp);
    slot_free(o);
}

/* ---- the same, keyed by the stream ----------------------------------------------- */

FILE *sph_out_fopen(const char *path, char *err, size_t n)
{
    sph_out *o = malloc(sizeof *o);
    if (!o) {
        say(err, n, "%s: out of memory%s", path, "");
        return NULL;
    }
    if (!sph_out_open(o, path, err, n)) {
        free(o);
        return NULL;
    }
    g_open[o->slot].owned = o;
    return o->f;
}

bool sph_out_fclose(FILE *f, bool keep, char *err, size_t n)
{
    for (int i = 0; i < MAX_OPEN; i++) {
        sph_out *o = g_open[i].owned;
        if (!o || o->f != f) continue;
        bool ok = true;
        if (keep)
            ok = sph_out_commit(o, err, n);
        else
            sph_out_abort(o);
        free(o);
        return ok;
    }
    say(err, n, "%s%s: not a stream of the atomic writer", "", "");
    return false;
}
