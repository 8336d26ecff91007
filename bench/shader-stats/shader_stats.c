// rtpbr-shader-stats: compiles every pipeline of a manifest (or of SPIR-V files) on Mesa
// RADV's null device for each chip family asked for and prints the driver's compile
// statistics as Markdown tables (or JSON): one table of the engine pipelines per chip, then
// the per-light cost of the light loops (the build with two lights minus the build with one;
// bench/README.md, "Shader statistics"). Needs no GPU; without RADV it says so and exits 0.
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "manifest.h"
#include "null_device.h"

#define MAX_FAMILIES 8
#define ERROR_SIZE 512

static const char *const default_families[] = {"navi21", "gfx1100"};

// The statistics the per-light table differences.
static const ss_statistic per_light_stats[] = {SS_STAT_INSTRUCTIONS, SS_STAT_LATENCY, SS_STAT_THROUGHPUT,
                                               SS_STAT_CODE_SIZE};

typedef struct compiled {
    bool ok;
    char error[ERROR_SIZE];
    ss_pipeline_stats stats;
} compiled;

typedef struct family_result {
    const char *family;
    bool available;
    char message[2 * ERROR_SIZE]; // why not available
    char device[256];
    char driver[256];
    bool validating;
    compiled *pipelines; // one per pipeline
    compiled *ones;      // one per light pair: the 1-light build
    compiled *twos;      // and the 2-light build
} family_result;

typedef struct options {
    const char *families[MAX_FAMILIES];
    int family_count;
    const char *baseline;
    bool json;
    bool validation;
    const char **files; // manifests and .spv files, in order
    int file_count;
} options;

static void usage(FILE *to)
{
    fprintf(to,
            "usage: rtpbr-shader-stats [--family NAME]... [--baseline NAME] [--json] [--no-validation]\n"
            "                          MANIFEST | FILE.spv...\n"
            "  Compiles each pipeline on Mesa RADV's null device (no GPU needed) and prints the\n"
            "  driver's statistics. MANIFEST: lines 'name<TAB>stage<TAB>path<TAB>defines' (manifest.h).\n"
            "  --family NAME   RADV_FORCE_FAMILY chip, repeatable (default: navi21 and gfx1100)\n"
            "  --baseline NAME per-light pair to compare the others with (its latency = 1x)\n"
            "  --json          JSON instead of Markdown\n"
            "  --no-validation do not enable VK_LAYER_KHRONOS_validation\n"
            "  -h, --help      this text\n");
}

static const ss_executable *first_executable(const compiled *c)
{
    return c->ok && c->stats.executable_count > 0 ? &c->stats.executables[0] : NULL;
}

static double stat_or_nan(const ss_executable *x, ss_statistic s) { return x && x->has[s] ? x->value[s] : NAN; }

// A 2-light build barely longer than the 1-light build kept its light loop a loop: then ACO
// weights the body as a loop (x8) in both and the differences are not per-light costs.
#define MIN_PER_LIGHT_GROWTH 0.05

static bool looks_unrolled(const ss_executable *one, const ss_executable *two)
{
    double i1 = stat_or_nan(one, SS_STAT_INSTRUCTIONS), i2 = stat_or_nan(two, SS_STAT_INSTRUCTIONS);
    return i2 - i1 >= MIN_PER_LIGHT_GROWTH * i1;
}

// Why a per-light pair is not measured (NULL: it is): see ss_light_pair.
static const char *pair_skip_reason(const ss_manifest *m, const ss_light_pair *pairs, uint32_t p, char *buf, size_t size)
{
    if (pairs[p].ignores_fixed_lights) {
        snprintf(buf, size, "its 1- and 2-light builds are the same SPIR-V: the shader ignores %sN",
                 SS_FIXED_LIGHTS_DEFINE);
        return buf;
    }
    if (pairs[p].same_as != UINT32_MAX) {
        snprintf(buf, size, "same SPIR-V as %s (a define the shader ignores)", m->entries[pairs[pairs[p].same_as].one].name);
        return buf;
    }
    return NULL;
}

