/* Scene loader: the glTF → rtpbr material mapping (docs/materials.md),
 * decoded textures, generated tangents. Expected values are computed by hand
 * from the JSON in each test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include "test_main.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_scene_util.h"

#define EPS 1e-6

static void near(double got, double want, const char* what) {
    if (!(fabs(got - want) <= EPS * fmax(1.0, fabs(want))))
        fail_msg("%s: got %.9g, expected %.9g", what, got, want);
}

static const float kQuad[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}; /* z = 0, CCW about +Z */
static const uint32_t kQuadIdx[] = {0, 1, 2, 0, 2, 3};
static const float kQuadUv[] = {0, 0, 1, 0, 1, 1, 0, 1};           /* u = x, v = y */

static rtpbr_gltf_scene* load_materials(const char* name, const char* materials, const char* extra) {
    const char* dir = ts_dir(name);
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6,
                  .texcoords = kQuadUv, .material = 0, .materials = materials, .extra = extra};
    rtpbr_gltf_scene* scene = ts_load_scene(dir, "m.gltf", &s, NULL);
    return scene;
}

static void test_khr_extensions(void** state) {
    (void)state;
    rtpbr_gltf_scene* scene = load_materials(
        "khr",
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.6,0.4,1],\"metallicFactor\":0.3,"
        "\"roughnessFactor\":0.7},\"emissiveFactor\":[0.1,0.2,0.3],\"doubleSided\":true,"
        "\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3,\"extensions\":{"
        "\"KHR_materials_emissive_strength\":{\"emissiveStrength\":5},"
        "\"KHR_materials_ior\":{\"ior\":1.8},"
        "\"KHR_materials_specular\":{\"specularFactor\":0.5,\"specularColorFactor\":[0.9,0.8,0.7]},"
        "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":0.6,\"clearcoatRoughnessFactor\":0.2},"
        "\"KHR_materials_sheen\":{\"sheenColorFactor\":[0.2,0.5,0.4],\"sheenRoughnessFactor\":0.3},"
        "\"KHR_materials_anisotropy\":{\"anisotropyStrength\":0.4,\"anisotropyRotation\":1.2}}}",
        NULL);
    const rtpbr_gltf_material* m = &scene->materials[0];
    assert_false(m->has_disney);
    near(m->base_color[0], 0.8f, "base r");
    near(m->base_color[1], 0.6f, "base g");
    near(m->base_color[2], 0.4f, "base b");
    near(m->base_color[3], 1.0, "base a");
    near(m->metallic, 0.3f, "metallic");
    near(m->roughness, 0.7f, "roughness");
    /* emission = emissiveFactor × strength */
    near(m->emission[0], 0.1f * 5.0f, "emission r");
    near(m->emission[1], 0.2f * 5.0f, "emission g");
    near(m->emission[2], 0.3f * 5.0f, "emission b");
    /* Each extension as the file stores it, in its own struct with its has_ flag. */
    assert_true(m->has_emissive_strength && m->has_ior && m->has_specular && m->has_clearcoat &&
                m->has_sheen && m->has_anisotropy);
    near(m->emissive_strength.emissive_strength, 5.0, "strength");
    near(m->ior.ior, 1.8f, "ior");
    near(m->specular.specular_factor, 0.5, "specularFactor");
    near(m->specular.specular_color_factor[0], 0.9f, "specular color r");
    near(m->specular.specular_color_factor[2], 0.7f, "specular color b");
    near(m->clearcoat.clearcoat_factor, 0.6f, "clearcoat");
    near(m->clearcoat.clearcoat_roughness_factor, 0.2f, "clearcoatRoughnessFactor as stored");
    near(m->sheen.sheen_color_factor[0], 0.2f, "sheen color r");
    near(m->sheen.sheen_color_factor[1], 0.5f, "sheen color g");
    near(m->sheen.sheen_roughness_factor, 0.3f, "sheen roughness");
    near(m->anisotropy.anisotropy_strength, 0.4f, "anisotropy strength");
    near(m->anisotropy.anisotropy_rotation, 1.2f, "anisotropy rotation");
    assert_true(m->double_sided);
    assert_int_equal(m->alpha_mode, RTPBR_GLTF_ALPHA_MASK);
    near(m->alpha_cutoff, 0.3f, "alpha cutoff");
    assert_int_equal(m->base_color_texture, -1);
    assert_int_equal(m->gltf_material, 0);
    /* Emissive quad → one light with that radiance, two-sided. */
    assert_int_equal(scene->light_count, 1);
    near(scene->lights[0].radiance[2], 0.3f * 5.0f, "light radiance");
    assert_true(scene->lights[0].two_sided);
    rtpbr_gltf_destroy(scene);
}

