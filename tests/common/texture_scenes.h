// Small glTF scenes for the texture tests of both renderers (tests/engine/test_engine_textures.c,
// tests/oracle/test_texture_settings.cpp): one textured quad in a white furnace, written as a
// self-contained .gltf (buffer and PNG as data: URIs) so that the loader reads it as any file.
//
// The scene: a Lambertian quad [-1, 1]^2 in the plane z = 0 facing +Z (or -Z when
// `facing_away`), base colour = its texture (no specular: KHR_materials_specular 0), inside an
// emissive box of radiance 1 (|x|, |y|, |z| <= 10, double-sided, so every face is a light of the
// loader) that makes the quad's radiance equal its albedo (or, with `material_extensions`, the
// albedo of the extensions' lobes over a black base). A camera at (0, 0, 3) looks down -Z
// with a vertical field of view of 2 atan(1/3), so the quad fills a square image exactly.
// TEXCOORD_0 runs from uv_min at the quad's top-left corner (x = -1, y = +1) to uv_max at its
// bottom-right corner; TEXCOORD_1 holds the same values, and TEXCOORD_0 is all zero when the
// texture transform overrides texCoord with 1 (so that only the right set shows the texture).
// Header-only, C and C++.
#ifndef RTPBR_TESTS_TEXTURE_SCENES_H
#define RTPBR_TESTS_TEXTURE_SCENES_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct texture_scene {
    uint32_t texture_width, texture_height;
    const uint8_t *rgba;          // texture_width * texture_height texels, rows top to bottom
    int wrap_s, wrap_t;           // glTF codes (10497 repeat, 33071 clamp, 33648 mirror)
    int mag_filter, min_filter;   // glTF codes; 0: absent
    float uv_min[2], uv_max[2];   // TEXCOORD_0 (and _1) at the top-left and bottom-right corners
    int facing_away;              // the quad faces -Z (away from the camera)
    int double_sided;
    // KHR_texture_transform on baseColorTexture (when has_transform).
    int has_transform;
    float offset[2], rotation, scale[2];
    int texcoord;                 // the transform's texCoord override (-1: none)
    // glTF alpha of the quad's material: 0 OPAQUE (alpha not written), 1 MASK, 2 BLEND, with
    // baseColorFactor (1, 1, 1, base_alpha) and alphaCutoff (MASK; 0: absent, glTF's 0.5).
    int alpha_mode;
    float base_alpha, alpha_cutoff;
    // When given: the quad's material is black (baseColorFactor 0, no baseColorTexture,
    // metallic 0) with these material extensions, the body of its "extensions" object (which
    // may use the texture as {"index":0}); extensions_used: their names, the body of a JSON
    // list. Default: the texture is the base colour of a Lambertian quad.
    const char *material_extensions;
    const char *extensions_used;
} texture_scene;

// The camera: at (0, 0, 3) looking down -Z, tan(yfov / 2) = 1/3.
#define TEXTURE_SCENE_CAMERA_Z 3.0
#define TEXTURE_SCENE_TAN_HALF_FOV (1.0 / 3.0)

// The quad point seen through the centre of pixel (px, py) of a square image of n pixels:
// plane z = 0, x, y in [-1, 1] (y up).
static inline void texture_scene_pixel_point(uint32_t px, uint32_t py, uint32_t n, double *x, double *y)
{
    *x = (2.0 * (px + 0.5) / n - 1.0) * TEXTURE_SCENE_TAN_HALF_FOV * TEXTURE_SCENE_CAMERA_Z;
    *y = (1.0 - 2.0 * (py + 0.5) / n) * TEXTURE_SCENE_TAN_HALF_FOV * TEXTURE_SCENE_CAMERA_Z;
}

// The quad of a w x h texture, uv 0 to 1 across it, no texture transform; wrap: both axes' glTF
// wrap mode, filter: both filters' glTF code (0: absent).
static inline texture_scene texture_scene_quad(uint32_t w, uint32_t h, const uint8_t *rgba, int wrap, int filter)
{
    texture_scene s;
    memset(&s, 0, sizeof s);
    s.texture_width = w;
    s.texture_height = h;
    s.rgba = rgba;
    s.wrap_s = s.wrap_t = wrap;
    s.mag_filter = s.min_filter = filter;
    s.uv_max[0] = s.uv_max[1] = 1.0f;
    s.texcoord = -1;
    return s;
}

