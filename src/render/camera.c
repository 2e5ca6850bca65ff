/* Cameras, GL-free (see camera.h). Matrices are column-major, as GL reads them. */
#include "camera.h"

#include <math.h>
#include <string.h>

#define PI_F 3.14159265358979f

sph_orbit sph_orbit_default(void)
{
    return (sph_orbit){.yaw = 30.0f, .pitch = 25.0f, .zoom = 1.0f, .pan = {0, 0, 0}};
}

void sph_orbit_zoom_at(sph_orbit *o, const float lo[3], const float hi[3], const float at[3], float factor)
{
    /* the centre c = mid + pan maps to the rect's centre at s px/m: at's pixel offset (at - c) s stays
     * fixed when (at - c') s f = (at - c) s, so c' = at - (at - c) / f */
    for (int d = 0; d < 3; d++) {
        float centre = 0.5f * (lo[d] + hi[d]) + o->pan[d];
        o->pan[d] += (at[d] - centre) * (1.0f - 1.0f / factor);
    }
    o->zoom *= factor;
}

static void identity(float m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

static void mul(const float a[16], const float b[16], float out[16]) /* out = a b */
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int rr = 0; rr < 4; rr++) {
            float s = 0;
            for (int k = 0; k < 4; k++) s += a[k * 4 + rr] * b[c * 4 + k];
            r[c * 4 + rr] = s;
        }
    memcpy(out, r, sizeof r);
}

/* Clip space of the rect to clip space of the image: the view lands in rect. */
static void rect_to_image(const sph_camera *c, float m[16])
{
    identity(m);
    float sx = (float)c->rect[2] / (float)c->img_w, sy = (float)c->rect[3] / (float)c->img_h;
    float cx = ((float)c->rect[0] + 0.5f * (float)c->rect[2]) / (float)c->img_w * 2.0f - 1.0f;
    float cy = 1.0f - ((float)c->rect[1] + 0.5f * (float)c->rect[3]) / (float)c->img_h * 2.0f;
    m[0] = sx;
    m[5] = sy;
    m[12] = cx; /* x' = sx x + cx w */
    m[13] = cy;
}

static void fit_2d(sph_camera *c, const float lo[3], const float hi[3], const sph_orbit *o)
{
    float dx = hi[0] - lo[0], dy = hi[1] - lo[1];
    if (!(dx > 0)) dx = 1;
    if (!(dy > 0)) dy = 1;
    float zoom = o && o->zoom > 0 ? o->zoom : 1.0f;
    float s = fminf((float)c->rect[2] / dx, (float)c->rect[3] / dy) * zoom;
    c->px_per_m = s;
    float mx = 0.5f * (lo[0] + hi[0]) + (o ? o->pan[0] : 0), my = 0.5f * (lo[1] + hi[1]) + (o ? o->pan[1] : 0);
    identity(c->view);
    c->view[12] = -mx;
    c->view[13] = -my;
    /* eye to rect clip: x in [-w/2s, w/2s] -> [-1, 1] */
    float p[16], r[16];
    identity(p);
    p[0] = 2.0f * s / (float)c->rect[2];
    p[5] = 2.0f * s / (float)c->rect[3];
    p[10] = -1.0f;
    rect_to_image(c, r);
    mul(r, p, c->proj);
}

static void normalize(float v[3])
{
    float n = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0)
        for (int k = 0; k < 3; k++) v[k] /= n;
}

