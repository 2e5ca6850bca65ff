/* What the lessons' exports share (lesson_util.c), and the lessons
 * themselves, one file per pair of related lessons:
 *   lesson_density.c  1 kernel estimation, 2 density summation
 *   lesson_forces.c   3 the pressure gradient, 4 the viscosity Laplacian
 *   lesson_search.c   5 the spatial hash, 6 sorting and offsets
 *   lesson_perf.c     7 the full simulation, 8 the optimisation ladder, 9 what accuracy costs
 *   lesson_walls.c    10 boundary handling, 11 how incompressible, at what cost
 * Their prose is in the lesson folders' report templates (lesson_report.c). */
#ifndef SPH_LESSON_STEPS_H
#define SPH_LESSON_STEPS_H

#include "lesson.h"
#include "sph_sim.h"

#define PI 3.14159265358979323846

/* Loads and validates a scene; false (and a failure in the report) if it cannot. */
bool lx_load_def(lx *x, const char *path, sph_scene_def *def);
/* `sphlab check` of a scene in the lesson's folder into {{pipeline}}; fills the
 * pipeline's pass names (names may be NULL) and returns their count. */
int lx_pipeline(lx *x, const char *file, char names[][24], int cap);
/* DIR/.work/SUB (rotating static buffers). */
const char *lx_work(lx *x, const char *sub);
/* Least-squares slope of y against x. */
double lx_slope(const double *xs, const double *ys, size_t n);
/* Decay rate of the velocity [1/s] (half that of the kinetic energy) from a
 * stats CSV; keep (may be NULL) receives the table. */
bool lx_decay_rate(lx *x, const char *stats, double *rate, plot_table *keep);
/* The 2D scenes' lattice: the particle of a block at (column, row). */
uint32_t lx_lattice_id(const sph_scene_def *d, int col, int row);

/* Values of a dump by particle id (the dump is in id order). */
typedef struct lx_dump {
    plot_table t;
    const double *id, *x, *y, *vx, *vy, *rho, *p;
    size_t n;
} lx_dump;

bool lx_read_dump(lx *x, const char *path, lx_dump *d);
double lx_at_id(const lx_dump *d, const double *col, uint32_t id);
/* Moves every frame of DIR/.work/SUB into DIR/SUB (made afresh); returns their count. */
int lx_take_all(lx *x, const char *sub);

int lx_lesson1(lx *x);
int lx_lesson2(lx *x);
int lx_lesson3(lx *x);
int lx_lesson4(lx *x);
int lx_lesson5(lx *x);
int lx_lesson6(lx *x);
int lx_lesson7(lx *x);
int lx_lesson8(lx *x);
int lx_lesson9(lx *x);
int lx_lesson10(lx *x);
int lx_lesson11(lx *x);

#endif