// The quad of one red texel (repeat): the starting point of the alpha and back-face tests of
// both renderers.
static inline texture_scene texture_scene_red_quad(void)
{
    static const uint8_t red[4] = {255, 0, 0, 255};
    return texture_scene_quad(1, 1, red, 10497, 0);
}

// The quad of a 4 x 4 texture (nearest, repeat) through KHR_texture_transform (offset
// (0.3, -0.2), rotation 0.5, scale (1.5, 0.75)) read through TEXCOORD_1 (the transform's texCoord
// override; TEXCOORD_0 is all zero): the transform test of both renderers.
static inline texture_scene texture_scene_transformed_quad(const uint8_t *rgba)
{
    texture_scene s = texture_scene_quad(4, 4, rgba, 10497, 9728);
    s.has_transform = 1;
    s.offset[0] = 0.3f;
    s.offset[1] = -0.2f;
    s.rotation = 0.5f;
    s.scale[0] = 1.5f;
    s.scale[1] = 0.75f;
    s.texcoord = 1;
    return s;
}

// ---- writing ---------------------------------------------------------------------------------

static inline uint32_t texture_scene_crc(const uint8_t *p, size_t n, uint32_t crc)
{
    crc = ~crc;
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static inline void texture_scene_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24), p[1] = (uint8_t)(v >> 16), p[2] = (uint8_t)(v >> 8), p[3] = (uint8_t)v;
}

// An RGBA8 PNG with stored (uncompressed) deflate blocks; returns its size, *out malloc'ed.
static inline size_t texture_scene_png(uint32_t w, uint32_t h, const uint8_t *rgba, uint8_t **out)
{
    size_t raw_size = (size_t)h * (1 + 4 * (size_t)w);
    uint8_t *raw = (uint8_t *)malloc(raw_size);
    for (uint32_t y = 0; y < h; ++y) {
        raw[y * (1 + 4 * (size_t)w)] = 0; // filter: none
        memcpy(raw + y * (1 + 4 * (size_t)w) + 1, rgba + 4 * (size_t)w * y, 4 * (size_t)w);
    }
    size_t blocks = raw_size / 65535 + 1;
    size_t zsize = 2 + raw_size + 5 * blocks + 4;
    size_t size = 8 + 25 + (12 + zsize) + 12;
    uint8_t *p = (uint8_t *)malloc(size), *q = p;
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(q, signature, 8), q += 8;
    texture_scene_be32(q, 13), memcpy(q + 4, "IHDR", 4);
    texture_scene_be32(q + 8, w), texture_scene_be32(q + 12, h);
    q[16] = 8, q[17] = 6, q[18] = 0, q[19] = 0, q[20] = 0; // 8-bit RGBA
    texture_scene_be32(q + 21, texture_scene_crc(q + 4, 17, 0)), q += 25;
    texture_scene_be32(q, (uint32_t)zsize), memcpy(q + 4, "IDAT", 4);
    uint8_t *z = q + 8;
    z[0] = 0x78, z[1] = 0x01;
    size_t at = 2;
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < raw_size; ++i) a = (a + raw[i]) % 65521u, b = (b + a) % 65521u;
    for (size_t done = 0, k = 0; k < blocks; ++k) {
        size_t n = raw_size - done < 65535 ? raw_size - done : 65535;
        z[at] = k + 1 == blocks ? 1 : 0;
        z[at + 1] = (uint8_t)n, z[at + 2] = (uint8_t)(n >> 8);
        z[at + 3] = (uint8_t)~n, z[at + 4] = (uint8_t)(~n >> 8);
        memcpy(z + at + 5, raw + done, n);
        at += 5 + n, done += n;
    }
    texture_scene_be32(z + at, (b << 16) | a);
    texture_scene_be32(q + 8 + zsize, texture_scene_crc(q + 4, 4 + zsize, 0)), q += 12 + zsize;
    texture_scene_be32(q, 0), memcpy(q + 4, "IEND", 4), texture_scene_be32(q + 8, texture_scene_crc(q + 4, 4, 0));
    free(raw);
    *out = p;
    return size;
}

static inline void texture_scene_base64(FILE *f, const uint8_t *p, size_t n)
{
    static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16 | (i + 1 < n ? (uint32_t)p[i + 1] << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
        fputc(table[v >> 18 & 63], f), fputc(table[v >> 12 & 63], f);
        fputc(i + 1 < n ? table[v >> 6 & 63] : '=', f), fputc(i + 2 < n ? table[v & 63] : '=', f);
    }
}

