// The manifest of rtpbr-shader-stats (format: manifest.h).
#define _POSIX_C_SOURCE 200809L

#include "manifest.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spirv_reflect.h"

#define MAX_SPIRV_BYTES (64u * 1024u * 1024u)

static bool fail(char *error, size_t error_size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error, error_size, format, args);
    va_end(args);
    return false;
}

static const char *stage_name(VkShaderStageFlagBits stage)
{
    switch (stage) {
    case VK_SHADER_STAGE_VERTEX_BIT: return "vert";
    case VK_SHADER_STAGE_FRAGMENT_BIT: return "frag";
    case VK_SHADER_STAGE_COMPUTE_BIT: return "comp";
    default: return "other";
    }
}

static bool valid_stage(const char *stage)
{
    return strcmp(stage, "vert") == 0 || strcmp(stage, "frag") == 0 || strcmp(stage, "comp") == 0;
}

static int fixed_lights_of(const char *defines)
{
    const char *d = strstr(defines, SS_FIXED_LIGHTS_DEFINE);
    if (!d) return 0;
    char *end;
    long n = strtol(d + strlen(SS_FIXED_LIGHTS_DEFINE), &end, 10);
    return n >= 1 && n < 1000 && (*end == '\0' || *end == ' ') ? (int)n : -1;
}

static bool append(ss_manifest *m, const char *name, const char *stage, const char *path, const char *defines,
                   char *error, size_t error_size)
{
    ss_entry *grown = realloc(m->entries, (m->count + 1) * sizeof *grown);
    if (!grown) return fail(error, error_size, "out of memory");
    m->entries = grown;
    ss_entry *e = &m->entries[m->count];
    *e = (ss_entry){.name = strdup(name), .stage = strdup(stage), .path = strdup(path), .defines = strdup(defines)};
    m->count++; // from here on ss_manifest_finish frees it, complete or not
    if (!e->name || !e->stage || !e->path || !e->defines) return fail(error, error_size, "out of memory");
    e->fixed_lights = fixed_lights_of(defines);
    if (e->fixed_lights < 0) return fail(error, error_size, "%s: bad %sN define", name, SS_FIXED_LIGHTS_DEFINE);
    return true;
}

bool ss_manifest_read(ss_manifest *m, const char *path, char *error, size_t error_size)
{
    FILE *f = fopen(path, "r");
    if (!f) return fail(error, error_size, "cannot open manifest %s: %s", path, strerror(errno));
    char *line = NULL;
    size_t capacity = 0;
    unsigned number = 0;
    bool ok = true;
    while (ok && getline(&line, &capacity, f) >= 0) {
        ++number;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '\0' || line[0] == '#') continue;
        char *fields[4] = {line, NULL, NULL, NULL};
        int n = 1;
        for (char *p = line; *p && n < 4; ++p)
            if (*p == '\t') {
                *p = '\0';
                fields[n++] = p + 1;
            }
        if (n != 4 || strchr(fields[3], '\t') || !fields[0][0] || !fields[2][0])
            ok = fail(error, error_size, "%s:%u: expected name, stage, path and defines separated by tabs", path, number);
        else if (!valid_stage(fields[1]))
            ok = fail(error, error_size, "%s:%u: stage \"%s\" is not vert, frag or comp", path, number, fields[1]);
        else
            ok = append(m, fields[0], fields[1], fields[2], fields[3], error, error_size);
    }
    if (ok && ferror(f)) ok = fail(error, error_size, "error reading %s", path);
    free(line);
    fclose(f);
    return ok;
}

static bool load_words(const char *path, uint32_t **words, size_t *word_count, char *error, size_t error_size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return fail(error, error_size, "cannot open %s: %s", path, strerror(errno));
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    bool ok = size > 0 && size % 4 == 0 && (unsigned long)size <= MAX_SPIRV_BYTES && fseek(f, 0, SEEK_SET) == 0;
    uint32_t *data = ok ? malloc((size_t)size) : NULL;
    ok = data && fread(data, 1, (size_t)size, f) == (size_t)size;
    fclose(f);
    if (!ok) {
        free(data);
        return fail(error, error_size, "%s: not a readable SPIR-V file (size %ld bytes)", path, size);
    }
    *words = data;
    *word_count = (size_t)size / 4;
    return true;
}

static bool load_entry(ss_entry *e, char *error, size_t error_size)
{
    if (e->words) return true;
    if (!load_words(e->path, &e->words, &e->word_count, error, error_size)) return false;
    ss_reflection refl;
    char why[256];
    if (!ss_reflect(e->words, e->word_count, &refl, why, sizeof why))
        return fail(error, error_size, "%s (%s): %s", e->name, e->path, why);
    const char *stage = stage_name(refl.stage);
    if (strcmp(e->stage, stage) != 0) {
        if (e->stage[0] != '\0') return fail(error, error_size, "%s: listed as %s, module is %s", e->name, e->stage, stage);
        free(e->stage);
        if (!(e->stage = strdup(stage))) return fail(error, error_size, "out of memory");
    }
    return true;
}

bool ss_manifest_add_spirv(ss_manifest *m, const char *path, char *error, size_t error_size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t len = strlen(base);
    if (len > 4 && strcmp(base + len - 4, ".spv") == 0) len -= 4;
    char name[128];
    snprintf(name, sizeof name, "%.*s", (int)(len < sizeof name ? len : sizeof name - 1), base);
    if (!append(m, name, "", path, "", error, error_size)) return false;
    return load_entry(&m->entries[m->count - 1], error, error_size);
}