static void compile_pipeline(ss_device *device, const ss_manifest *m, const uint32_t *entries, uint32_t count,
                             compiled *out)
{
    ss_shader shaders[2];
    for (uint32_t i = 0; i < count; ++i) {
        const ss_entry *e = &m->entries[entries[i]];
        shaders[i] = (ss_shader){e->name, e->words, e->word_count};
    }
    out->ok = ss_device_compile(device, shaders, count, &out->stats, out->error, sizeof out->error);
    if (!out->ok) fprintf(stderr, "rtpbr-shader-stats: %s\n", out->error);
}

// ---- Markdown -----------------------------------------------------------------------------

static void print_value(double v)
{
    if (isnan(v)) printf(" – |");
    else printf(" %.0f |", v);
}

static void print_markdown(const options *opt, const family_result *results, const ss_manifest *m,
                           const ss_pipeline *pipelines, uint32_t pipeline_count, const ss_light_pair *pairs,
                           uint32_t pair_count)
{
    for (int f = 0; f < opt->family_count; ++f) {
        const family_result *r = &results[f];
        if (!r->available) {
            printf("## %s\n\n%s\n\n", r->family, r->message);
            continue;
        }
        printf("## %s: %s, %s%s\n\n", r->family, r->device, r->driver, r->validating ? ", validation on" : "");
        printf("| pipeline | executable | wave |");
        for (int s = 0; s < SS_STAT_COUNT; ++s) printf(" %s |", ss_statistic_columns[s]);
        printf("\n|---|---|---|");
        for (int s = 0; s < SS_STAT_COUNT; ++s) printf("---:|");
        printf("\n");
        for (uint32_t p = 0; p < pipeline_count; ++p) {
            const compiled *c = &r->pipelines[p];
            if (!c->ok) {
                printf("| %s | error: %s |\n", pipelines[p].name, c->error);
                continue;
            }
            for (uint32_t e = 0; e < c->stats.executable_count; ++e) {
                const ss_executable *x = &c->stats.executables[e];
                printf("| %s | %s | %u |", pipelines[p].name, x->name, x->subgroup_size);
                for (int s = 0; s < SS_STAT_COUNT; ++s) print_value(stat_or_nan(x, (ss_statistic)s));
                printf("\n");
            }
        }
        printf("\n");
    }
    if (pair_count == 0) return;
    printf("## Per light (build with 2 lights minus build with 1: -D%s1 / 2)\n\n", &SS_FIXED_LIGHTS_DEFINE[2]);
    printf("| light loop | chip |");
    for (size_t s = 0; s < sizeof per_light_stats / sizeof *per_light_stats; ++s)
        printf(" %s |", ss_statistic_columns[per_light_stats[s]]);
    printf(" VGPRs (1 → 2 lights) | spilled VGPRs (2 lights) | scratch B/wave (2 lights) |%s\n",
           opt->baseline ? " latency / baseline's |" : "");
    printf("|---|---|");
    for (size_t s = 0; s < sizeof per_light_stats / sizeof *per_light_stats; ++s) printf("---:|");
    printf("---:|---:|---:|%s\n", opt->baseline ? "---:|" : "");
    for (uint32_t p = 0; p < pair_count; ++p) {
        const char *name = m->entries[pairs[p].one].name;
        char reason[256];
        if (pair_skip_reason(m, pairs, p, reason, sizeof reason)) continue;
        for (int f = 0; f < opt->family_count; ++f) {
            const family_result *r = &results[f];
            if (!r->available) continue;
            const ss_executable *one = first_executable(&r->ones[p]), *two = first_executable(&r->twos[p]);
            if (!one || !two) {
                printf("| %s | %s | error: %s |\n", name, r->family, r->ones[p].ok ? r->twos[p].error : r->ones[p].error);
                continue;
            }
            printf("| %s | %s |", name, r->family);
            for (size_t s = 0; s < sizeof per_light_stats / sizeof *per_light_stats; ++s)
                print_value(stat_or_nan(two, per_light_stats[s]) - stat_or_nan(one, per_light_stats[s]));
            printf(" %.0f → %.0f |", stat_or_nan(one, SS_STAT_VGPRS), stat_or_nan(two, SS_STAT_VGPRS));
            print_value(stat_or_nan(two, SS_STAT_SPILLED_VGPRS));
            print_value(stat_or_nan(two, SS_STAT_SCRATCH));
            if (opt->baseline) {
                double ratio = NAN;
                for (uint32_t b = 0; b < pair_count; ++b) {
                    const ss_executable *b1 = first_executable(&r->ones[b]), *b2 = first_executable(&r->twos[b]);
                    if (strcmp(m->entries[pairs[b].one].name, opt->baseline) != 0 || !b1 || !b2) continue;
                    ratio = (stat_or_nan(two, SS_STAT_LATENCY) - stat_or_nan(one, SS_STAT_LATENCY)) /
                            (stat_or_nan(b2, SS_STAT_LATENCY) - stat_or_nan(b1, SS_STAT_LATENCY));
                }
                if (isnan(ratio)) printf(" – |");
                else printf(" %.2f× |", ratio);
            }
            printf("\n");
        }
    }
    printf("\n");
    for (uint32_t p = 0; p < pair_count; ++p) {
        char reason[256];
        if (pair_skip_reason(m, pairs, p, reason, sizeof reason))
            printf("Not measured: %s: %s.\n\n", m->entries[pairs[p].one].name, reason);
    }
    for (uint32_t p = 0; p < pair_count; ++p)
        for (int f = 0; f < opt->family_count; ++f) {
            const ss_executable *one = first_executable(&results[f].ones[p]), *two = first_executable(&results[f].twos[p]);
            if (results[f].available && one && two && !looks_unrolled(one, two))
                printf("**Not a per-light cost:** %s on %s: the 2-light build has only %.0f more instructions than the "
                       "1-light build, so its light loop is still a loop (ACO weights loop bodies x8); the N-light "
                       "build must hold N copies of the body.\n\n",
                       m->entries[pairs[p].one].name, results[f].family,
                       stat_or_nan(two, SS_STAT_INSTRUCTIONS) - stat_or_nan(one, SS_STAT_INSTRUCTIONS));
        }
}

