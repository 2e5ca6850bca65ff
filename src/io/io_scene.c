/* A scene definition saved as a scene file through the atomic writer: the
 * text comes from the core's sph_scene_write, the file appears whole or not
 * at all. */
#include <stdio.h>

#include "io.h"
#include "sph_scene.h"

bool sph_io_save_scene(const char *path, const sph_scene_def *def, char *err, size_t n)
{
    FILE *f = sph_out_fopen(path, err, n);
    if (!f) return false;
    sph_error e;
    if (sph_scene_write(def, f, &e) != SPH_ERR_OK) {
        if (err) snprintf(err, n, "%s: %s", path, e.msg);
        sph_out_fclose(f, false, NULL, 0);
        return false;
    }
    return sph_out_fclose(f, true, err, n);
}
