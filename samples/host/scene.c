// rtpbr-sample-host's mesh format: a line-based text file (samples/README.md, "rtpbr-sample-host").
//   size W H
//   camera PX PY PZ  TX TY TZ  YFOV_DEGREES
//   background R G B
//   material NAME R G B METALLIC ROUGHNESS [emission R G B] [clearcoat F ROUGHNESS] [sheen R G B ROUGHNESS]
//   tri NAME  X Y Z  X Y Z  X Y Z
//   quad NAME X Y Z  X Y Z  X Y Z  X Y Z        (planar, convex; two triangles 0 1 2, 0 2 3)
//   light R G B  X Y Z  X Y Z  X Y Z  X Y Z [two-sided]
// '#' starts a comment. Corners are counter-clockwise seen from the front; the face normal
// follows (right-hand rule). Every surface is seen from both sides.
#include "host.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_LINE = 1024, MAX_TOKENS = 24 };

typedef struct parser {
    const char *path;
    unsigned line;
    char *error;
    size_t error_size;
    // Triangles in file order, before grouping: three vertices and a material each.
    sh_vertex *vertices;
    uint32_t *material_of;
    uint32_t triangle_count;
} parser;

static int fail(parser *p, const char *fmt, ...)
{
    int n = snprintf(p->error, p->error_size, "%s:%u: ", p->path, p->line);
    if (n < 0 || (size_t)n >= p->error_size) return 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->error + n, p->error_size - (size_t)n, fmt, ap);
    va_end(ap);
    return 1;
}

// Tokens t[0 .. n) as finite floats into out.
static int numbers(parser *p, char **t, int n, float *out, const char *what)
{
    for (int i = 0; i < n; ++i) {
        char *end;
        errno = 0;
        double v = strtod(t[i], &end);
        if (end == t[i] || *end || errno == ERANGE || !isfinite(v) || fabs(v) > 1e30)
            return fail(p, "%s: '%s' is not a finite number", what, t[i]);
        out[i] = (float)v;
    }
    return 0;
}

static int non_negative(parser *p, const float *v, int n, const char *what)
{
    for (int i = 0; i < n; ++i)
        if (v[i] < 0.0f) return fail(p, "%s must not be negative", what);
    return 0;
}

static int unit_range(parser *p, float v, const char *what)
{
    return v < 0.0f || v > 1.0f ? fail(p, "%s must be in [0, 1] (got %g)", what, v) : 0;
}

static int find_material(const sh_scene *s, const char *name)
{
    for (uint32_t m = 0; m < s->material_count; ++m)
        if (!strcmp(s->materials[m].name, name)) return (int)m;
    return -1;
}