// ---- JSON ---------------------------------------------------------------------------------

static void json_string(const char *s)
{
    putchar('"');
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') printf("\\%c", c);
        else if (c < 0x20) printf("\\u%04x", c);
        else putchar(c);
    }
    putchar('"');
}

static void json_number(double v)
{
    if (isnan(v)) printf("null");
    else printf("%.0f", v);
}

static void json_executables(const compiled *c)
{
    if (!c->ok) {
        printf("\"error\": ");
        json_string(c->error);
        return;
    }
    printf("\"executables\": [");
    for (uint32_t e = 0; e < c->stats.executable_count; ++e) {
        const ss_executable *x = &c->stats.executables[e];
        printf("%s{\"name\": ", e ? ", " : "");
        json_string(x->name);
        printf(", \"subgroup_size\": %u", x->subgroup_size);
        for (int s = 0; s < SS_STAT_COUNT; ++s) {
            printf(", \"%s\": ", ss_statistic_keys[s]);
            json_number(stat_or_nan(x, (ss_statistic)s));
        }
        printf("}");
    }
    printf("]");
}

static void print_json(const options *opt, const family_result *results, const ss_manifest *m,
                       const ss_pipeline *pipelines, uint32_t pipeline_count, const ss_light_pair *pairs,
                       uint32_t pair_count)
{
    printf("{\"families\": [");
    for (int f = 0; f < opt->family_count; ++f) {
        const family_result *r = &results[f];
        printf("%s\n {\"family\": ", f ? "," : "");
        json_string(r->family);
        printf(", \"available\": %s", r->available ? "true" : "false");
        if (!r->available) {
            printf(", \"message\": ");
            json_string(r->message);
            printf("}");
            continue;
        }
        printf(", \"device\": ");
        json_string(r->device);
        printf(", \"driver\": ");
        json_string(r->driver);
        printf(", \"validation\": %s,\n  \"pipelines\": [", r->validating ? "true" : "false");
        for (uint32_t p = 0; p < pipeline_count; ++p) {
            printf("%s\n   {\"name\": ", p ? "," : "");
            json_string(pipelines[p].name);
            printf(", ");
            json_executables(&r->pipelines[p]);
            printf("}");
        }
        printf("],\n  \"per_light\": [");
        for (uint32_t p = 0; p < pair_count; ++p) {
            printf("%s\n   {\"name\": ", p ? "," : "");
            json_string(m->entries[pairs[p].one].name);
            char reason[256];
            if (pair_skip_reason(m, pairs, p, reason, sizeof reason)) {
                printf(", \"not_measured\": ");
                json_string(reason);
                printf("}");
                continue;
            }
            printf(", \"one_light\": {");
            json_executables(&r->ones[p]);
            printf("}, \"two_lights\": {");
            json_executables(&r->twos[p]);
            printf("}");
            const ss_executable *one = first_executable(&r->ones[p]), *two = first_executable(&r->twos[p]);
            if (one && two) printf(", \"unrolled\": %s", looks_unrolled(one, two) ? "true" : "false");
            for (size_t s = 0; one && two && s < sizeof per_light_stats / sizeof *per_light_stats; ++s) {
                printf(", \"%s_per_light\": ", ss_statistic_keys[per_light_stats[s]]);
                json_number(stat_or_nan(two, per_light_stats[s]) - stat_or_nan(one, per_light_stats[s]));
            }
            printf("}");
        }
        printf("]}");
    }
    printf("]}\n");
}

