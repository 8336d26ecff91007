// Engine: rendering through the public API on lavapipe with validation on. Reference values
// come from the scene's own numbers and from formulas written in this file.
#include <stdlib.h>

#include "engine_test.h"

#define W 96
#define H 64

// An emissive square [-1, 1]^2 at z = 0 seen from (0, 0, 3): radiance is its emission inside
// the square's image, the background outside. Also checks the camera geometry pixel by pixel.
static void render_emissive_square(void **state)
{
    test_env *env = *state;
    rtpbr_context *ctx = env->ctx;
    float positions[12];
    rtpbr_material_desc material = {.emission = {2.0f, 1.0f, 0.5f}};
    rtpbr_mesh_desc mesh = test_square_mesh(1.0f, 0.0f, positions);
    rtpbr_camera_desc camera = {.position = {0.0f, 0.0f, 3.0f}, .yfov = 0.6f};
    rtpbr_gpu_scene_desc sd = {.meshes = &mesh, .mesh_count = 1, .materials = &material, .material_count = 1,
                               .cameras = &camera, .camera_count = 1};
    rtpbr_gpu_scene *scene = NULL;
    assert_int_equal(rtpbr_gpu_scene_create(ctx, &sd, &scene), RTPBR_SUCCESS);
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    rtpbr_render_desc rd = {.background = {0.1f, 0.2f, 0.3f}, .exposure = -1.0f};
    assert_int_equal(rtpbr_render(r, scene, &rd), RTPBR_SUCCESS);

    float *radiance = malloc(W * H * 16);
    uint8_t *display = malloc(W * H * 4);
    assert_int_equal(test_read_radiance(r, radiance, W * H * 16), RTPBR_SUCCESS);
    assert_int_equal(test_read_display(r, display, W * H * 4), RTPBR_SUCCESS);

    // Where the ray through each pixel centre meets z = 0 (pinhole at z = 3, looking down -Z,
    // rows top to bottom): x = ndc_x * tan(fov/2) * aspect * 3, y = -ndc_y * tan(fov/2) * 3.
    const double t = tan(0.3), pixel_world = 2.0 * t * 3.0 / H;
    int inside = 0, outside = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double nx = (x + 0.5) / W * 2.0 - 1.0, ny = (y + 0.5) / H * 2.0 - 1.0;
            double wx = nx * t * ((double)W / H) * 3.0, wy = -ny * t * 3.0;
            double edge = fmax(fabs(wx), fabs(wy));
            const float *p = radiance + 4 * (y * W + x);
            const uint8_t *d = display + 4 * (y * W + x);
            if (edge < 1.0 - 1.5 * pixel_world) {
                ++inside;
                assert_float_equal(p[0], 2.0f, 0.0f);
                assert_float_equal(p[1], 1.0f, 0.0f);
                assert_float_equal(p[2], 0.5f, 0.0f);
                assert_float_equal(p[3], 1.0f, 0.0f);
                // exposure -1: display = sRGB(ACES(radiance / 2)), within one 8-bit step.
                assert_true(abs(d[0] - test_srgb8(test_aces(1.0))) <= 1);
                assert_true(abs(d[1] - test_srgb8(test_aces(0.5))) <= 1);
                assert_true(abs(d[2] - test_srgb8(test_aces(0.25))) <= 1);
            } else if (edge > 1.0 + 1.5 * pixel_world) {
                ++outside;
                assert_float_equal(p[0], 0.1f, 1e-7f);
                assert_float_equal(p[1], 0.2f, 1e-7f);
                assert_float_equal(p[2], 0.3f, 1e-7f);
                assert_float_equal(p[3], 0.0f, 0.0f);
                assert_true(abs(d[1] - test_srgb8(test_aces(0.1))) <= 1);
            }
        }
    assert_true(inside > W * H / 4);
    assert_true(outside > W * H / 10);

    // Every tone-mapping operator gives its documented curve on the square.
    const struct { rtpbr_tonemap op; double expect; } ops[] = {
        {RTPBR_TONEMAP_REINHARD, 0.5 / 1.5},
        {RTPBR_TONEMAP_LINEAR, 0.5},
        {RTPBR_TONEMAP_ACES, test_aces(0.5)},
    };
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; ++i) {
        rtpbr_render_desc o = {.tonemap = ops[i].op, .exposure = -1.0f};
        assert_int_equal(rtpbr_render(r, scene, &o), RTPBR_SUCCESS);
        assert_int_equal(test_read_display(r, display, W * H * 4), RTPBR_SUCCESS);
        const uint8_t *centre = display + 4 * ((H / 2) * W + W / 2);
        assert_true(abs(centre[1] - test_srgb8(ops[i].expect)) <= 1);
    }
    // Every shader variant runs.
    for (int ndf = RTPBR_NDF_DEFAULT; ndf <= RTPBR_NDF_BECKMANN_MODEL; ++ndf)
        for (int ms = RTPBR_MULTISCATTER_DEFAULT; ms <= RTPBR_MULTISCATTER_OFF; ++ms) {
            rtpbr_render_desc v = {.ndf = (rtpbr_ndf)ndf, .multiscatter = (rtpbr_multiscatter)ms};
            assert_int_equal(rtpbr_render(r, scene, &v), RTPBR_SUCCESS);
        }

    free(radiance);
    free(display);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
    env->no_errors = true;
}

