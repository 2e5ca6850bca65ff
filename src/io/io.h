/* The I/O layer: how every command writes a file (docs/architecture.md, "I/O layer").
 *
 *   io_out.c   the atomic writer: a unique temporary beside the target
 *              (mkstemp), every write and the close checked, renamed over
 *              the target on commit, removed on abort; the refusals (an
 *              existing non-regular file, one of the command's inputs); the
 *              registry of open temporaries that SIGINT/SIGTERM remove;
 *   io_dir.c   mkdir -p, and an output folder's checks;
 *   io_png.c   PNG through stb_image_write's callback, into the writer;
 *   io_json.c  JSON through cJSON, printed or saved through the writer;
 *   vtk.c      particles as legacy VTK (vtk.h);
 *   io_scene.c a scene definition as a scene file (the core's sph_scene_write).
 *
 * GL-free and free of the commands; only vtk.c and io_scene.c use the core (through
 * the core's public sph_sim.h and sph_scene.h). Functions that can fail return false and put
 * the reason, naming the path, in err (n bytes; err may be NULL). */
#ifndef SPH_IO_H
#define SPH_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

enum { SPH_IO_PATH = 1024 };

/* One output file being written. */
typedef struct sph_out {
    FILE *f;                     /* write here; NULL once released or closed */
    char path[SPH_IO_PATH];      /* the target */
    char tmp[SPH_IO_PATH + 32];  /* the temporary, DIR/.NAME.XXXXXX.tmp */
    bool live;                   /* a temporary exists (a zeroed sph_out is not live) */
    int slot;                    /* its entry in the registry of temporaries */
} sph_out;

/* Creates the temporary for PATH and opens it for writing. Refuses (false,
 * reason in err) a PATH that exists and is not a regular file (a directory, a
 * device, a FIFO), one that is a registered input (sph_io_add_input), and a
 * folder where no file can be made. The first call also installs the
 * SIGINT/SIGTERM handler (where those signals have their default action). */
bool sph_out_open(sph_out *o, const char *path, char *err, size_t n);
/* Closes the temporary's stream (checked) and keeps the temporary, for a
 * library that writes the file by name (o->tmp); commit renames it. */
bool sph_out_release(sph_out *o, char *err, size_t n);
/* Flushes and closes (each checked; fsync first if sph_io_set_fsync), checks
 * the target again, renames the temporary over it. On any failure the
 * temporary is removed and the target is left as it was. */
bool sph_out_commit(sph_out *o, char *err, size_t n);
/* Closes and removes the temporary. Harmless on an output never opened. */
void sph_out_abort(sph_out *o);

/* The same writer for code that holds only a FILE: open returns the stream
 * (NULL and err on failure); close commits it (keep) or removes it. */
FILE *sph_out_fopen(const char *path, char *err, size_t n);
bool sph_out_fclose(FILE *f, bool keep, char *err, size_t n);

/* fsync every output before its rename (off by default: frames are many). */
void sph_io_set_fsync(bool on);

/* Registers PATH as an input of this command: no output may be the same file
 * (same device and inode, so ./x and x match). False if PATH cannot be
 * stat'ed (then it cannot be overwritten either) or the table is full. */
bool sph_io_add_input(const char *path);

/* The signal handler: removes every open temporary, writes "interrupted;
 * partial outputs removed", then dies by the signal. Installed by the first
 * sph_out_open; installing it earlier is harmless. */
void sph_io_catch_signals(void);

/* mkdir -p: makes DIR and its missing parents; false unless DIR ends up a directory. */
bool sph_mkdir_p(const char *dir, char *err, size_t n);
/* Removes the folders sph_mkdir_p made in this process that are still empty,
 * the deepest first: called when a command fails, so that it leaves no empty
 * output folder behind. A folder that was there before is never touched. */
void sph_dirs_made_remove_empty(void);
/* mkdir -p of the folder PATH names a file in (none: nothing to make): an output file's folder is made as an
 * output folder is (`run --stats new/s.csv` failed where `render --out new` made it). */
bool sph_parent_dir(const char *path, char *err, size_t n);
/* mkdir -p DIR, then checks that a file can be made in it (one is made and removed). */
bool sph_output_dir(const char *dir, char *err, size_t n);

/* An RGB image (w x h, rows top first, 3 bytes a pixel) as a PNG through the writer. */
bool sph_io_write_png(const char *path, const uint8_t *rgb, int w, int h, char *err, size_t n);

/* A scene definition as a scene file at PATH (the keys that differ from their
 * defaults; sph_scene_write), through the writer. */
struct sph_scene_def;
bool sph_io_save_scene(const char *path, const struct sph_scene_def *def, char *err, size_t n);

#endif