// ---- main ---------------------------------------------------------------------------------

// Options may come before or after the files; "--" ends the options.
static int parse_options(int argc, char **argv, const char **files, options *opt)
{
    *opt = (options){.validation = true, .files = files};
    bool options_done = false;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        if (!options_done && (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0)) {
            usage(stdout);
            return -1;
        } else if (options_done || strncmp(arg, "--", 2) != 0) {
            opt->files[opt->file_count++] = arg;
        } else if (strcmp(arg, "--") == 0) {
            options_done = true;
        } else if (strcmp(arg, "--json") == 0) {
            opt->json = true;
        } else if (strcmp(arg, "--no-validation") == 0) {
            opt->validation = false;
        } else if (strcmp(arg, "--family") == 0 && i + 1 < argc) {
            if (opt->family_count == MAX_FAMILIES) {
                fprintf(stderr, "rtpbr-shader-stats: at most %d families\n", MAX_FAMILIES);
                return 2;
            }
            opt->families[opt->family_count++] = argv[++i];
        } else if (strcmp(arg, "--baseline") == 0 && i + 1 < argc) {
            opt->baseline = argv[++i];
        } else {
            fprintf(stderr, "rtpbr-shader-stats: unknown option or missing value: %s\n", arg);
            usage(stderr);
            return 2;
        }
    }
    if (opt->file_count == 0) {
        usage(stderr);
        return 2;
    }
    if (opt->family_count == 0)
        for (size_t f = 0; f < sizeof default_families / sizeof *default_families; ++f)
            opt->families[opt->family_count++] = default_families[f];
    return 0;
}

static bool is_spirv_path(const char *path)
{
    size_t len = strlen(path);
    return len > 4 && strcmp(path + len - 4, ".spv") == 0;
}