static void sub3(float o[3], const float a[3], const float b[3]) { o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2]; }
static void cross(float o[3], const float a[3], const float b[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// A face of `corners` corners (3 or 4) with material m: its triangles, the face normal.
static int add_face(parser *p, const float *c, int corners, uint32_t m)
{
    float e1[3], e2[3], n[3];
    sub3(e1, c + 3, c);
    sub3(e2, c + 6, c);
    cross(n, e1, e2); // the face normal, right-hand rule over corners 0 1 2
    float len = sqrtf(dot3(n, n));
    if (!(len > 1e-12f)) return fail(p, "degenerate face (zero area)");
    for (int k = 0; k < 3; ++k) n[k] /= len;
    if (corners == 4) { // planar and convex: corner 3 in the plane, every turn the same way
        float d[3];
        sub3(d, c + 9, c);
        if (fabsf(dot3(d, n)) > 1e-4f * (1.0f + sqrtf(dot3(d, d)))) return fail(p, "quad is not planar");
        for (int k = 0; k < 4; ++k) {
            float a[3], b[3], t[3];
            sub3(a, c + 3 * ((k + 1) % 4), c + 3 * k);
            sub3(b, c + 3 * ((k + 2) % 4), c + 3 * ((k + 1) % 4));
            cross(t, a, b);
            if (!(dot3(t, n) > 0.0f)) return fail(p, "quad is not convex (or its corners are not in order)");
        }
    }
    static const int fan[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < corners - 2; ++t) {
        if (p->triangle_count >= SH_MAX_TRIANGLES) return fail(p, "too many triangles (at most %u)", SH_MAX_TRIANGLES);
        if (!p->vertices) {
            p->vertices = malloc((size_t)SH_MAX_TRIANGLES * 3 * sizeof *p->vertices);
            p->material_of = malloc((size_t)SH_MAX_TRIANGLES * sizeof *p->material_of);
            if (!p->vertices || !p->material_of) return fail(p, "out of memory");
        }
        for (int k = 0; k < 3; ++k) {
            sh_vertex *v = &p->vertices[3 * p->triangle_count + k];
            memcpy(v->position, c + 3 * fan[t][k], sizeof v->position);
            memcpy(v->normal, n, sizeof v->normal);
        }
        p->material_of[p->triangle_count++] = m;
    }
    return 0;
}

static int parse_line(parser *p, sh_scene *s, char **t, int n, int *have_camera)
{
    const char *k = t[0];
    if (!strcmp(k, "size")) {
        if (n != 3) return fail(p, "size takes 2 values: W H");
        unsigned long v[2];
        for (int i = 0; i < 2; ++i) {
            char *end;
            errno = 0;
            v[i] = strtoul(t[1 + i], &end, 10);
            if (end == t[1 + i] || *end || t[1 + i][0] == '-' || errno || v[i] < 1 || v[i] > SH_MAX_SIZE)
                return fail(p, "size: '%s' is not a whole number in 1..%u", t[1 + i], SH_MAX_SIZE);
        }
        s->width = (uint32_t)v[0], s->height = (uint32_t)v[1];
        return 0;
    }
    if (!strcmp(k, "camera")) {
        float v[7];
        if (n != 8) return fail(p, "camera takes 7 values: PX PY PZ TX TY TZ YFOV_DEGREES");
        if (numbers(p, t + 1, 7, v, "camera")) return 1;
        float f[3];
        sub3(f, v + 3, v);
        float len = sqrtf(dot3(f, f));
        if (!(len > 1e-6f)) return fail(p, "camera: the target is the position");
        if (fabsf(f[1]) > 0.999f * len) return fail(p, "camera: looks straight up or down (up is +Y)");
        if (!(v[6] > 1.0f && v[6] < 179.0f)) return fail(p, "camera: field of view must be in (1, 179) degrees");
        memcpy(s->camera.position, v, sizeof s->camera.position);
        memcpy(s->camera.target, v + 3, sizeof s->camera.target);
        s->camera.yfov = v[6] * 3.14159265358979f / 180.0f;
        *have_camera = 1;
        return 0;
    }
    if (!strcmp(k, "background")) {
        if (n != 4) return fail(p, "background takes 3 values: R G B");
        return numbers(p, t + 1, 3, s->background, "background") || non_negative(p, s->background, 3, "background");
    }
    if (!strcmp(k, "material")) {
        if (n < 7) return fail(p, "material takes NAME R G B METALLIC ROUGHNESS [emission R G B] [clearcoat F ROUGHNESS] [sheen R G B ROUGHNESS]");
        if (strlen(t[1]) >= sizeof s->materials[0].name) return fail(p, "material name longer than %zu characters", sizeof s->materials[0].name - 1);
        if (find_material(s, t[1]) >= 0) return fail(p, "material '%s' defined twice", t[1]);
        if (s->material_count >= SH_MAX_MATERIALS) return fail(p, "too many materials (at most %u)", SH_MAX_MATERIALS);
        sh_material m = {0};
        strcpy(m.name, t[1]);
        float v[5];
        if (numbers(p, t + 2, 5, v, "material") || non_negative(p, v, 3, "base colour") || unit_range(p, v[3], "metallic") ||
            unit_range(p, v[4], "roughness"))
            return 1;
        memcpy(m.base_color, v, sizeof m.base_color);
        m.metallic = v[3], m.roughness = v[4];
        for (int i = 7; i < n;) {
            if (!strcmp(t[i], "emission") && i + 3 < n) {
                if (numbers(p, t + i + 1, 3, m.emission, "emission") || non_negative(p, m.emission, 3, "emission")) return 1;
                i += 4;
            } else if (!strcmp(t[i], "clearcoat") && i + 2 < n) {
                if (numbers(p, t + i + 1, 1, &m.clearcoat, "clearcoat") || numbers(p, t + i + 2, 1, &m.clearcoat_roughness, "clearcoat") ||
                    unit_range(p, m.clearcoat, "clearcoat") || unit_range(p, m.clearcoat_roughness, "clearcoat roughness"))
                    return 1;
                i += 3;
            } else if (!strcmp(t[i], "sheen") && i + 4 < n) {
                if (numbers(p, t + i + 1, 3, m.sheen_color, "sheen") || numbers(p, t + i + 4, 1, &m.sheen_roughness, "sheen") ||
                    non_negative(p, m.sheen_color, 3, "sheen colour") || unit_range(p, m.sheen_roughness, "sheen roughness"))
                    return 1;
                i += 5;
            } else {
                return fail(p, "material: unexpected '%s' (emission R G B, clearcoat F ROUGHNESS or sheen R G B ROUGHNESS)", t[i]);
            }
        }
        s->materials[s->material_count++] = m;
        return 0;
    }
    if (!strcmp(k, "tri") || !strcmp(k, "quad")) {
        int corners = k[0] == 't' ? 3 : 4;
        if (n != 2 + 3 * corners) return fail(p, "%s takes a material name and %d corners (X Y Z each)", k, corners);
        int m = find_material(s, t[1]);
        if (m < 0) return fail(p, "unknown material '%s' (define it first)", t[1]);
        float c[12];
        return numbers(p, t + 2, 3 * corners, c, k) || add_face(p, c, corners, (uint32_t)m);
    }
    if (!strcmp(k, "light")) {
        int two_sided = n == 17 && !strcmp(t[16], "two-sided");
        if (n != 16 && !two_sided) return fail(p, "light takes R G B and 4 corners (X Y Z each), then optionally two-sided");
        if (s->light_count >= SH_MAX_LIGHTS) return fail(p, "too many lights (at most %u)", SH_MAX_LIGHTS);
        sh_light l = {.two_sided = two_sided};
        if (numbers(p, t + 1, 3, l.radiance, "light") || non_negative(p, l.radiance, 3, "light radiance") ||
            numbers(p, t + 4, 12, &l.corners[0][0], "light"))
            return 1;
        s->lights[s->light_count++] = l; // rtpbr_light_set_update checks planarity and area
        return 0;
    }
    return fail(p, "unknown keyword '%s' (size, camera, background, material, tri, quad, light)", k);
}

int sh_scene_load(const char *path, sh_scene *s, char *error, size_t error_size)
{
    memset(s, 0, sizeof *s);
    s->width = 640, s->height = 480;
    parser p = {.path = path, .error = error, .error_size = error_size};
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(error, error_size, "%s: cannot open: %s", path, strerror(errno));
        return 1;
    }
    char line[MAX_LINE + 2];
    int have_camera = 0, status = 0;
    while (!status && fgets(line, sizeof line, f)) {
        ++p.line;
        size_t len = strlen(line);
        if (len > MAX_LINE || (len == MAX_LINE + 1 && line[len - 1] != '\n')) {
            status = fail(&p, "line longer than %d characters", MAX_LINE);
            break;
        }
        char *hash = strchr(line, '#');
        if (hash) *hash = 0;
        char *t[MAX_TOKENS + 1];
        int n = 0;
        for (char *tok = strtok(line, " \t\r\n"); tok; tok = strtok(NULL, " \t\r\n")) {
            if (n == MAX_TOKENS) { n = -1; break; }
            t[n++] = tok;
        }
        if (n < 0) status = fail(&p, "too many values on one line");
        else if (n > 0) status = parse_line(&p, s, t, n, &have_camera);
    }
    if (!status && ferror(f)) status = fail(&p, "read error");
    fclose(f);
    if (!status && !have_camera) status = fail(&p, "no camera line");
    if (!status && p.triangle_count == 0) status = fail(&p, "no tri or quad: nothing to draw");
    if (!status) { // group the triangles by material (file order within), one draw each
        s->vertices = malloc((size_t)p.triangle_count * 3 * sizeof *s->vertices);
        if (!s->vertices) status = fail(&p, "out of memory");
        for (uint32_t m = 0; !status && m < s->material_count; ++m) {
            s->draws[m].first_vertex = s->vertex_count;
            for (uint32_t i = 0; i < p.triangle_count; ++i)
                if (p.material_of[i] == m) {
                    memcpy(&s->vertices[s->vertex_count], &p.vertices[3 * i], 3 * sizeof *s->vertices);
                    s->vertex_count += 3;
                }
            s->draws[m].vertex_count = s->vertex_count - s->draws[m].first_vertex;
        }
    }
    free(p.vertices);
    free(p.material_of);
    if (status) {
        sh_scene_free(s);
        return 1;
    }
    return 0;
}

void sh_scene_free(sh_scene *s)
{
    free(s->vertices);
    memset(s, 0, sizeof *s);
}

rtpbr_material_desc sh_material_record(const sh_material *m)
{
    rtpbr_material_desc d = {.metallic = m->metallic, .roughness = m->roughness, .double_sided = 1,
        .clearcoat_factor = m->clearcoat, .clearcoat_roughness_factor = m->clearcoat_roughness,
        .sheen_roughness_factor = m->sheen_roughness};
    memcpy(d.base_color, m->base_color, sizeof d.base_color);
    memcpy(d.emission, m->emission, sizeof d.emission);
    memcpy(d.sheen_color_factor, m->sheen_color, sizeof d.sheen_color_factor);
    return d;
}

rtpbr_light_desc sh_light_record(const sh_light *l)
{
    rtpbr_light_desc d = {.vertex_count = 4, .two_sided = l->two_sided};
    memcpy(d.vertices, l->corners, sizeof l->corners);
    memcpy(d.emission, l->radiance, sizeof d.emission);
    return d;
}

static void normalize(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f) v[0] /= l, v[1] /= l, v[2] /= l;
}

