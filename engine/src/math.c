// Small column-major 4x4 matrix helpers and the camera transform.
#include <math.h>
#include <string.h>

#include "util.h"

void rtpbr_mat4_identity(float m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void rtpbr_mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            float s = 0.0f;
            for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

bool rtpbr_mat4_mirrors(const float m[16])
{
    double det = (double)m[0] * ((double)m[5] * m[10] - (double)m[9] * m[6]) -
                 (double)m[4] * ((double)m[1] * m[10] - (double)m[9] * m[2]) +
                 (double)m[8] * ((double)m[1] * m[6] - (double)m[5] * m[2]);
    return det < 0.0;
}

// Gauss-Jordan elimination with partial pivoting, in double precision.
bool rtpbr_mat4_invert(float out[16], const float m[16])
{
    double a[4][8];
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c) {
            a[row][c] = m[c * 4 + row];
            a[row][c + 4] = row == c ? 1.0 : 0.0;
        }
    for (int c = 0; c < 4; ++c) {
        int pivot = c;
        for (int row = c + 1; row < 4; ++row)
            if (fabs(a[row][c]) > fabs(a[pivot][c])) pivot = row;
        if (fabs(a[pivot][c]) < 1e-300) return false;
        if (pivot != c)
            for (int k = 0; k < 8; ++k) {
                double t = a[c][k];
                a[c][k] = a[pivot][k];
                a[pivot][k] = t;
            }
        double inv = 1.0 / a[c][c];
        for (int k = 0; k < 8; ++k) a[c][k] *= inv;
        for (int row = 0; row < 4; ++row) {
            if (row == c) continue;
            double f = a[row][c];
            for (int k = 0; k < 8; ++k) a[row][k] -= f * a[c][k];
        }
    }
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c) out[c * 4 + row] = (float)a[row][c + 4];
    return true;
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f) v[0] /= l, v[1] /= l, v[2] /= l;
}

static void cross3(float out[3], const float a[3], const float b[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

void rtpbr_camera_matrices(const rtpbr_camera_desc *cam, float aspect, float view_proj[16])
{
    float yfov = cam->yfov > 0.0f ? cam->yfov : 0.78539816f;
    float znear = cam->znear > 0.0f ? cam->znear : 0.01f;
    float zfar = cam->zfar > 0.0f ? cam->zfar : 1000.0f;
    float up[3] = {cam->up[0], cam->up[1], cam->up[2]};
    if (up[0] == 0.0f && up[1] == 0.0f && up[2] == 0.0f) up[1] = 1.0f;

    // Camera basis: forward f, right s, true up u (view looks down -Z).
    float f[3] = {cam->target[0] - cam->position[0], cam->target[1] - cam->position[1],
                  cam->target[2] - cam->position[2]};
    if (f[0] == 0.0f && f[1] == 0.0f && f[2] == 0.0f) f[2] = -1.0f;
    normalize3(f);
    float s[3], u[3];
    cross3(s, f, up);
    if (s[0] == 0.0f && s[1] == 0.0f && s[2] == 0.0f) { // up parallel to forward: pick another up
        float alt[3] = {1.0f, 0.0f, 0.0f};
        if (fabsf(f[0]) > 0.9f) alt[0] = 0.0f, alt[2] = 1.0f;
        cross3(s, f, alt);
    }
    normalize3(s);
    cross3(u, s, f);

    const float *p = cam->position;
    float view[16] = {
        s[0], u[0], -f[0], 0.0f,
        s[1], u[1], -f[1], 0.0f,
        s[2], u[2], -f[2], 0.0f,
        -(s[0] * p[0] + s[1] * p[1] + s[2] * p[2]),
        -(u[0] * p[0] + u[1] * p[1] + u[2] * p[2]),
        f[0] * p[0] + f[1] * p[1] + f[2] * p[2], 1.0f,
    };
    // Vulkan clip space: x right, y down, depth 0 (near) .. 1 (far).
    float t = 1.0f / tanf(0.5f * yfov);
    float proj[16] = {0};
    proj[0] = t / aspect;
    proj[5] = -t;
    proj[10] = zfar / (znear - zfar);
    proj[11] = -1.0f;
    proj[14] = znear * zfar / (znear - zfar);
    rtpbr_mat4_mul(view_proj, proj, view);
}

bool rtpbr_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i])) return false;
    return true;
}