int main(int argc, char **argv)
{
    options opt;
    const char **files = calloc((size_t)argc, sizeof *files);
    if (!files) return 1;
    int status = parse_options(argc, argv, files, &opt);
    if (status) {
        free(files);
        return status < 0 ? 0 : status; // -1: -h, --help
    }

    char error[ERROR_SIZE];
    ss_manifest m = {0};
    ss_pipeline *pipelines = NULL;
    ss_light_pair *pairs = NULL;
    uint32_t pipeline_count = 0, pair_count = 0;
    family_result results[MAX_FAMILIES] = {{0}};
    bool ok = true;
    for (int i = 0; ok && i < opt.file_count; ++i)
        ok = is_spirv_path(opt.files[i]) ? ss_manifest_add_spirv(&m, opt.files[i], error, sizeof error)
                                         : ss_manifest_read(&m, opt.files[i], error, sizeof error);
    ok = ok && ss_manifest_load_modules(&m, error, sizeof error) &&
         ss_manifest_pipelines(&m, NULL, NULL, &pipelines, &pipeline_count, error, sizeof error) &&
         ss_manifest_pairs(&m, &pairs, &pair_count, error, sizeof error);
    if (ok && opt.baseline) {
        bool found = false;
        for (uint32_t p = 0; p < pair_count; ++p) found = found || strcmp(m.entries[pairs[p].one].name, opt.baseline) == 0;
        if (!found) {
            snprintf(error, sizeof error, "--baseline %s: no per-light pair of that name", opt.baseline);
            ok = false;
        }
    }
    if (!ok) {
        fprintf(stderr, "rtpbr-shader-stats: %s\n", error);
        status = 2;
        goto cleanup;
    }

    bool any_available = false;
    for (int f = 0; f < opt.family_count; ++f) {
        family_result *r = &results[f];
        r->family = opt.families[f];
        r->pipelines = calloc(pipeline_count ? pipeline_count : 1, sizeof *r->pipelines);
        r->ones = calloc(pair_count ? pair_count : 1, sizeof *r->ones);
        r->twos = calloc(pair_count ? pair_count : 1, sizeof *r->twos);
        if (!r->pipelines || !r->ones || !r->twos) {
            fprintf(stderr, "rtpbr-shader-stats: out of memory\n");
            status = 1;
            goto cleanup;
        }
        ss_device *device = NULL;
        ss_open_result opened = ss_device_create(r->family, opt.validation, &device, error, sizeof error);
        if (opened != SS_OPEN_OK) {
            snprintf(r->message, sizeof r->message, "RADV null device for %s not available: %s", r->family, error);
            fprintf(stderr, "rtpbr-shader-stats: %s\n", r->message);
            if (opened == SS_OPEN_FAILED) status = 1;
            continue;
        }
        any_available = true;
        r->available = true;
        snprintf(r->device, sizeof r->device, "%s", ss_device_name(device));
        snprintf(r->driver, sizeof r->driver, "%s", ss_device_driver_info(device));
        r->validating = ss_device_validating(device);
        fprintf(stderr, "rtpbr-shader-stats: %s: %u pipelines, %u per-light pairs on %s\n", r->family, pipeline_count,
                pair_count, r->device);
        for (uint32_t p = 0; p < pipeline_count; ++p) {
            compile_pipeline(device, &m, pipelines[p].entries, pipelines[p].shader_count, &r->pipelines[p]);
            if (!r->pipelines[p].ok) status = 1;
        }
        for (uint32_t p = 0; p < pair_count; ++p) {
            char reason[256];
            if (pair_skip_reason(&m, pairs, p, reason, sizeof reason)) continue;
            compile_pipeline(device, &m, &pairs[p].one, 1, &r->ones[p]);
            compile_pipeline(device, &m, &pairs[p].two, 1, &r->twos[p]);
            if (!r->ones[p].ok || !r->twos[p].ok) status = 1;
        }
        ss_device_destroy(device);
    }
    if (!any_available)
        fprintf(stderr, "rtpbr-shader-stats: no RADV null device available; nothing measured "
                        "(needs Mesa's RADV, package mesa-vulkan-drivers)\n");
    if (opt.json) print_json(&opt, results, &m, pipelines, pipeline_count, pairs, pair_count);
    else print_markdown(&opt, results, &m, pipelines, pipeline_count, pairs, pair_count);

cleanup:
    for (int f = 0; f < MAX_FAMILIES; ++f) {
        free(results[f].pipelines);
        free(results[f].ones);
        free(results[f].twos);
    }
    free(pipelines);
    free(pairs);
    ss_manifest_finish(&m);
    free(files);
    return status;
}