// Writes the scene to `path`; returns 0 on success.
static inline int texture_scene_write(const texture_scene *s, const char *path)
{
    // Buffer: quad positions (4 x vec3), normals, TEXCOORD_0, TEXCOORD_1, indices (6 x u16 + pad);
    // box positions (8 x vec3), box indices (36 x u16), inward faces.
    float quad_pos[12] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
    float nz = s->facing_away ? -1.0f : 1.0f;
    float quad_nrm[12] = {0, 0, nz, 0, 0, nz, 0, 0, nz, 0, 0, nz};
    float uv[8] = {s->uv_min[0], s->uv_min[1], s->uv_max[0], s->uv_min[1],
                   s->uv_max[0], s->uv_max[1], s->uv_min[0], s->uv_max[1]};
    // Counter-clockwise seen from +Z: 3 2 1, 3 1 0 (top-left 0, top-right 1, bottom-right 2, bottom-left 3).
    uint16_t front[8] = {3, 2, 1, 3, 1, 0, 0, 0}, away[8] = {3, 1, 2, 3, 0, 1, 0, 0};
    const float e = 10.0f;
    float box_pos[24] = {-e, -e, -e, e, -e, -e, e, e, -e, -e, e, -e, -e, -e, e, e, -e, e, e, e, e, -e, e, e};
    uint16_t box_idx[36] = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                            3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
    uint8_t buffer[48 + 48 + 32 + 32 + 16 + 96 + 72];
    size_t at = 0;
#define TEXTURE_SCENE_PUT(array) (memcpy(buffer + at, array, sizeof array), at += sizeof array)
    TEXTURE_SCENE_PUT(quad_pos);
    TEXTURE_SCENE_PUT(quad_nrm);
    float zeros[8] = {0};
    if (s->has_transform && s->texcoord == 1) TEXTURE_SCENE_PUT(zeros);
    else TEXTURE_SCENE_PUT(uv);
    TEXTURE_SCENE_PUT(uv);
    if (s->facing_away) TEXTURE_SCENE_PUT(away);
    else TEXTURE_SCENE_PUT(front);
    TEXTURE_SCENE_PUT(box_pos);
    TEXTURE_SCENE_PUT(box_idx);
#undef TEXTURE_SCENE_PUT
    uint8_t *png = NULL;
    size_t png_size = texture_scene_png(s->texture_width, s->texture_height, s->rgba, &png);
    FILE *f = fopen(path, "w");
    if (!f) {
        free(png);
        return -1;
    }
    const int zero0 = s->has_transform && s->texcoord == 1;
    float lo0 = fminf(s->uv_min[0], s->uv_max[0]), hi0 = fmaxf(s->uv_min[0], s->uv_max[0]);
    float lo1 = fminf(s->uv_min[1], s->uv_max[1]), hi1 = fmaxf(s->uv_min[1], s->uv_max[1]);
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],\n");
    fprintf(f, "\"extensionsUsed\":[%s%s],\n",
            s->material_extensions ? s->extensions_used : "\"KHR_materials_specular\"",
            s->has_transform ? ",\"KHR_texture_transform\"" : "");
    if (s->has_transform) fprintf(f, "\"extensionsRequired\":[\"KHR_texture_transform\"],\n");
    fprintf(f, "\"nodes\":[{\"mesh\":0},{\"mesh\":1},{\"camera\":0,\"translation\":[0,0,%g]}],\n",
            TEXTURE_SCENE_CAMERA_Z);
    fprintf(f, "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":%.9g,\"aspectRatio\":1,"
               "\"znear\":0.05,\"zfar\":100}}],\n",
            2.0 * atan(TEXTURE_SCENE_TAN_HALF_FOV));
    fprintf(f, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2,"
               "\"TEXCOORD_1\":3},\"indices\":4,\"material\":0}]},\n"
               "{\"primitives\":[{\"attributes\":{\"POSITION\":5},\"indices\":6,\"material\":1}]}],\n");
    if (s->material_extensions) {
        fprintf(f, "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0},"
                   "\"doubleSided\":%s,\"extensions\":{%s}},\n",
                s->double_sided ? "true" : "false", s->material_extensions);
    } else {
        fprintf(f, "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0");
        if (s->has_transform) {
            fprintf(f, ",\"extensions\":{\"KHR_texture_transform\":{\"offset\":[%.9g,%.9g],\"rotation\":%.9g,"
                       "\"scale\":[%.9g,%.9g]",
                    s->offset[0], s->offset[1], s->rotation, s->scale[0], s->scale[1]);
            if (s->texcoord >= 0) fprintf(f, ",\"texCoord\":%d", s->texcoord);
            fprintf(f, "}}");
        }
        fprintf(f, "},\"metallicFactor\":0,\"roughnessFactor\":1");
        if (s->alpha_mode) fprintf(f, ",\"baseColorFactor\":[1,1,1,%.9g]", s->base_alpha);
        fprintf(f, "},\"doubleSided\":%s,", s->double_sided ? "true" : "false");
        if (s->alpha_mode) fprintf(f, "\"alphaMode\":\"%s\",", s->alpha_mode == 1 ? "MASK" : "BLEND");
        if (s->alpha_mode == 1 && s->alpha_cutoff > 0.0f) fprintf(f, "\"alphaCutoff\":%.9g,", s->alpha_cutoff);
        fprintf(f, "\"extensions\":{\"KHR_materials_specular\":{\"specularFactor\":0}}},\n");
    }
    fprintf(f, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0},"
               "\"emissiveFactor\":[1,1,1],\"doubleSided\":true}],\n");
    fprintf(f, "\"textures\":[{\"source\":0,\"sampler\":0}],\n\"samplers\":[{\"wrapS\":%d,\"wrapT\":%d", s->wrap_s,
            s->wrap_t);
    if (s->mag_filter) fprintf(f, ",\"magFilter\":%d", s->mag_filter);
    if (s->min_filter) fprintf(f, ",\"minFilter\":%d", s->min_filter);
    fprintf(f, "}],\n\"images\":[{\"uri\":\"data:image/png;base64,");
    texture_scene_base64(f, png, png_size);
    fprintf(f, "\"}],\n");
    fprintf(f, "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
               "\"min\":[-1,-1,0],\"max\":[1,1,0]},\n"
               "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},\n"
               "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\","
               "\"min\":[%.9g,%.9g],\"max\":[%.9g,%.9g]},\n"
               "{\"bufferView\":3,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\","
               "\"min\":[%.9g,%.9g],\"max\":[%.9g,%.9g]},\n"
               "{\"bufferView\":4,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},\n"
               "{\"bufferView\":5,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\",\"min\":[-10,-10,-10],"
               "\"max\":[10,10,10]},\n"
               "{\"bufferView\":6,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"}],\n",
            zero0 ? 0.0f : lo0, zero0 ? 0.0f : lo1, zero0 ? 0.0f : hi0, zero0 ? 0.0f : hi1, lo0, lo1, hi0, hi1);
    fprintf(f, "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,"
               "\"byteLength\":48},{\"buffer\":0,\"byteOffset\":96,\"byteLength\":32},{\"buffer\":0,"
               "\"byteOffset\":128,\"byteLength\":32},{\"buffer\":0,\"byteOffset\":160,\"byteLength\":12},"
               "{\"buffer\":0,\"byteOffset\":176,\"byteLength\":96},{\"buffer\":0,\"byteOffset\":272,"
               "\"byteLength\":72}],\n");
    fprintf(f, "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,", at);
    texture_scene_base64(f, buffer, at);
    fprintf(f, "\"}]}\n");
    free(png);
    return fclose(f) == 0 ? 0 : -1;
}

