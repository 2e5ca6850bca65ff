/* Legacy VTK writer (see vtk.h). Binary legacy VTK is big-endian by
 * definition, whatever the machine. */
#include "vtk.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void put_be32(FILE *f, uint32_t v)
{
    unsigned char b[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8), (unsigned char)v};
    fwrite(b, 1, 4, f);
}

static void put_float(FILE *f, float x)
{
    uint32_t v;
    memcpy(&v, &x, sizeof v);
    put_be32(f, v);
}

static void put_double(FILE *f, double x)
{
    uint64_t v;
    memcpy(&v, &x, sizeof v);
    put_be32(f, (uint32_t)(v >> 32));
    put_be32(f, (uint32_t)v);
}

/* A position field, absolute (sim->origin added), in double: at x = 1e5 m a
 * float would keep 8 mm. Used only when the simulation frame is shifted, so
 * a scene at the origin writes the same float file as before. */
static void put_position(FILE *f, const sph_sim *sim, const sph_field *fd)
{
    for (uint32_t i = 0; i < sim->n; i++)
        for (int c = 0; c < 3; c++) put_double(f, c < fd->ncomp && fd->c[c] ? sph_sim_abs(sim, c, fd->c[c][i]) : 0.0);
    fputc('\n', f);
}

/* Components of a field, padded to 3 for vectors (VTK vectors are 3D). */
static void put_field(FILE *f, const sph_sim *sim, const sph_field *fd, int ncomp)
{
    for (uint32_t i = 0; i < sim->n; i++)
        for (int c = 0; c < ncomp; c++) put_float(f, c < fd->ncomp && fd->c[c] ? fd->c[c][i] : 0.0f);
    fputc('\n', f);
}

bool sph_vtk_write(const sph_sim *sim, const char *path, char *err, size_t n)
{
    sph_out o;
    if (!sph_out_open(&o, path, err, n)) return false;
    FILE *f = o.f;
    const uint32_t np = sim->n;
    fprintf(f, "# vtk DataFile Version 3.0\n");
    fprintf(f, "sphlab %.60s %dD step %llu t %.9g s\n", sim->def.name[0] ? sim->def.name : "scene", sim->dim,
            (unsigned long long)sim->step, sim->t);
    const bool far = sph_sim_shifted(sim);
    fprintf(f, "BINARY\nDATASET POLYDATA\nPOINTS %u %s\n", np, far ? "double" : "float");
    sph_field pos;
    sph_sim_field(sim, SPH_FIELD_POS, &pos);
    if (far)
        put_position(f, sim, &pos);
    else
        put_field(f, sim, &pos, 3);
    fprintf(f, "VERTICES %u %llu\n", np, 2ull * np);
    for (uint32_t i = 0; i < np; i++) {
        put_be32(f, 1);
        put_be32(f, i);
    }
    fputc('\n', f);
    fprintf(f, "POINT_DATA %u\n", np);
    fprintf(f, "SCALARS id unsigned_int 1\nLOOKUP_TABLE default\n");
    for (uint32_t i = 0; i < np; i++) put_be32(f, sim->P.id[i]);
    fputc('\n', f);
    for (int id = 0; id < SPH_FIELD_COUNT; id++) {
        sph_field fd;
        if (id == SPH_FIELD_POS || !sph_sim_field(sim, (sph_field_id)id, &fd)) continue;
        bool vec = fd.ncomp > 1 || fd.c[1];
        if (vec && far && id == SPH_FIELD_PRED) { /* a position too */
            fprintf(f, "VECTORS %s double\n", fd.name);
            put_position(f, sim, &fd);
        } else if (vec) {
            fprintf(f, "VECTORS %s float\n", fd.name);
            put_field(f, sim, &fd, 3);
        } else {
            fprintf(f, "SCALARS %s float 1\nLOOKUP_TABLE default\n", fd.name);
            put_field(f, sim, &fd, 1);
        }
    }
    return sph_out_commit(&o, err, n);
}

bool sph_vtk_write_frame(const sph_sim *sim, const char *dir, unsigned frame, char *err, size_t n)
{
    char path[1024];
    if (snprintf(path, sizeof path, "%s/particles_%05u.vtk", dir, frame) >= (int)sizeof path) {
        snprintf(err, n, "%s: path too long", dir);
        return false;
    }
    return sph_vtk_write(sim, path, err, n);
}