// A nearer opaque surface hides a farther one (depth test), whatever the draw order.
static void depth_order(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float near_square[12], far_square[12];
    square_positions(0.5f, 0.5f, near_square);
    square_positions(3.0f, -0.5f, far_square);
    rtpbr_material_desc materials[2] = {{.emission = {1.0f, 0.0f, 0.0f}}, {.emission = {0.0f, 1.0f, 0.0f}}};
    rtpbr_mesh_desc meshes[2] = {
        {.positions = near_square, .indices = square_indices, .vertex_count = 4, .index_count = 6, .material = 0},
        {.positions = far_square, .indices = square_indices, .vertex_count = 4, .index_count = 6, .material = 1},
    };
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = meshes, .mesh_count = 2,
                                                                     .materials = materials, .material_count = 2});
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = 32, .height = 32});
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    float px[32 * 32 * 4];
    assert_int_equal(test_read_radiance(r, px, sizeof px), RTPBR_SUCCESS);
    const float *centre = px + 4 * (16 * 32 + 16);
    assert_float_equal(centre[0], 1.0f, 0.0f);
    assert_float_equal(centre[1], 0.0f, 0.0f);
    const float *corner = px + 4 * (1 * 32 + 1); // default camera (0,0,5), fov 45 deg: far square covers it
    assert_float_equal(corner[0], 0.0f, 0.0f);
    assert_float_equal(corner[1], 1.0f, 0.0f);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// Emission is one-sided unless the material is double-sided; a single-sided surface seen from
// behind is not drawn (glTF doubleSided false), a double-sided one reflects on both sides.
static void emission_sides(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float positions[12];
    square_positions(1.0f, 0.0f, positions); // front faces +Z
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = 16, .height = 16});
    // In front; behind at a grazing angle (where depth reconstruction errors are largest).
    rtpbr_camera_desc cameras[2] = {{.position = {0, 0, 3}}, {.position = {0.0f, -3.0f, -1.0f}, .up = {0, 0, 1}}};
    for (int double_sided = 0; double_sided < 2; ++double_sided) {
        rtpbr_material_desc material = {.base_color = {0.8f, 0.8f, 0.8f}, .emission = {1.5f, 1.5f, 1.5f},
                                        .double_sided = double_sided};
        rtpbr_mesh_desc mesh = {.positions = positions, .indices = square_indices, .vertex_count = 4, .index_count = 6};
        // The square is also a one-sided light: its own surface must not light itself (the
        // position reconstructed from depth must not land on its emitting side).
        rtpbr_light_desc light = {.vertex_count = 4, .emission = {1.5f, 1.5f, 1.5f}};
        memcpy(light.vertices, positions, sizeof positions);
        rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                         .materials = &material, .material_count = 1,
                                                                         .lights = &light, .light_count = 1,
                                                                         .cameras = cameras, .camera_count = 2});
        for (uint32_t c = 0; c < 2; ++c) {
            assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.camera_index = c}), RTPBR_SUCCESS);
            float px[16 * 16 * 4];
            assert_int_equal(test_read_radiance(r, px, sizeof px), RTPBR_SUCCESS);
            const float *centre = px + 4 * (8 * 16 + 8);
            float expect = (c == 0 || double_sided) ? 1.5f : 0.0f;
            assert_float_equal(centre[0], expect, 1e-3f);
            // A surface, except a single-sided one seen from behind: not drawn (glTF doubleSided).
            assert_float_equal(centre[3], c == 1 && !double_sided ? 0.0f : 1.0f, 0.0f);
            if (c == 1 && !double_sided)
                for (int i = 0; i < 16 * 16; ++i) assert_true(px[4 * i] <= 1e-3f); // dark everywhere
        }
        rtpbr_gpu_scene_destroy(scene);
    }
    rtpbr_renderer_destroy(r);
}

