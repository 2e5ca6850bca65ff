/* A command that fails leaves no empty output folder it made itself (a
 * user's review: `sphlab validate couette --out v1` from a folder where the
 * problem's scene cannot be found left an empty v1/ behind). */
#define _DEFAULT_SOURCE /* realpath */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "test_util.h"

static bool exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Runs the shell command CMD; its exit status. */
static int shell(const char *cmd)
{
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

Test(out_dirs, validate_without_its_scene_leaves_no_out_folder, .timeout = 60)
{
    /* the binary copied to a folder with no scenes/ beside it, run from there */
    const char *bin = getenv("SPHLAB");
    char abs[PATH_MAX];
    cr_assert(realpath(bin && *bin ? bin : "./sphlab", abs), "no sphlab binary");
    const char *dir = test_temp_dir("outdirs");
    char cmd[PATH_MAX * 2 + 256];
    snprintf(cmd, sizeof cmd,
             "cp '%s' '%s/sphlab' && cd '%s' && ./sphlab validate couette --quick --quiet --out v1/a 2>err.txt", abs,
             dir, dir);
    int rc = shell(cmd);
    cr_expect_eq(rc, 3, "exit %d, want 3 (the run failed)", rc);
    char path[256];
    snprintf(path, sizeof path, "%s/v1", dir);
    cr_expect(!exists(path), "%s: made by a command that failed before writing anything", path);
    /* the message names where it looked */
    snprintf(cmd, sizeof cmd, "grep -q 'scenes/validate/couette.ini: not found in %s nor %s ' '%s/err.txt'", dir, dir,
             dir);
    cr_expect_eq(shell(cmd), 0, "the message does not name the folders looked in (%s/err.txt)", dir);
    test_remove_dir(dir);
}

Test(out_dirs, render_refused_video_leaves_no_frames_folder, .timeout = 60)
{
    const char *dir = test_temp_dir("outdirs");
    char args[512], out[2048];
    snprintf(args, sizeof args,
             "render lessons/scenes/rest-2d.ini --steps 1 --quiet --out %s/r/frames --video /dev/null/sphlab/x.gif",
             dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_expect_eq(rc, 1, "exit %d: %s", rc, out);
    cr_expect(strstr(out, "/dev/null/sphlab/x.gif"), "the refusal names the video: %s", out);
    char path[256];
    snprintf(path, sizeof path, "%s/r", dir);
    cr_expect(!exists(path), "%s: made by a command that failed before writing anything", path);
    test_remove_dir(dir);
}

Test(out_dirs, a_folder_that_was_there_is_kept, .timeout = 60)
{
    const char *dir = test_temp_dir("outdirs");
    char args[512], out[2048];
    snprintf(args, sizeof args,
             "render lessons/scenes/rest-2d.ini --steps 1 --quiet --out %s --video /dev/null/sphlab/x.gif", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_expect_eq(rc, 1, "exit %d: %s", rc, out);
    cr_expect(exists(dir), "%s: the user's own folder was removed", dir);
    test_remove_dir(dir);
}