// ---- the alpha shadow scene ------------------------------------------------------------------
//
// A white Lambertian floor [-1, 1]^2 at z = 0 facing +Z (no specular), lit by a small square
// light (side ALPHA_SHADOW_LIGHT_SIZE, radiance 50, facing -Z) at height 4 above its centre,
// and between them, at z = 1, an occluder quad [-1, 1]^2 facing -Z (toward the floor), black,
// single-sided, with alphaMode MASK (cutoff 0.5) and a base colour texture whose alpha is
// `rgba`'s (rows top to bottom = +Y to -Y, as the texture_scene quad). The camera of
// texture_scene (at (0, 0, 3), looking down -Z, square image = the floor) sees the occluder from
// behind, so it is not drawn: the image is the floor, lit where the occluder is cut out.
// `opaque`: alphaMode OPAQUE instead (the control: no light reaches the floor below it).
#define ALPHA_SHADOW_LIGHT_SIZE 0.2
static inline int alpha_shadow_scene_write(uint32_t w, uint32_t h, const uint8_t *rgba, int opaque, const char *path)
{
    // floor (4 vec3 positions, 4 normals, 4 uv), occluder (4 positions, 4 normals, 4 uv),
    // light (4 positions), indices: floor, occluder, light (6 u16 each).
    float floor_pos[12] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
    float up[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    float occ_pos[12] = {-1, 1, 1, 1, 1, 1, 1, -1, 1, -1, -1, 1};
    float down[12] = {0, 0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1};
    float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const float l = (float)ALPHA_SHADOW_LIGHT_SIZE / 2;
    float light_pos[12] = {-l, l, 4, l, l, 4, l, -l, 4, -l, -l, 4};
    uint16_t ccw_up[6] = {3, 2, 1, 3, 1, 0}, ccw_down[6] = {3, 1, 2, 3, 0, 1};
    uint8_t buffer[48 * 2 + 32 + 48 * 2 + 32 + 48 + 12 * 3];
    size_t at = 0;
#define ALPHA_SHADOW_PUT(array) (memcpy(buffer + at, array, sizeof array), at += sizeof array)
    ALPHA_SHADOW_PUT(floor_pos), ALPHA_SHADOW_PUT(up), ALPHA_SHADOW_PUT(uv);          // 0, 48, 96
    ALPHA_SHADOW_PUT(occ_pos), ALPHA_SHADOW_PUT(down), ALPHA_SHADOW_PUT(uv);          // 128, 176, 224
    ALPHA_SHADOW_PUT(light_pos);                                                        // 256
    ALPHA_SHADOW_PUT(ccw_up), ALPHA_SHADOW_PUT(ccw_down), ALPHA_SHADOW_PUT(ccw_down);  // 304, 316, 328
#undef ALPHA_SHADOW_PUT
    uint8_t *png = NULL;
    size_t png_size = texture_scene_png(w, h, rgba, &png);
    FILE *f = fopen(path, "w");
    if (!f) {
        free(png);
        return -1;
    }
    fprintf(f, "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3]}],\n");
    fprintf(f, "\"extensionsUsed\":[\"KHR_materials_specular\",\"KHR_materials_emissive_strength\"],\n");
    fprintf(f, "\"nodes\":[{\"mesh\":0},{\"mesh\":1},{\"mesh\":2},{\"camera\":0,\"translation\":[0,0,%g]}],\n",
            TEXTURE_SCENE_CAMERA_Z);
    fprintf(f, "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":%.9g,\"aspectRatio\":1,"
               "\"znear\":0.05,\"zfar\":100}}],\n",
            2.0 * atan(TEXTURE_SCENE_TAN_HALF_FOV));
    fprintf(f, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
               "\"indices\":7,\"material\":0}]},\n"
               "{\"primitives\":[{\"attributes\":{\"POSITION\":3,\"NORMAL\":4,\"TEXCOORD_0\":5},\"indices\":8,"
               "\"material\":1}]},\n"
               "{\"primitives\":[{\"attributes\":{\"POSITION\":6},\"indices\":9,\"material\":2}]}],\n");
    fprintf(f, "\"materials\":[{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":1},"
               "\"extensions\":{\"KHR_materials_specular\":{\"specularFactor\":0}}},\n"
               "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"baseColorTexture\":{\"index\":0},"
               "\"metallicFactor\":0,\"roughnessFactor\":1},%s"
               "\"extensions\":{\"KHR_materials_specular\":{\"specularFactor\":0}}},\n"
               "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1],\"metallicFactor\":0},"
               "\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":"
               "{\"emissiveStrength\":50}}}],\n",
            opaque ? "" : "\"alphaMode\":\"MASK\",");
    fprintf(f, "\"textures\":[{\"source\":0,\"sampler\":0}],\n\"samplers\":[{\"magFilter\":9728,"
               "\"minFilter\":9728,\"wrapS\":33071,\"wrapT\":33071}],\n\"images\":[{\"uri\":\"data:image/png;base64,");
    texture_scene_base64(f, png, png_size);
    fprintf(f, "\"}],\n\"accessors\":[");
    const char *vec3 = "{\"bufferView\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"%s},\n";
    char minmax[96];
    for (int i = 0; i < 7; ++i) {
        if (i == 2 || i == 5) {
            fprintf(f, "{\"bufferView\":%d,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},\n", i);
            continue;
        }
        float z = i == 0 ? 0.0f : i == 3 ? 1.0f : 4.0f, e = i == 6 ? l : 1.0f;
        if (i == 0 || i == 3 || i == 6) snprintf(minmax, sizeof minmax, ",\"min\":[%g,%g,%g],\"max\":[%g,%g,%g]", -e, -e, z, e, e, z);
        else minmax[0] = 0;
        fprintf(f, vec3, i, minmax);
    }
    for (int i = 7; i < 10; ++i)
        fprintf(f, "{\"bufferView\":%d,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}%s\n", i,
                i < 9 ? "," : "],");
    static const int offsets[10] = {0, 48, 96, 128, 176, 224, 256, 304, 316, 328};
    static const int lengths[10] = {48, 48, 32, 48, 48, 32, 48, 12, 12, 12};
    fprintf(f, "\"bufferViews\":[");
    for (int i = 0; i < 10; ++i)
        fprintf(f, "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":%d}%s", offsets[i], lengths[i], i < 9 ? "," : "],\n");
    fprintf(f, "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,", at);
    texture_scene_base64(f, buffer, at);
    fprintf(f, "\"}]}\n");
    free(png);
    return fclose(f) == 0 ? 0 : -1;
}