// An sRGB emission texture on the square: at the centre of each quadrant (one colour each)
// radiance = emission factor x the decoded texel (IEC 61966-2-1 decoding written here).
static double srgb_decode(int v)
{
    double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static void emission_texture(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    float positions[12];
    square_positions(1.0f, 0.0f, positions);
    // uv = ((x + 1) / 2, (1 - y) / 2): texel row 0 is the top (+Y) of the square.
    const float uv[8] = {0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f};
    // Four colours, one per quadrant, each 2x2 texels: bilinear filtering near a quadrant's
    // centre only mixes texels of its colour.
    const uint8_t colours[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 128, 64, 32, 255};
    uint8_t texels[4 * 4 * 4];
    for (int ty = 0; ty < 4; ++ty)
        for (int tx = 0; tx < 4; ++tx) memcpy(texels + 4 * (ty * 4 + tx), colours + 4 * ((ty / 2) * 2 + tx / 2), 4);
    rtpbr_texture_desc texture = {.width = 4, .height = 4, .rgba = texels, .srgb = 1};
    rtpbr_material_desc material = {.emission = {2.0f, 2.0f, 2.0f}, .emission_texture = 1};
    rtpbr_mesh_desc mesh = {.positions = positions, .texcoords = uv, .indices = square_indices, .vertex_count = 4,
                            .index_count = 6};
    rtpbr_camera_desc camera = {.position = {0.0f, 0.0f, 3.0f}, .yfov = 0.6f};
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                     .materials = &material, .material_count = 1,
                                                                     .cameras = &camera, .camera_count = 1,
                                                                     .textures = &texture, .texture_count = 1});
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = W, .height = H});
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    float *px = malloc(W * H * 16);
    assert_int_equal(test_read_radiance(r, px, W * H * 16), RTPBR_SUCCESS);
    const double t = tan(0.3);
    for (int q = 0; q < 4; ++q) {
        double wx = (q % 2) ? 0.5 : -0.5, wy = (q / 2) ? -0.5 : 0.5; // texel q's quadrant centre
        int x = (int)floor((wx / (t * ((double)W / H) * 3.0) + 1.0) * 0.5 * W);
        int y = (int)floor((1.0 - wy / (t * 3.0)) * 0.5 * H);
        const float *p = px + 4 * (y * W + x);
        for (int c = 0; c < 3; ++c) {
            double expect = 2.0 * srgb_decode(colours[4 * q + c]);
            if (!(fabs(p[c] - expect) <= 0.01 * expect + 2e-3)) /* 8-bit texels, fp16 G-buffer */
                fail_msg("quadrant %d channel %d (pixel %d, %d): %f, expected %f", q, c, x, y, p[c], expect);
        }
    }
    // A texture index past the scene's textures is refused.
    material.emission_texture = 2;
    rtpbr_gpu_scene *bad = NULL;
    assert_int_equal(rtpbr_gpu_scene_create(ctx,
                                            &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                    .materials = &material, .material_count = 1,
                                                                    .textures = &texture, .texture_count = 1},
                                            &bad),
                     RTPBR_ERROR_INVALID_ARGUMENT);
    free(px);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

// A host allocator that counts the library's live blocks and bytes (a size header in front).
typedef struct counting_allocator {
    long blocks;
    long long bytes;
} counting_allocator;

typedef union block_header {
    size_t size;
    max_align_t align;
} block_header;

static void *counting_alloc(size_t size, void *user_data)
{
    counting_allocator *a = user_data;
    block_header *h = malloc(sizeof *h + size);
    if (!h) return NULL;
    h->size = size;
    a->blocks++;
    a->bytes += (long long)size;
    return h + 1;
}

static void counting_free(void *ptr, void *user_data)
{
    if (!ptr) return;
    counting_allocator *a = user_data;
    block_header *h = (block_header *)ptr - 1;
    a->blocks--;
    a->bytes -= (long long)h->size;
    free(h);
}