bool ss_manifest_load_modules(ss_manifest *m, char *error, size_t error_size)
{
    for (uint32_t i = 0; i < m->count; ++i)
        if (!load_entry(&m->entries[i], error, error_size)) return false;
    return true;
}

void ss_manifest_finish(ss_manifest *m)
{
    for (uint32_t i = 0; i < m->count; ++i) {
        ss_entry *e = &m->entries[i];
        free(e->name);
        free(e->stage);
        free(e->path);
        free(e->defines);
        free(e->words);
    }
    free(m->entries);
    *m = (ss_manifest){0};
}

// The pipeline name of a graphics entry: its name without the stage suffix.
static void graphics_base(const ss_entry *e, char *base, size_t size)
{
    size_t len = strlen(e->name);
    const char *suffix = strcmp(e->stage, "vert") == 0 ? "_vert" : "_frag";
    if (len > 5 && strcmp(e->name + len - 5, suffix) == 0) len -= 5;
    snprintf(base, size, "%.*s", (int)(len < size ? len : size - 1), e->name);
}

bool ss_manifest_pipelines(const ss_manifest *m, bool (*keep)(const char *name, void *user), void *user,
                           ss_pipeline **out, uint32_t *count, char *error, size_t error_size)
{
    *out = NULL;
    *count = 0;
    ss_pipeline *list = calloc(m->count ? m->count : 1, sizeof *list);
    if (!list) return fail(error, error_size, "out of memory");
    uint32_t n = 0;
    for (uint32_t i = 0; i < m->count; ++i) {
        const ss_entry *e = &m->entries[i];
        if (e->fixed_lights || (keep && !keep(e->name, user))) continue;
        if (strcmp(e->stage, "comp") == 0) {
            ss_pipeline *p = &list[n++];
            snprintf(p->name, sizeof p->name, "%s", e->name);
            p->shader_count = 1;
            p->entries[0] = i;
            continue;
        }
        if (strcmp(e->stage, "frag") == 0) continue; // joined to its vertex shader below
        ss_pipeline *p = &list[n];
        graphics_base(e, p->name, sizeof p->name);
        for (uint32_t j = 0; j < m->count && p->shader_count == 0; ++j) {
            const ss_entry *f = &m->entries[j];
            char base[128];
            if (f->fixed_lights || strcmp(f->stage, "frag") != 0) continue;
            graphics_base(f, base, sizeof base);
            if (strcmp(base, p->name) != 0) continue;
            p->shader_count = 2;
            p->entries[0] = i;
            p->entries[1] = j;
        }
        if (p->shader_count == 0) {
            fail(error, error_size, "vertex shader %s has no fragment shader %s_frag", e->name, p->name);
            free(list);
            return false;
        }
        ++n;
    }
    // A fragment shader nobody joined is an error too (a pipeline would be missing).
    for (uint32_t j = 0; j < m->count; ++j) {
        const ss_entry *f = &m->entries[j];
        if (f->fixed_lights || strcmp(f->stage, "frag") != 0 || (keep && !keep(f->name, user))) continue;
        bool joined = false;
        for (uint32_t k = 0; k < n && !joined; ++k) joined = list[k].shader_count == 2 && list[k].entries[1] == j;
        if (!joined) {
            free(list);
            return fail(error, error_size, "fragment shader %s has no vertex shader", f->name);
        }
    }
    *out = list;
    *count = n;
    return true;
}

static bool same_module(const ss_entry *a, const ss_entry *b)
{
    return a->words && b->words && a->word_count == b->word_count &&
           memcmp(a->words, b->words, a->word_count * sizeof *a->words) == 0;
}

bool ss_manifest_pairs(const ss_manifest *m, ss_light_pair **out, uint32_t *count, char *error, size_t error_size)
{
    *out = NULL;
    *count = 0;
    ss_light_pair *list = calloc(m->count ? m->count : 1, sizeof *list);
    if (!list) return fail(error, error_size, "out of memory");
    uint32_t n = 0;
    for (uint32_t i = 0; i < m->count; ++i) {
        const ss_entry *e = &m->entries[i];
        if (e->fixed_lights == 0) continue;
        if (strcmp(e->stage, "comp") != 0) {
            free(list);
            return fail(error, error_size, "per-light build %s is not a compute shader", e->name);
        }
        if (e->fixed_lights != 1) continue;
        uint32_t partner = UINT32_MAX;
        for (uint32_t j = 0; j < m->count; ++j)
            if (m->entries[j].fixed_lights == 2 && strcmp(m->entries[j].name, e->name) == 0) partner = j;
        if (partner == UINT32_MAX) {
            free(list);
            return fail(error, error_size, "per-light build %s with 1 light has no 2-light partner", e->name);
        }
        list[n++] = (ss_light_pair){.one = i, .two = partner};
    }
    // A define that changes nothing would make a per-light cost of 0 or a duplicate row.
    for (uint32_t p = 0; p < n; ++p) {
        list[p].ignores_fixed_lights = same_module(&m->entries[list[p].one], &m->entries[list[p].two]);
        list[p].same_as = UINT32_MAX;
        for (uint32_t q = 0; q < p && list[p].same_as == UINT32_MAX; ++q)
            if (same_module(&m->entries[list[p].one], &m->entries[list[q].one])) list[p].same_as = q;
    }
    *out = list;
    *count = n;
    return true;
}