// ---- expectations (closed form, independent of both renderers) ------------------------------

// glTF wrap of a texture coordinate into [0, 1) (clamp: [0, 1]).
static inline double texture_scene_wrap(double u, int mode)
{
    if (mode == 33071) return u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
    if (mode == 33648) {
        double m = u - 2.0 * floor(u / 2.0); // [0, 2)
        return m < 1.0 ? m : 2.0 - m;
    }
    return u - floor(u);
}

// The texel (nearest) a wrapped coordinate falls in, and how far (in texels) it is from the
// nearest texel edge across which the texel changes (clamped coordinates outside (0, 1) are
// far from every edge).
static inline int texture_scene_texel(double u, int mode, uint32_t n, double *edge_distance)
{
    double w = texture_scene_wrap(u, mode) * n;
    int i = (int)floor(w);
    if (i >= (int)n) i = (int)n - 1;
    double f = w - i;
    *edge_distance = fmin(f, 1.0 - f);
    if (mode == 33071) { // no seam at 0 and 1: only the edges between texels count
        if (u <= 0.0 || u >= 1.0) *edge_distance = 1.0;
        else if (i == 0) *edge_distance = n > 1 ? 1.0 - f : 1.0;
        else if (i == (int)n - 1) *edge_distance = f;
    }
    return i;
}