static void test_defaults_and_disney_extras(void** state) {
    (void)state;
    rtpbr_gltf_scene* scene = load_materials(
        "disney",
        "{},"
        "{\"extras\":{\"rtpbr_disney\":{\"baseColor\":[0.1,0.2,0.3],\"metallic\":0.1,\"roughness\":0.4,"
        "\"subsurface\":0.25,\"specular\":0.3,\"specularTint\":0.5,\"anisotropic\":0.6,\"sheen\":0.2,"
        "\"sheenTint\":0.75,\"clearcoat\":0.35,\"clearcoatGloss\":0.9}}},"
        "{\"extras\":{\"rtpbr_disney\":{\"ior\":2.0}}}",
        NULL);
    assert_int_equal(scene->material_count, 3);
    /* glTF defaults (spec §5.19): white, metallic = roughness = 1, ior 1.5 */
    const rtpbr_gltf_material* d = &scene->materials[0];
    assert_false(d->has_disney || d->has_ior || d->has_specular || d->has_clearcoat || d->has_sheen ||
                 d->has_anisotropy || d->has_emissive_strength);
    for (int k = 0; k < 4; ++k) near(d->base_color[k], 1.0, "default base colour");
    near(d->metallic, 1.0, "default metallic");
    near(d->roughness, 1.0, "default roughness");
    /* Absent extensions hold their defaults. */
    near(d->ior.ior, 1.5, "default ior");
    near(d->specular.specular_factor, 1.0, "default specularFactor");
    near(d->specular.specular_color_factor[1], 1.0, "default specular colour");
    near(d->clearcoat.clearcoat_factor, 0.0, "default clearcoat");
    near(d->clearcoat.clearcoat_roughness_factor, 0.0, "default clearcoat roughness");
    near(d->sheen.sheen_color_factor[2], 0.0, "default sheen");
    near(d->anisotropy.anisotropy_strength, 0.0, "default anisotropy");
    near(d->emissive_strength.emissive_strength, 1.0, "default strength");
    near(d->disney.specular, 0.5, "Burley's default specular (F0 0.04)");
    near(d->disney.clearcoat_gloss, 1.0, "Burley's default clearcoat gloss");
    near(d->emission[0], 0.0, "default emission");
    near(d->normal_scale, 1.0, "default normal scale");
    near(d->alpha_cutoff, 0.5, "default cutoff");
    assert_int_equal(d->alpha_mode, RTPBR_GLTF_ALPHA_OPAQUE);
    assert_false(d->double_sided);
    assert_int_equal(d->normal_texture, -1);
    assert_int_equal(scene->light_count, 0);

    const rtpbr_gltf_material* m = &scene->materials[1];
    assert_true(m->has_disney);
    near(m->base_color[0], 0.1f, "disney base r");
    near(m->base_color[2], 0.3f, "disney base b");
    near(m->base_color[3], 1.0, "disney base a (kept)");
    near(m->metallic, 0.1f, "disney metallic");
    near(m->roughness, 0.4f, "disney roughness");
    near(m->disney.subsurface, 0.25, "subsurface");
    near(m->disney.specular, 0.3f, "disney specular");
    near(m->disney.specular_tint, 0.5, "specular tint");
    near(m->disney.anisotropic, 0.6f, "anisotropic");
    near(m->disney.sheen, 0.2f, "sheen");
    near(m->disney.sheen_tint, 0.75, "sheen tint");
    near(m->disney.clearcoat, 0.35f, "clearcoat");
    near(m->disney.clearcoat_gloss, 0.9f, "clearcoat gloss");
    /* Disney's keys do not touch the KHR structs. */
    assert_false(m->has_clearcoat || m->has_sheen || m->has_anisotropy || m->has_ior);
    near(m->clearcoat.clearcoat_factor, 0.0, "no KHR clearcoat from Disney's");
    near(m->anisotropy.anisotropy_strength, 0.0, "no KHR anisotropy from Disney's");
    near(m->ior.ior, 1.5, "KHR ior untouched");

    /* ior only → specular = F0(2)/0.08 = (1/3)²/0.08 = 1.3889, clamped to 1 */
    const rtpbr_gltf_material* q = &scene->materials[2];
    assert_true(q->has_disney);
    near(q->disney.specular, 1.0, "specular from ior, clamped");
    rtpbr_gltf_destroy(scene);
}

