#define _POSIX_C_SOURCE 200809L
#include "test_scene_util.h"
#include "test_main.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

char* ts_format(const char* fmt, ...) {
    va_list a, b;
    va_start(a, fmt);
    va_copy(b, a);
    char probe[1];
    int n = vsnprintf(probe, sizeof probe, fmt, a);
    va_end(a);
    char* s = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (!s) abort(); /* test helper: no way to go on */
    vsnprintf(s, (size_t)n + 1, fmt, b);
    va_end(b);
    return s;
}

char* ts_data_uri(const char* mime, const void* data, size_t size) {
    static const char tbl[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned char* p = data;
    size_t prefix = strlen("data:;base64,") + strlen(mime);
    char* s = malloc(prefix + 4 * ((size + 2) / 3) + 1);
    char* o = s + sprintf(s, "data:%s;base64,", mime);
    for (size_t i = 0; i < size; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16;
        if (i + 1 < size) v |= (uint32_t)p[i + 1] << 8;
        if (i + 2 < size) v |= p[i + 2];
        *o++ = tbl[(v >> 18) & 63];
        *o++ = tbl[(v >> 12) & 63];
        *o++ = i + 1 < size ? tbl[(v >> 6) & 63] : '=';
        *o++ = i + 2 < size ? tbl[v & 63] : '=';
    }
    *o = '\0';
    return s;
}

size_t ts_bin_append(ts_bin* bin, const void* data, size_t size) {
    while (bin->size % 4) bin->bytes[bin->size++] = 0;
    size_t at = bin->size;
    memcpy(bin->bytes + at, data, size);
    bin->size += size;
    return at;
}

void ts_scene_bin(const ts_scene* s, ts_bin* bin) {
    bin->size = 0;
    ts_bin_append(bin, s->positions, s->vertex_count * 3 * sizeof(float));
    ts_bin_append(bin, s->indices, s->index_count * sizeof(uint32_t));
    if (s->texcoords) ts_bin_append(bin, s->texcoords, s->vertex_count * 2 * sizeof(float));
}

char* ts_scene_json(const ts_scene* s) {
    ts_bin* bin = malloc(sizeof *bin);
    ts_scene_bin(s, bin);
    const size_t pos_bytes = s->vertex_count * 12, idx_bytes = s->index_count * 4;
    char* uri = s->buffer_uri ? ts_format("%s", s->buffer_uri)
                              : ts_data_uri("application/octet-stream", bin->bytes, bin->size);
    const size_t idx_at = (pos_bytes + 3) / 4 * 4, uv_at = idx_at + idx_bytes;
    char* uv_view = s->texcoords ? ts_format(",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}",
                                             uv_at, s->vertex_count * 8)
                                 : ts_format("%s", "");
    char* uv_accessor = s->texcoords
        ? ts_format(",{\"bufferView\":2,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"}",
                    s->vertex_count)
        : ts_format("%s", "");
    char* accessors = s->accessors
        ? ts_format("%s", s->accessors)
        : ts_format("{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
                    "{\"bufferView\":1,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}%s",
                    s->vertex_count, s->index_count, uv_accessor);
    char* material = s->material >= 0 ? ts_format(",\"material\":%d", s->material) : ts_format("%s", "");
    char* meshes = s->meshes ? ts_format("%s", s->meshes)
                             : ts_format("{\"primitives\":[{\"attributes\":{\"POSITION\":0%s},\"indices\":1%s}]}",
                                         s->texcoords ? ",\"TEXCOORD_0\":2" : "", material);
    char* json = ts_format(
        "{\"asset\":{\"version\":\"2.0\"},"
        "\"buffers\":[{\"uri\":\"%s\",\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}%s],"
        "\"accessors\":[%s],\"meshes\":[%s],\"materials\":[%s],"
        "\"nodes\":[%s],\"scenes\":[{\"nodes\":[%s]}],\"scene\":0%s}",
        uri, bin->size, pos_bytes, idx_at, idx_bytes, uv_view, accessors, meshes,
        s->materials ? s->materials : "", s->nodes ? s->nodes : "{\"mesh\":0}",
        s->scene_nodes ? s->scene_nodes : "0", s->extra ? s->extra : "");
    free(uri);
    free(accessors);
    free(uv_view);
    free(uv_accessor);
    free(material);
    free(meshes);
    free(bin);
    return json;
}

unsigned char* ts_glb(const char* json, const void* bin, size_t bin_size, size_t* size) {
    const size_t jlen = (strlen(json) + 3) / 4 * 4, blen = (bin_size + 3) / 4 * 4;
    const size_t total = 20 + jlen + (bin ? 8 + blen : 0);
    unsigned char* glb = calloc(1, total);
    if (!glb) abort();
    const uint32_t h[5] = {0x46546C67u, 2, (uint32_t)total, (uint32_t)jlen, 0x4E4F534Au}; /* "glTF", "JSON" */
    memcpy(glb, h, 20);
    memset(glb + 20, ' ', jlen);
    memcpy(glb + 20, json, strlen(json));
    if (bin) {
        const uint32_t bh[2] = {(uint32_t)blen, 0x004E4942u}; /* "BIN\0" */
        memcpy(glb + 20 + jlen, bh, 8);
        memcpy(glb + 28 + jlen, bin, bin_size);
    }
    *size = total;
    return glb;
}

