// Test of suite 'shader-stats': the engine's lighting passes, compiled by Mesa RADV for chips
// this machine does not have (the null device, bench/shader-stats/null_device.h), stay within
// the register budget of issue 14. Compile statistics are deterministic for a given driver,
// so these are exact checks, not timings:
//   - no shipped lighting variant (every engine pipeline named LIGHTING_PREFIX*, and the
//     forward pass's of BLEND surfaces, FORWARD_PREFIX*) spills VGPRs or SGPRs or uses scratch
//     memory, on any chip of FAMILIES;
//   - the default lighting variant uses at most MAX_DEFAULT_VGPRS VGPRs on BUDGET_FAMILY:
//     every pipeline named DEFAULT or DEFAULT_* (is_default), DEFAULT given on the command line
//     from shader_stats_default_lighting in bench/shader-stats/meson.build;
//   - (mode builds) no per-light statistics build of a lighting variant (the manifest's
//     LIGHTING_PREFIX* entries built with -DRTPBR_STATS_FIXED_LIGHTS=N: the light loop over
//     exactly N lights of one shape, unrolled, whose 2-light minus 1-light statistics are
//     bench/shader-stats' per-light costs) spills or uses scratch, on any chip of FAMILIES
//     (issue 32: a per-light figure taken from a build that spills measures the spills).
//
//   test_shader_stats bounds MANIFEST DEFAULT
//       the checks on the engine's shaders; exit 0 when all hold, 1 when any fails
//   test_shader_stats builds MANIFEST
//       the no-spill check on the per-light statistics builds; exit 0 when it holds
//   test_shader_stats control MANIFEST
//       the negative control: the same checks run on the shaders of tests/shader-stats/, and
//       must find exactly the violations those shaders were written to have
//       (lighting_control_spill: spills and scratch on gfx1100, > 96 VGPRs on navi21, and as
//       a per-light build, spills and scratch on gfx1100; lighting_control_small: none), or the
//       check could not be trusted to fail
// Exit 77 (skip) only when RADV's null device is not available here; a Vulkan error or a
// validation message fails.
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "manifest.h"
#include "null_device.h"

#define LIGHTING_PREFIX "lighting"
#define FORWARD_PREFIX "forward"
#define MAX_DEFAULT_VGPRS 96
#define BUDGET_FAMILY "navi21"
static const char *const FAMILIES[] = {"navi21", "gfx1100"};
#define FAMILY_COUNT (sizeof FAMILIES / sizeof *FAMILIES)

#define EXIT_SKIP 77
#define ERROR_SIZE 512

// What the checks found for one pipeline on one chip.
typedef struct finding {
    char *pipeline; // owned
    const char *family;
    double vgprs, spilled_vgprs, spilled_sgprs, scratch;
    bool spills, uses_scratch, over_budget;
} finding;

typedef struct findings {
    uint32_t count;
    finding list[256];
} findings;

// The rule of shader_stats_default_lighting (bench/shader-stats/meson.build).
static bool is_default(const char *name, const char *pattern)
{
    size_t n = strlen(pattern);
    return strncmp(name, pattern, n) == 0 && (name[n] == '\0' || name[n] == '_');
}

static bool is_lighting(const char *name, void *user)
{
    (void)user;
    return strncmp(name, LIGHTING_PREFIX, strlen(LIGHTING_PREFIX)) == 0 ||
           strncmp(name, FORWARD_PREFIX, strlen(FORWARD_PREFIX)) == 0;
}

// The per-light statistics builds of the lighting variants (entries with RTPBR_STATS_FIXED_LIGHTS
// named LIGHTING_PREFIX*), each a compute pipeline named "NAME, N lights". *out malloc'ed.
static bool per_light_builds(const ss_manifest *m, ss_pipeline **out, uint32_t *count)
{
    *count = 0;
    *out = calloc(m->count ? m->count : 1, sizeof **out);
    if (!*out) return false;
    for (uint32_t i = 0; i < m->count; ++i) {
        const ss_entry *e = &m->entries[i];
        if (e->fixed_lights == 0 || strcmp(e->stage, "comp") != 0 ||
            strncmp(e->name, LIGHTING_PREFIX, strlen(LIGHTING_PREFIX)) != 0)
            continue;
        ss_pipeline *p = &(*out)[(*count)++];
        snprintf(p->name, sizeof p->name, "%s, %d light%s", e->name, e->fixed_lights, e->fixed_lights == 1 ? "" : "s");
        p->shader_count = 1;
        p->entries[0] = i;
    }
    return true;
}