// TEXCOORD_0 at the quad point (x, y) (linear between the corners).
static inline void texture_scene_uv(const texture_scene *s, double x, double y, double uv[2])
{
    double tx = (x + 1.0) / 2.0, ty = (1.0 - y) / 2.0;
    uv[0] = s->uv_min[0] + tx * (s->uv_max[0] - s->uv_min[0]);
    uv[1] = s->uv_min[1] + ty * (s->uv_max[1] - s->uv_min[1]);
}

// KHR_texture_transform, the spec's matrix T R S written out: its example (offset (0, 1),
// rotation pi/2, scale 0.5: "the lower left quadrant of the source image, rotated clockwise
// 90 degrees") fixes the signs: u' = sx u cos r + sy v sin r + ox, v' = -sx u sin r + sy v cos r + oy.
static inline void texture_scene_transform(const texture_scene *s, const double uv[2], double out[2])
{
    double c = cos(s->rotation), n = sin(s->rotation);
    double su = s->scale[0] * uv[0], sv = s->scale[1] * uv[1];
    out[0] = c * su + n * sv + s->offset[0];
    out[1] = -n * su + c * sv + s->offset[1];
}

// The 4 x 4 RGBA texture of the transform tests: 16 distinct colours, each channel one of 0,
// 128, 255 (the base-3 digits of the texel's index), opaque.
static inline void texture_scene_distinct_texels(uint8_t texels[64])
{
    static const uint8_t levels[3] = {0, 128, 255};
    for (int i = 0; i < 16; ++i) {
        texels[4 * i] = levels[i % 3];
        texels[4 * i + 1] = levels[i / 3 % 3];
        texels[4 * i + 2] = levels[i / 9 % 3];
        texels[4 * i + 3] = 255;
    }
}

// sRGB 8-bit to linear (IEC 61966-2-1), for expected base colours.
static inline double texture_scene_srgb_to_linear(uint8_t v)
{
    double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

#endif // RTPBR_TESTS_TEXTURE_SCENES_H