// A right-handed look-at (view looks down -Z) and a perspective projection into Vulkan's clip
// space; the same convention as rtpbr_camera_desc, so rtpbr_render of the same camera rasterises
// the same pixels.
void sh_camera_matrices(const sh_camera *c, float aspect, int reversed_z, float view[16], float proj[16],
                        float view_proj[16])
{
    float f[3] = {c->target[0] - c->position[0], c->target[1] - c->position[1], c->target[2] - c->position[2]};
    normalize(f);
    float s[3] = {-f[2], 0.0f, f[0]}, u[3]; // s = f x up, up = +Y
    normalize(s);
    cross(u, s, f);
    const float *p = c->position;
    const float v[16] = {s[0], u[0], -f[0], 0.0f, s[1], u[1], -f[1], 0.0f, s[2], u[2], -f[2], 0.0f,
                         -(s[0] * p[0] + s[1] * p[1] + s[2] * p[2]), -(u[0] * p[0] + u[1] * p[1] + u[2] * p[2]),
                         f[0] * p[0] + f[1] * p[1] + f[2] * p[2], 1.0f};
    float t = 1.0f / tanf(0.5f * c->yfov); // cot(fov / 2)
    float pr[16] = {0};
    pr[0] = t / aspect;
    pr[5] = -t; // y down
    pr[10] = SH_ZFAR / (SH_ZNEAR - SH_ZFAR); // depth 0 at znear, 1 at zfar
    pr[11] = -1.0f;
    pr[14] = SH_ZNEAR * SH_ZFAR / (SH_ZNEAR - SH_ZFAR);
    if (reversed_z) { // depth 1 at znear, 0 at zfar: (n z + n f) / ((f - n) (-z))
        pr[10] = SH_ZNEAR / (SH_ZFAR - SH_ZNEAR);
        pr[14] = SH_ZNEAR * SH_ZFAR / (SH_ZFAR - SH_ZNEAR);
    }
    memcpy(view, v, sizeof v);
    memcpy(proj, pr, sizeof pr);
    for (int col = 0; col < 4; ++col) // view_proj = proj * view
        for (int row = 0; row < 4; ++row) {
            float sum = 0.0f;
            for (int k = 0; k < 4; ++k) sum += pr[k * 4 + row] * v[col * 4 + k];
            view_proj[col * 4 + row] = sum;
        }
}