// Compiles the manifest's lighting pipelines (per_light: its per-light statistics builds instead)
// on every chip and records what the checks find. Returns 0, EXIT_SKIP or 1 (an error: the
// checks could not be made).
static int run_checks(const char *manifest_path, const char *default_name, bool per_light, findings *out)
{
    char error[ERROR_SIZE];
    ss_manifest m = {0};
    ss_pipeline *pipelines = NULL;
    uint32_t count = 0;
    int status = 0;
    if (!ss_manifest_read(&m, manifest_path, error, sizeof error) || !ss_manifest_load_modules(&m, error, sizeof error) ||
        (!per_light && !ss_manifest_pipelines(&m, is_lighting, NULL, &pipelines, &count, error, sizeof error))) {
        fprintf(stderr, "FAIL: %s\n", error);
        status = 1;
        goto cleanup;
    }
    if (per_light && !per_light_builds(&m, &pipelines, &count)) {
        fprintf(stderr, "FAIL: out of memory\n");
        status = 1;
        goto cleanup;
    }
    bool default_found = per_light; // (the budget is the shipped default variant's)
    for (uint32_t p = 0; p < count; ++p) default_found = default_found || is_default(pipelines[p].name, default_name);
    if (count == 0 || !default_found) {
        fprintf(stderr, "FAIL: %s lists %u %s* %s and %s default variant %s or %s_*\n", manifest_path, count,
                LIGHTING_PREFIX, per_light ? "per-light builds" : "pipelines", default_found ? "the" : "no", default_name,
                default_name);
        status = 1;
        goto cleanup;
    }
    for (size_t f = 0; f < FAMILY_COUNT && status == 0; ++f) {
        ss_device *device = NULL;
        ss_open_result opened = ss_device_create(FAMILIES[f], true, &device, error, sizeof error);
        if (opened != SS_OPEN_OK) {
            fprintf(stderr, "%s: %s\n", opened == SS_OPEN_UNAVAILABLE ? "SKIP" : "FAIL", error);
            status = opened == SS_OPEN_UNAVAILABLE ? EXIT_SKIP : 1;
            break;
        }
        if (!ss_device_validating(device)) printf("note: VK_LAYER_KHRONOS_validation is not installed\n");
        for (uint32_t p = 0; p < count && status == 0; ++p) {
            ss_shader shaders[2];
            for (uint32_t i = 0; i < pipelines[p].shader_count; ++i) {
                const ss_entry *e = &m.entries[pipelines[p].entries[i]];
                shaders[i] = (ss_shader){e->name, e->words, e->word_count};
            }
            ss_pipeline_stats stats;
            if (!ss_device_compile(device, shaders, pipelines[p].shader_count, &stats, error, sizeof error)) {
                fprintf(stderr, "FAIL: %s on %s: %s\n", pipelines[p].name, FAMILIES[f], error);
                status = 1;
                break;
            }
            for (uint32_t e = 0; e < stats.executable_count && status == 0; ++e) {
                const ss_executable *x = &stats.executables[e];
                const ss_statistic needed[] = {SS_STAT_VGPRS, SS_STAT_SPILLED_VGPRS, SS_STAT_SPILLED_SGPRS, SS_STAT_SCRATCH};
                for (size_t k = 0; k < sizeof needed / sizeof *needed; ++k)
                    if (!x->has[needed[k]]) {
                        fprintf(stderr, "FAIL: %s on %s: the driver reports no \"%s\"\n", pipelines[p].name, FAMILIES[f],
                                ss_statistic_driver_names[needed[k]]);
                        status = 1;
                    }
                if (status || out->count == sizeof out->list / sizeof *out->list) {
                    if (!status) fprintf(stderr, "FAIL: too many pipelines\n");
                    status = 1;
                    break;
                }
                char *name = strdup(pipelines[p].name);
                if (!name) {
                    fprintf(stderr, "FAIL: out of memory\n");
                    status = 1;
                    break;
                }
                finding *r = &out->list[out->count++];
                *r = (finding){
                    .pipeline = name,
                    .family = FAMILIES[f],
                    .vgprs = x->value[SS_STAT_VGPRS],
                    .spilled_vgprs = x->value[SS_STAT_SPILLED_VGPRS],
                    .spilled_sgprs = x->value[SS_STAT_SPILLED_SGPRS],
                    .scratch = x->value[SS_STAT_SCRATCH],
                };
                r->spills = r->spilled_vgprs > 0 || r->spilled_sgprs > 0;
                r->uses_scratch = r->scratch > 0;
                r->over_budget = !per_light && is_default(pipelines[p].name, default_name) &&
                                 strcmp(FAMILIES[f], BUDGET_FAMILY) == 0 && r->vgprs > MAX_DEFAULT_VGPRS;
            }
        }
        ss_device_destroy(device);
    }
cleanup:
    free(pipelines);
    ss_manifest_finish(&m);
    return status;
}

static void free_findings(findings *f)
{
    for (uint32_t i = 0; i < f->count; ++i) free(f->list[i].pipeline);
}

static bool violates(const finding *r) { return r->spills || r->uses_scratch || r->over_budget; }