static void test_textures_and_tangents(void** state) {
    (void)state;
    /* 2×2 RGBA: red, green / blue, white-with-alpha-128. */
    const unsigned char px[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
    size_t png_size;
    unsigned char* png = ts_png(px, 2, 2, &png_size);
    char* uri = ts_data_uri("image/png", png, png_size);
    const char* dir = ts_dir("textures");
    ts_write(dir, "tex.png", png, png_size);
    /* texture 0 = data: URI image, texture 1 = external tex.png with sampler
     * (clamp, mirrored, nearest). Base colour + emissive share texture 0
     * (sRGB), metallic-roughness + normal share texture 1 (linear). */
    char* extra = ts_format(
        ",\"images\":[{\"uri\":\"%s\"},{\"uri\":\"tex.png\"}],"
        "\"samplers\":[{\"wrapS\":33071,\"wrapT\":33648,\"magFilter\":9728}],"
        "\"textures\":[{\"source\":0},{\"source\":1,\"sampler\":0}]",
        uri);
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6,
                  .texcoords = kQuadUv, .material = 0, .extra = extra,
                  .materials = "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
                               "\"metallicRoughnessTexture\":{\"index\":1}},"
                               "\"normalTexture\":{\"index\":1,\"scale\":0.5},"
                               "\"emissiveTexture\":{\"index\":0}}"};
    char* json = ts_scene_json(&s);
    char err[512];
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = ts_load_text(dir, "t.gltf", json, NULL, &scene, err, sizeof err);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->texture_count, 2);
    const rtpbr_gltf_material* m = &scene->materials[0];
    assert_int_equal(m->base_color_texture, m->emission_texture);
    assert_int_equal(m->metallic_roughness_texture, m->normal_texture);
    assert_int_not_equal(m->base_color_texture, m->normal_texture);
    near(m->normal_scale, 0.5, "normal scale");
    const rtpbr_gltf_texture* c = &scene->textures[m->base_color_texture];
    const rtpbr_gltf_texture* n = &scene->textures[m->normal_texture];
    assert_true(c->srgb);
    assert_false(n->srgb);
    assert_int_equal(c->gltf_texture, 0);
    assert_int_equal(n->gltf_texture, 1);
    for (int t = 0; t < 2; ++t) {
        const rtpbr_gltf_texture* x = t ? n : c;
        assert_int_equal(x->width, 2);
        assert_int_equal(x->height, 2);
        assert_non_null(x->pixels);
        assert_memory_equal(x->pixels, px, 16);
    }
    assert_int_equal(c->wrap_s, RTPBR_GLTF_WRAP_REPEAT);
    assert_int_equal(n->wrap_s, RTPBR_GLTF_WRAP_CLAMP_TO_EDGE);
    assert_int_equal(n->wrap_t, RTPBR_GLTF_WRAP_MIRRORED_REPEAT);
    assert_true(n->nearest);
    assert_false(c->nearest);

    /* Normal map + UVs, no TANGENT: generated. u = x, v = y on a +Z quad →
     * T = +X, B = +Y, w = sign((N × T)·B) = +1. */
    const rtpbr_gltf_primitive* p = &scene->primitives[0];
    assert_true(p->has_texcoords);
    assert_true(p->has_tangents);
    assert_true(p->tangents_generated);
    for (uint32_t v = 0; v < 4; ++v) {
        near(p->tangents[4 * v + 0], 1.0, "tangent x");
        near(p->tangents[4 * v + 1], 0.0, "tangent y");
        near(p->tangents[4 * v + 3], 1.0, "tangent w");
        near(p->texcoords[2 * v], kQuadUv[2 * v], "texcoord u");
    }
    rtpbr_gltf_destroy(scene);

    /* skip_images: same indices, no pixels. */
    rtpbr_gltf_load_desc desc = {0};
    desc.skip_images = true;
    r = ts_load_text(dir, "t.gltf", json, &desc, &scene, err, sizeof err);
    assert_int_equal(r, RTPBR_GLTF_SUCCESS);
    assert_int_equal(scene->texture_count, 2);
    assert_null(scene->textures[0].pixels);
    assert_int_equal(scene->textures[0].width, 0);
    rtpbr_gltf_destroy(scene);

    /* Limits and broken images get their own codes. */
    desc.skip_images = false;
    desc.max_texture_dimension = 1;
    r = ts_load_text(dir, "t.gltf", json, &desc, &scene, err, sizeof err);
    assert_int_equal(r, RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE);
    assert_null(scene);
    assert_non_null(strstr(err, "image"));

    free(extra);
    free(json);
    const unsigned char junk[24] = "this is not an image!!!";
    char* bad_uri = ts_data_uri("image/png", junk, sizeof junk);
    extra = ts_format(",\"images\":[{\"uri\":\"%s\"}],\"textures\":[{\"source\":0}]", bad_uri);
    s.extra = extra;
    s.materials = "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}";
    json = ts_scene_json(&s);
    r = ts_load_text(dir, "bad.gltf", json, NULL, &scene, err, sizeof err);
    assert_int_equal(r, RTPBR_GLTF_ERROR_IMAGE_DECODE);
    assert_null(scene);
    assert_non_null(strstr(err, "image 0"));

    free(bad_uri);
    free(extra);
    free(json);
    free(uri);
    free(png);
}