// Create, render and destroy a scene and a renderer many times (100; the environment variable
// RTPBR_TEST_LIFECYCLE_ITERATIONS sets fewer, as under valgrind), then contexts 5 times (at
// most as many as iterations): every iteration gives back
// every host block it took (counted through the context's allocator), the validation layer's
// object tracker reports any Vulkan object still alive at vkDestroyDevice, and LeakSanitizer
// (ASan build) or memcheck (valgrind setup) any host leak.
static void lifecycle(void **state)
{
    (void)state;
    int iterations = 100;
    const char *env = getenv("RTPBR_TEST_LIFECYCLE_ITERATIONS");
    if (env && atoi(env) > 0) iterations = atoi(env);
    test_log log = {0};
    counting_allocator counts = {0};
    rtpbr_context_desc desc = {
        .allocator = {counting_alloc, counting_free, &counts},
        .logger = {test_log_func, &log},
        .validation = 1,
    };
    rtpbr_context *ctx = NULL;
    assert_int_equal(rtpbr_context_create(&desc, &ctx), RTPBR_SUCCESS);
    const long context_blocks = counts.blocks;
    const long long context_bytes = counts.bytes;
    assert_true(context_blocks > 0); // the context itself comes from the allocator
    float positions[12];
    rtpbr_mesh_desc mesh = test_square_mesh(1.0f, 0.0f, positions);
    rtpbr_light_desc light = {.vertices = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}}, .vertex_count = 4,
                              .emission = {1, 1, 1}};
    for (int i = 0; i < iterations; ++i) {
        rtpbr_gpu_scene *scene = NULL;
        rtpbr_renderer *r = NULL;
        assert_int_equal(rtpbr_gpu_scene_create(ctx,
                                                &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                        .lights = &light, .light_count = 1},
                                                &scene),
                         RTPBR_SUCCESS);
        assert_int_equal(rtpbr_renderer_create(ctx, &(rtpbr_renderer_desc){.width = 8 + (uint32_t)i, .height = 8}, &r),
                         RTPBR_SUCCESS);
        assert_true(counts.blocks > context_blocks); // scene and renderer are host blocks too
        assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
        rtpbr_renderer_destroy(r);
        rtpbr_gpu_scene_destroy(scene);
        if (counts.blocks != context_blocks || counts.bytes != context_bytes)
            fail_msg("iteration %d: %ld blocks / %lld bytes live, %ld / %lld before", i, counts.blocks, counts.bytes,
                     context_blocks, context_bytes);
    }
    rtpbr_context_destroy(ctx);
    assert_int_equal(counts.blocks, 0);
    assert_int_equal(counts.bytes, 0);
    for (int i = 0; i < 5 && i < iterations; ++i) rtpbr_context_destroy(test_context(&log));
    assert_int_equal(log.validation, 0);
    assert_int_equal(log.errors, 0);
}