static void cross(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void fit_3d(sph_camera *c, const float lo[3], const float hi[3], const sph_orbit *o)
{
    sph_orbit def = sph_orbit_default();
    if (!o) o = &def;
    float ctr[3], rad = 0;
    for (int d = 0; d < 3; d++) {
        ctr[d] = 0.5f * (lo[d] + hi[d]) + o->pan[d];
        rad += 0.25f * (hi[d] - lo[d]) * (hi[d] - lo[d]);
    }
    rad = sqrtf(rad);
    if (!(rad > 0)) rad = 1;
    const float fovy = 35.0f * PI_F / 180.0f;
    float aspect = (float)c->rect[2] / (float)c->rect[3];
    float half = tanf(0.5f * fovy);
    float fit = fminf(half, half * aspect); /* the narrower half-angle's tangent */
    float zoom = o->zoom > 0 ? o->zoom : 1.0f;
    float dist = rad / sinf(atanf(fit)) / zoom;
    /* y is up, as in the 2D scenes (gravity along -y); the orbit turns about
     * it. Yaw 0, pitch 0 looks along -z: the x-y plane as in 2D. */
    float yaw = o->yaw * PI_F / 180.0f, pitch = o->pitch * PI_F / 180.0f;
    float dir[3] = {cosf(pitch) * sinf(yaw), sinf(pitch), cosf(pitch) * cosf(yaw)};
    for (int d = 0; d < 3; d++) c->eye[d] = ctr[d] + dist * dir[d];
    float f[3] = {-dir[0], -dir[1], -dir[2]}, up[3] = {0, 1, 0}, s[3], u[3];
    cross(f, up, s);
    normalize(s);
    cross(s, f, u);
    identity(c->view);
    for (int k = 0; k < 3; k++) {
        c->view[k * 4 + 0] = s[k];
        c->view[k * 4 + 1] = u[k];
        c->view[k * 4 + 2] = -f[k];
    }
    c->view[12] = -(s[0] * c->eye[0] + s[1] * c->eye[1] + s[2] * c->eye[2]);
    c->view[13] = -(u[0] * c->eye[0] + u[1] * c->eye[1] + u[2] * c->eye[2]);
    c->view[14] = (f[0] * c->eye[0] + f[1] * c->eye[1] + f[2] * c->eye[2]);
    float zn = fmaxf(dist - 2.0f * rad, 0.01f * rad), zf = dist + 2.0f * rad;
    float p[16], r[16];
    memset(p, 0, sizeof p);
    p[0] = 1.0f / (half * aspect);
    p[5] = 1.0f / half;
    p[10] = (zf + zn) / (zn - zf);
    p[11] = -1.0f;
    p[14] = 2.0f * zf * zn / (zn - zf);
    rect_to_image(c, r);
    mul(r, p, c->proj);
    c->px_per_m = 0.5f * (float)c->rect[3] / (half * dist);
}

void sph_camera_fit(sph_camera *c, int dim, const float lo[3], const float hi[3], const sph_orbit *orbit, int img_w,
                    int img_h, const int rect[4])
{
    memset(c, 0, sizeof *c);
    c->dim = dim;
    c->img_w = img_w;
    c->img_h = img_h;
    memcpy(c->rect, rect, sizeof c->rect);
    if (c->rect[2] < 1) c->rect[2] = 1;
    if (c->rect[3] < 1) c->rect[3] = 1;
    if (dim == 3)
        fit_3d(c, lo, hi, orbit);
    else
        fit_2d(c, lo, hi, orbit);
}

bool sph_camera_project(const sph_camera *c, const float x[3], float px[2], float *depth)
{
    float w4[4] = {x[0], x[1], c->dim == 3 ? x[2] : 0.0f, 1.0f}, e[4], k[4];
    for (int r = 0; r < 4; r++) e[r] = c->view[r] * w4[0] + c->view[4 + r] * w4[1] + c->view[8 + r] * w4[2] + c->view[12 + r];
    for (int r = 0; r < 4; r++) k[r] = c->proj[r] * e[0] + c->proj[4 + r] * e[1] + c->proj[8 + r] * e[2] + c->proj[12 + r] * e[3];
    if (!(k[3] > 0)) return false;
    float nx = k[0] / k[3], ny = k[1] / k[3], nz = k[2] / k[3];
    px[0] = (nx * 0.5f + 0.5f) * (float)c->img_w;
    px[1] = (0.5f - ny * 0.5f) * (float)c->img_h;
    if (depth) *depth = nz * 0.5f + 0.5f;
    return true;
}

void sph_camera_unproject(const sph_camera *c, const float px[2], const float on[3], float out[3])
{
    if (c->dim != 3) {
        /* invert the 2D chain: pixel -> image NDC -> rect NDC -> eye -> world */
        float nx = px[0] / (float)c->img_w * 2.0f - 1.0f, ny = 1.0f - px[1] / (float)c->img_h * 2.0f;
        float ex = (nx - c->proj[12]) / c->proj[0], ey = (ny - c->proj[13]) / c->proj[5];
        out[0] = ex - c->view[12];
        out[1] = ey - c->view[13];
        out[2] = 0;
        return;
    }
    /* ray through the pixel in eye space, then to world */
    float nx = px[0] / (float)c->img_w * 2.0f - 1.0f, ny = 1.0f - px[1] / (float)c->img_h * 2.0f;
    /* undo the rect mapping (x' = sx x + cx w), then the perspective */
    float sx = (float)c->rect[2] / (float)c->img_w, sy = (float)c->rect[3] / (float)c->img_h;
    float cx = ((float)c->rect[0] + 0.5f * (float)c->rect[2]) / (float)c->img_w * 2.0f - 1.0f;
    float cy = 1.0f - ((float)c->rect[1] + 0.5f * (float)c->rect[3]) / (float)c->img_h * 2.0f;
    float qx = (nx - cx) / sx, qy = (ny - cy) / sy; /* NDC of the rect */
    float p0 = c->proj[0] / sx, p5 = c->proj[5] / sy;  /* the perspective's own focal terms */
    float de[3] = {qx / p0, qy / p5, -1.0f};          /* eye-space direction */
    float dw[3], ow[3] = {c->eye[0], c->eye[1], c->eye[2]};
    /* the view's rotation is orthonormal: world = R^T eye */
    for (int k = 0; k < 3; k++) dw[k] = c->view[k * 4 + 0] * de[0] + c->view[k * 4 + 1] * de[1] + c->view[k * 4 + 2] * de[2];
    /* plane through `on` with normal along the view axis (third row of R) */
    float nrm[3] = {c->view[2], c->view[6], c->view[10]};
    float den = nrm[0] * dw[0] + nrm[1] * dw[1] + nrm[2] * dw[2];
    float t = 0;
    if (den != 0) t = (nrm[0] * (on[0] - ow[0]) + nrm[1] * (on[1] - ow[1]) + nrm[2] * (on[2] - ow[2])) / den;
    for (int k = 0; k < 3; k++) out[k] = ow[k] + t * dw[k];
}