static void test_glb_buffer_view_image(void** state) {
    (void)state;
    /* GLB: quad geometry + a 3×1 PNG in bufferView 3 of the BIN chunk. */
    const unsigned char px[12] = {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 0};
    size_t png_size;
    unsigned char* png = ts_png(px, 3, 1, &png_size);
    ts_scene s = {.positions = kQuad, .vertex_count = 4, .indices = kQuadIdx, .index_count = 6, .texcoords = kQuadUv};
    ts_bin bin;
    ts_scene_bin(&s, &bin);
    const size_t png_at = ts_bin_append(&bin, png, png_size);
    const char* fmt =
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24},"
        "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":32},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5125,\"count\":6,\"type\":\"SCALAR\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"}],"
        "\"images\":[{\"bufferView\":3,\"mimeType\":\"image/png\"}],\"textures\":[{\"source\":0}],"
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":2},\"indices\":1,"
        "\"material\":0}]}],\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
    char* json = ts_format(fmt, bin.size, png_at, png_size);
    size_t glb_size;
    unsigned char* glb = ts_glb(json, bin.bytes, bin.size, &glb_size);
    char err[512];
    rtpbr_gltf_load_desc desc = {0};
    desc.error_message = err;
    desc.error_message_size = sizeof err;
    rtpbr_gltf_scene* scene = NULL;
    rtpbr_gltf_result r = rtpbr_gltf_load_memory(glb, glb_size, &desc, &scene);
    if (r != RTPBR_GLTF_SUCCESS) fail_msg("%s: %s", rtpbr_gltf_result_string(r), err);
    assert_int_equal(scene->texture_count, 1);
    assert_int_equal(scene->textures[0].width, 3);
    assert_int_equal(scene->textures[0].height, 1);
    assert_memory_equal(scene->textures[0].pixels, px, 12);
    assert_true(scene->textures[0].srgb);
    rtpbr_gltf_destroy(scene);
    free(json);
    free(glb);

    /* The image's bufferView reaches past the buffer: caught before decoding (by the schema
     * pass, against the buffer's byteLength, since issue 18). */
    json = ts_format(fmt, bin.size, png_at, png_size + 4096);
    glb = ts_glb(json, bin.bytes, bin.size, &glb_size);
    r = rtpbr_gltf_load_memory(glb, glb_size, &desc, &scene);
    assert_int_equal(r, RTPBR_GLTF_ERROR_INVALID_ACCESSOR);
    assert_null(scene);
    if (!strstr(err, "bufferView 3")) fail_msg("message: %s", err);
    free(json);
    free(glb);
    free(png);
}

RTPBR_TEST_MAIN(cmocka_unit_test(test_khr_extensions),
                cmocka_unit_test(test_defaults_and_disney_extras),
                cmocka_unit_test(test_textures_and_tangents),
                cmocka_unit_test(test_glb_buffer_view_image))