// rtpbr_record into the host's own UNORM image gives the display image of rtpbr_render, and
// rtpbr_read_radiance after the host's submission its radiance.
static void record_into_host_image(void **state)
{
    rtpbr_context *ctx = test_env_context(state);
    rtpbr_vulkan_device vk = rtpbr_context_vulkan_device(ctx);
    float positions[12];
    rtpbr_material_desc material = {.emission = {0.2f, 0.6f, 3.0f}};
    rtpbr_mesh_desc mesh = test_square_mesh(1.0f, 0.0f, positions);
    rtpbr_gpu_scene *scene = test_scene(ctx, &(rtpbr_gpu_scene_desc){.meshes = &mesh, .mesh_count = 1,
                                                                     .materials = &material, .material_count = 1});
    enum { S = 40 };
    rtpbr_renderer *r = test_renderer(ctx, &(rtpbr_renderer_desc){.width = S, .height = S});
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){0}), RTPBR_SUCCESS);
    uint8_t expect[S * S * 4];
    assert_int_equal(test_read_display(r, expect, sizeof expect), RTPBR_SUCCESS);
    static float expect_radiance[S * S * 4], radiance[S * S * 4];
    assert_int_equal(test_read_radiance(r, expect_radiance, sizeof expect_radiance), RTPBR_SUCCESS);
    // Another frame read back, so that a read of the recorded frame's radiance that copied
    // nothing would give this one's (background 5 in the corner).
    assert_int_equal(rtpbr_render(r, scene, &(rtpbr_render_desc){.background = {5, 5, 5}}), RTPBR_SUCCESS);
    assert_int_equal(test_read_radiance(r, radiance, sizeof radiance), RTPBR_SUCCESS);
    assert_float_equal(radiance[0], 5.0f, 0.0f);
    assert_float_equal(expect_radiance[0], 0.0f, 0.0f);

    // The host's objects: an image, a host-visible buffer, a command pool and buffer, a fence.
    VkDevice dev = vk.device;
    VkImage image;
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = VK_FORMAT_R8G8B8A8_UNORM, .extent = {S, S, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT};
    assert_int_equal(vkCreateImage(dev, &ii, NULL, &image), VK_SUCCESS);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(vk.physical_device, &mp);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, image, &req);
    uint32_t type = 0;
    while (!(req.memoryTypeBits & (1u << type))) ++type;
    VkDeviceMemory image_memory, buffer_memory;
    assert_int_equal(vkAllocateMemory(dev, &(VkMemoryAllocateInfo){VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, NULL, req.size, type},
                                      NULL, &image_memory),
                     VK_SUCCESS);
    assert_int_equal(vkBindImageMemory(dev, image, image_memory, 0), VK_SUCCESS);
    VkImageView view;
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = VK_FORMAT_R8G8B8A8_UNORM,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    assert_int_equal(vkCreateImageView(dev, &vi, NULL, &view), VK_SUCCESS);
    VkBuffer buffer;
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = S * S * 4,
                             .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    assert_int_equal(vkCreateBuffer(dev, &bi, NULL, &buffer), VK_SUCCESS);
    vkGetBufferMemoryRequirements(dev, buffer, &req);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    type = 0;
    while (!((req.memoryTypeBits & (1u << type)) && (mp.memoryTypes[type].propertyFlags & host) == host)) ++type;
    assert_int_equal(vkAllocateMemory(dev, &(VkMemoryAllocateInfo){VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, NULL, req.size, type},
                                      NULL, &buffer_memory),
                     VK_SUCCESS);
    assert_int_equal(vkBindBufferMemory(dev, buffer, buffer_memory, 0), VK_SUCCESS);
    VkCommandPool pool;
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .queueFamilyIndex = vk.queue_family_index};
    assert_int_equal(vkCreateCommandPool(dev, &pi, NULL, &pool), VK_SUCCESS);
    VkCommandBuffer cmd;
    VkCommandBufferAllocateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    assert_int_equal(vkAllocateCommandBuffers(dev, &ci, &cmd), VK_SUCCESS);
    VkFence fence;
    assert_int_equal(vkCreateFence(dev, &(VkFenceCreateInfo){.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO}, NULL, &fence),
                     VK_SUCCESS);

    assert_int_equal(vkBeginCommandBuffer(cmd, &(VkCommandBufferBeginInfo){.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO}),
                     VK_SUCCESS);
    rtpbr_record_desc target = {.command_buffer = cmd, .image = image, .view = view, .format = VK_FORMAT_R8G8B8A8_UNORM,
                                .new_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    assert_int_equal(rtpbr_record(r, scene, &(rtpbr_render_desc){0}, &target), RTPBR_SUCCESS);
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {S, S, 1}};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    test_submit_for_host(dev, vk.queue, cmd, fence);
    void *mapped;
    assert_int_equal(vkMapMemory(dev, buffer_memory, 0, VK_WHOLE_SIZE, 0, &mapped), VK_SUCCESS);
    test_device_output(mapped, S * S * 4);
    const uint8_t *got = mapped;
    for (int i = 0; i < S * S * 4; ++i) assert_true(abs(got[i] - expect[i]) <= 1);
    vkUnmapMemory(dev, buffer_memory);
    // The recorded frame's radiance, copied by this read now that the host's submission has
    // completed: rtpbr_render's.
    assert_int_equal(test_read_radiance(r, radiance, sizeof radiance), RTPBR_SUCCESS);
    assert_memory_equal(radiance, expect_radiance, sizeof radiance);

    vkDestroyFence(dev, fence, NULL);
    vkDestroyCommandPool(dev, pool, NULL);
    vkDestroyBuffer(dev, buffer, NULL);
    vkFreeMemory(dev, buffer_memory, NULL);
    vkDestroyImageView(dev, view, NULL);
    vkDestroyImage(dev, image, NULL);
    vkFreeMemory(dev, image_memory, NULL);
    rtpbr_renderer_destroy(r);
    rtpbr_gpu_scene_destroy(scene);
}

int main(void)
{
    // RTPBR_TEST_FILTER="depth_order" runs only the tests whose names match (cmocka pattern).
    const char *filter = getenv("RTPBR_TEST_FILTER");
    if (filter && *filter) cmocka_set_test_filter(filter);
    RTPBR_RUN_TESTS(NULL, NULL,
                    test_env_case(render_emissive_square),
                    test_env_case(depth_order),
                    test_env_case(emission_sides),
                    test_env_case(emission_texture),
                    test_env_case(record_into_host_image),
                    cmocka_unit_test(lifecycle));
}
