/* PNG files (io.h): stb_image_write encodes, its callback hands the bytes to
 * the atomic writer, so a failed write (a full disk) is an error and never
 * leaves a short or empty PNG under the final name. */
#include "io.h"

#include <stb_image_write.h>

static void put_bytes(void *ctx, void *data, int size)
{
    sph_out *o = ctx;
    /* a short write sets the stream's error flag, which commit reports */
    if (o->f && size > 0) fwrite(data, 1, (size_t)size, o->f);
}

bool sph_io_write_png(const char *path, const uint8_t *rgb, int w, int h, char *err, size_t n)
{
    sph_out o;
    if (!sph_out_open(&o, path, err, n)) return false;
    if (!stbi_write_png_to_func(put_bytes, &o, w, h, 3, rgb, w * 3)) {
        sph_out_abort(&o);
        if (err && n) snprintf(err, n, "%s: the PNG encoder failed (out of memory?)", path);
        return false;
    }
    return sph_out_commit(&o, err, n);
}