/* ---- PNG (ISO/IEC 15948): signature, IHDR, one IDAT with stored deflate
 * blocks (RFC 1950/1951), IEND. CRC-32 and Adler-32 computed bitwise. */
static uint32_t crc32_update(uint32_t crc, const unsigned char* p, size_t n) {
    crc = ~crc;
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static void put_be32(unsigned char* p, uint32_t v) {
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static size_t put_chunk(unsigned char* out, const char* type, const unsigned char* data, uint32_t n) {
    put_be32(out, n);
    memcpy(out + 4, type, 4);
    if (n) memcpy(out + 8, data, n);
    put_be32(out + 8 + n, crc32_update(0, out + 4, 4 + (size_t)n));
    return 12 + (size_t)n;
}

unsigned char* ts_png(const unsigned char* rgba, uint32_t w, uint32_t h, size_t* size) {
    const size_t raw_size = (size_t)h * (1 + 4 * (size_t)w);
    unsigned char* raw = malloc(raw_size);
    for (uint32_t y = 0; y < h; ++y) {
        raw[y * (1 + 4 * (size_t)w)] = 0; /* filter: none */
        memcpy(raw + y * (1 + 4 * (size_t)w) + 1, rgba + (size_t)y * w * 4, 4 * (size_t)w);
    }
    const size_t blocks = raw_size / 65535 + 1;
    const size_t z_size = 2 + raw_size + 5 * blocks + 4;
    unsigned char* z = malloc(z_size);
    size_t zi = 0;
    z[zi++] = 0x78;
    z[zi++] = 0x01;
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < raw_size; ++i) a = (a + raw[i]) % 65521u, b = (b + a) % 65521u;
    for (size_t off = 0, k = 0; k < blocks; ++k) {
        size_t len = raw_size - off < 65535 ? raw_size - off : 65535;
        z[zi++] = k + 1 == blocks ? 1 : 0;
        z[zi++] = (unsigned char)(len & 0xff);
        z[zi++] = (unsigned char)(len >> 8);
        z[zi++] = (unsigned char)(~len & 0xff);
        z[zi++] = (unsigned char)((~len >> 8) & 0xff);
        memcpy(z + zi, raw + off, len);
        zi += len;
        off += len;
    }
    put_be32(z + zi, (b << 16) | a);
    zi += 4;
    unsigned char ihdr[13];
    put_be32(ihdr, w);
    put_be32(ihdr + 4, h);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 6;  /* RGBA */
    ihdr[10] = ihdr[11] = ihdr[12] = 0;
    unsigned char* png = malloc(8 + 25 + 12 + zi + 12);
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(png, sig, 8);
    size_t n = 8;
    n += put_chunk(png + n, "IHDR", ihdr, 13);
    n += put_chunk(png + n, "IDAT", z, (uint32_t)zi);
    n += put_chunk(png + n, "IEND", NULL, 0);
    free(raw);
    free(z);
    *size = n;
    return png;
}

static void remove_tree(const char* dir) {
    char* cmd = ts_format("rm -rf -- '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not clean %s\n", dir);
    free(cmd);
}

const char* ts_dir(const char* name) {
    static char path[4096];
    const char* root = getenv("RTPBR_GLTF_TEST_DIR");
    snprintf(path, sizeof path, "%s/scene-test-data", root ? root : "/tmp");
    mkdir(path, 0755);
    snprintf(path, sizeof path, "%s/scene-test-data/%s", root ? root : "/tmp", name);
    remove_tree(path);
    if (mkdir(path, 0755) != 0 && errno != EEXIST) perror(path);
    return path;
}

char* ts_path(const char* dir, const char* file) { return ts_format("%s/%s", dir, file); }

int ts_exists(const char* path) { return access(path, F_OK) == 0; }

void ts_write(const char* dir, const char* file, const void* data, size_t size) {
    char* p = ts_path(dir, file);
    FILE* f = fopen(p, "wb");
    if (f) {
        fwrite(data, 1, size, f);
        fclose(f);
    }
    free(p);
}

rtpbr_gltf_result ts_load_text(const char* dir, const char* name, const char* text,
                                const rtpbr_gltf_load_desc* desc, rtpbr_gltf_scene** out, char* err,
                                size_t err_size) {
    ts_write(dir, name, text, strlen(text));
    rtpbr_gltf_load_desc d = {0};
    if (desc) d = *desc;
    d.error_message = err;
    d.error_message_size = err_size;
    char* p = ts_path(dir, name);
    rtpbr_gltf_result r = rtpbr_gltf_load(p, &d, out);
    free(p);
    return r;
}

rtpbr_gltf_scene* ts_load_scene(const char* dir, const char* name, const ts_scene* s,
                                const rtpbr_gltf_load_desc* desc) {
    char* json = ts_scene_json(s);
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, name, json, desc, &scene, err, sizeof err);
    free(json);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s: %s", name, rtpbr_gltf_result_string(r), err);
    return scene;
}