static void print_findings(const findings *f, const char *default_name)
{
    printf("| pipeline | chip | VGPRs | spilled VGPRs | spilled SGPRs | scratch B/wave | verdict |\n"
           "|---|---|---:|---:|---:|---:|---|\n");
    for (uint32_t i = 0; i < f->count; ++i) {
        const finding *r = &f->list[i];
        char verdict[256] = "ok";
        if (violates(r))
            snprintf(verdict, sizeof verdict, "FAIL:%s%s%s", r->spills ? " spills" : "", r->uses_scratch ? " scratch" : "",
                     r->over_budget ? " VGPRs over budget" : "");
        printf("| %s%s | %s | %.0f | %.0f | %.0f | %.0f | %s |\n", r->pipeline,
               is_default(r->pipeline, default_name) ? " (default)" : "", r->family, r->vgprs, r->spilled_vgprs,
               r->spilled_sgprs, r->scratch, verdict);
    }
}

static int bounds(const char *manifest, const char *default_name, bool per_light)
{
    findings *f = calloc(1, sizeof *f);
    if (!f) return 1;
    int status = run_checks(manifest, default_name, per_light, f);
    if (status == 0) {
        print_findings(f, default_name);
        uint32_t failures = 0;
        for (uint32_t i = 0; i < f->count; ++i) {
            const finding *r = &f->list[i];
            if (r->spills)
                printf("FAIL: %s on %s spills (%.0f VGPRs, %.0f SGPRs); bound: none\n", r->pipeline, r->family,
                       r->spilled_vgprs, r->spilled_sgprs);
            if (r->uses_scratch)
                printf("FAIL: %s on %s uses %.0f B of scratch per wave; bound: none\n", r->pipeline, r->family, r->scratch);
            if (r->over_budget)
                printf("FAIL: %s on %s uses %.0f VGPRs; bound: %d\n", r->pipeline, r->family, r->vgprs, MAX_DEFAULT_VGPRS);
            failures += violates(r);
        }
        if (per_light)
            printf("%u of %u per-light statistics builds spill or use scratch (issue 32: none may)\n", failures, f->count);
        else
            printf("%u of %u lighting pipeline compilations break the bounds of issue 14\n", failures, f->count);
        status = failures ? 1 : 0;
    }
    free_findings(f);
    free(f);
    return status;
}

// The negative control: its shaders must be found exactly as they were written, as engine
// pipelines and as per-light statistics builds (the control manifest lists each shader both
// ways: bench/shader-stats/meson.build).
static bool named(const char *pipeline, const char *name, bool per_light)
{
    size_t n = strlen(name);
    return strncmp(pipeline, name, n) == 0 && (per_light ? pipeline[n] == ',' : pipeline[n] == '\0');
}

static int control(const char *manifest)
{
    static const char spill_name[] = "lighting_control_spill", small_name[] = "lighting_control_small";
    int status = 0;
    for (int mode = 0; mode < 2 && status == 0; ++mode) {
        bool per_light = mode == 1;
        findings *f = calloc(1, sizeof *f);
        if (!f) return 1;
        status = run_checks(manifest, spill_name, per_light, f);
        if (status == 0) {
            print_findings(f, spill_name);
            bool spill_gfx1100 = false, scratch_gfx1100 = false, budget_navi21 = false, small_seen = false;
            for (uint32_t i = 0; i < f->count; ++i) {
                const finding *r = &f->list[i];
                if (named(r->pipeline, small_name, per_light)) {
                    small_seen = true;
                    if (violates(r)) {
                        printf("FAIL: %s on %s should pass the checks\n", r->pipeline, r->family);
                        status = 1;
                    }
                } else if (named(r->pipeline, spill_name, per_light)) {
                    bool gfx1100 = strcmp(r->family, "gfx1100") == 0;
                    spill_gfx1100 = spill_gfx1100 || (gfx1100 && r->spills);
                    scratch_gfx1100 = scratch_gfx1100 || (gfx1100 && r->uses_scratch);
                    budget_navi21 = budget_navi21 || r->over_budget;
                }
            }
            // (the VGPR budget is the shipped default variant's: not a per-light build's)
            if (!spill_gfx1100 || !scratch_gfx1100 || budget_navi21 == per_light || !small_seen) {
                printf("FAIL: the %s checks missed a violation the control shaders have, or found one they do not "
                       "(spills on gfx1100: %s, scratch on gfx1100: %s, VGPRs over budget on navi21: %s, small "
                       "control compiled: %s)\n",
                       per_light ? "per-light builds'" : "pipelines'", spill_gfx1100 ? "found" : "missed",
                       scratch_gfx1100 ? "found" : "missed", budget_navi21 ? "found" : "not found",
                       small_seen ? "yes" : "no");
                status = 1;
            } else {
                printf("the %s checks found every violation of the control shaders and none in the small one\n",
                       per_light ? "per-light builds'" : "pipelines'");
            }
        }
        free_findings(f);
        free(f);
    }
    return status;
}

int main(int argc, char **argv)
{
    if (argc == 4 && strcmp(argv[1], "bounds") == 0) return bounds(argv[2], argv[3], false);
    if (argc == 3 && strcmp(argv[1], "builds") == 0) return bounds(argv[2], "", true);
    if (argc == 3 && strcmp(argv[1], "control") == 0) return control(argv[2]);
    fprintf(stderr, "usage: test_shader_stats bounds MANIFEST DEFAULT | builds MANIFEST | control MANIFEST\n");
    return 2;
}
