/* Cameras, GL-free: the matrices the shaders use and the same projection on
 * the CPU, so overlays (and tests) find the pixel of any point in the world.
 * Pixel coordinates have their origin at the top-left corner of the image,
 * y downwards, as in the PNG files. */
#ifndef SPH_CAMERA_H
#define SPH_CAMERA_H

#include <stdbool.h>

typedef struct sph_camera {
    int dim;              /* 2: orthographic; 3: perspective orbit */
    int img_w, img_h;     /* [px] the whole image */
    int rect[4];          /* [px] x, y (top-left), width, height of the view the domain is fitted into */
    float view[16];       /* world to eye, column-major */
    float proj[16];       /* eye to clip of the whole image, column-major */
    float eye[3];         /* [m] camera position (3D) */
    float px_per_m;       /* [px/m] scale in 2D; in 3D at the orbit's target */
} sph_camera;

/* Orbit parameters of the 3D view; zoom 1 shows the whole domain. */
typedef struct sph_orbit {
    float yaw, pitch;     /* [deg] */
    float zoom;           /* [1] > 1 comes closer */
    float pan[3];         /* [m] target offset from the domain's centre */
} sph_orbit;

sph_orbit sph_orbit_default(void);

/* Zooms the orbit by factor towards the world point at, whose pixel stays
 * where it is in 2D (3D: the orbit's target moves towards it alike);
 * lo, hi: the domain box the camera is fitted to. */
void sph_orbit_zoom_at(sph_orbit *o, const float lo[3], const float hi[3], const float at[3], float factor);

/* Fits the domain box [lo, hi] into rect (2D: x-y, aspect kept; 3D: the
 * orbit looks at the box's centre from a distance that shows all of it). */
void sph_camera_fit(sph_camera *c, int dim, const float lo[3], const float hi[3], const sph_orbit *orbit, int img_w,
                    int img_h, const int rect[4]);

/* World point to pixel; *depth in [0, 1] (0 near). False if behind the camera. */
bool sph_camera_project(const sph_camera *c, const float x[3], float px[2], float *depth);

/* Pixel to a world point: in 2D exact (z = 0); in 3D on the plane through
 * `on` facing the camera. */
void sph_camera_unproject(const sph_camera *c, const float px[2], const float on[3], float out[3]);

#endif
