// The viewer's panels (see ui.h).
#include "ui.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>

struct viewer_ui {
    VkDevice device = VK_NULL_HANDLE;
    VkRenderPass pass = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkFramebuffer framebuffers[VIEWER_MAX_SWAPCHAIN_IMAGES] = {};
    uint32_t framebuffer_count = 0;
    VkExtent2D extent = {};
    ImGuiContext *imgui = nullptr;
    bool glfw_backend = false, vulkan_backend = false;
};

static bool check(VkResult r, const char *what)
{
    if (r != VK_SUCCESS) std::fprintf(stderr, "rtpbr-viewer: %s failed (VkResult %d)\n", what, r);
    return r == VK_SUCCESS;
}

static void check_imgui(VkResult r)
{
    if (r != VK_SUCCESS) std::fprintf(stderr, "rtpbr-viewer: ImGui's Vulkan backend: VkResult %d\n", r);
}

// One subpass over the swapchain image, which stays in TRANSFER_DST_OPTIMAL before and after
// (the engine's frame and the overlay copies leave it there; the screenshot copy and the
// present barrier start from there).
static bool create_pass(viewer_ui *ui, VkFormat format)
{
    VkAttachmentDescription colour = {};
    colour.format = format;
    colour.samples = VK_SAMPLE_COUNT_1_BIT;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    colour.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    VkAttachmentReference ref = {0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass = {};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency deps[2] = {};
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    VkRenderPassCreateInfo info = {};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = 1;
    info.pAttachments = &colour;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = deps;
    return check(vkCreateRenderPass(ui->device, &info, nullptr, &ui->pass), "vkCreateRenderPass");
}

static void destroy_framebuffers(viewer_ui *ui)
{
    for (uint32_t i = 0; i < ui->framebuffer_count; ++i) vkDestroyFramebuffer(ui->device, ui->framebuffers[i], nullptr);
    ui->framebuffer_count = 0;
}

bool viewer_ui_resize(viewer_ui *ui, viewer_window *w)
{
    destroy_framebuffers(ui);
    ui->extent = w->extent;
    for (uint32_t i = 0; i < w->image_count; ++i) {
        VkFramebufferCreateInfo info = {};
        info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
        info.renderPass = ui->pass;
        info.attachmentCount = 1;
        info.pAttachments = &w->views[i];
        info.width = w->extent.width;
        info.height = w->extent.height;
        info.layers = 1;
        if (!check(vkCreateFramebuffer(ui->device, &info, nullptr, &ui->framebuffers[i]), "vkCreateFramebuffer"))
            return false;
        ui->framebuffer_count = i + 1;
    }
    return true;
}

// The font atlas, uploaded once with a command buffer of the window's pool.
static bool upload_fonts(viewer_window *w)
{
    VkCommandBufferAllocateInfo alloc = {};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = w->pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd;
    if (!check(vkAllocateCommandBuffers(w->device, &alloc, &cmd), "vkAllocateCommandBuffers")) return false;
    VkCommandBufferBeginInfo begin = {};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    bool ok = check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer") && ImGui_ImplVulkan_CreateFontsTexture(cmd) &&
              check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    if (ok) {
        VkSubmitInfo submit = {};
        submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        ok = check(vkQueueSubmit(w->queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit") &&
             check(vkQueueWaitIdle(w->queue), "vkQueueWaitIdle");
    }
    vkFreeCommandBuffers(w->device, w->pool, 1, &cmd);
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return ok;
}

bool viewer_ui_create(viewer_ui **out, viewer_window *w)
{
    *out = nullptr;
    viewer_ui *ui = new (std::nothrow) viewer_ui;
    if (!ui) return false;
    ui->device = w->device;
    IMGUI_CHECKVERSION();
    ui->imgui = ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini: every run starts with the same layout
    ImGui::StyleColorsDark();
    // See-through panels: the lights and reflections behind them stay visible.
    ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 0.6f;
    ImGui::GetStyle().Colors[ImGuiCol_FrameBg].w = 0.45f;
    VkDescriptorPoolSize size = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo pool = {};
    pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 1;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    bool ok = create_pass(ui, w->format) &&
              check(vkCreateDescriptorPool(w->device, &pool, nullptr, &ui->pool), "vkCreateDescriptorPool");
    if (ok) ok = ui->glfw_backend = ImGui_ImplGlfw_InitForVulkan(w->glfw, true); // chains to the app's callbacks
    if (ok) {
        ImGui_ImplVulkan_InitInfo info = {};
        info.Instance = w->instance;
        info.PhysicalDevice = w->physical_device;
        info.Device = w->device;
        info.QueueFamily = w->queue_family;
        info.Queue = w->queue;
        info.DescriptorPool = ui->pool;
        info.MinImageCount = w->image_count < 2 ? 2 : w->image_count;
        info.ImageCount = info.MinImageCount;
        info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        info.CheckVkResultFn = check_imgui;
        ok = ui->vulkan_backend = ImGui_ImplVulkan_Init(&info, ui->pass);
    }
    ok = ok && upload_fonts(w) && viewer_ui_resize(ui, w);
    if (!ok) {
        std::fprintf(stderr, "rtpbr-viewer: cannot set up the Dear ImGui panels\n");
        viewer_ui_destroy(ui);
        return false;
    }
    *out = ui;
    return true;
}

void viewer_ui_destroy(viewer_ui *ui)
{
    if (!ui) return;
    destroy_framebuffers(ui);
    if (ui->vulkan_backend) ImGui_ImplVulkan_Shutdown();
    if (ui->glfw_backend) ImGui_ImplGlfw_Shutdown();
    if (ui->imgui) ImGui::DestroyContext(ui->imgui);
    if (ui->pool) vkDestroyDescriptorPool(ui->device, ui->pool, nullptr);
    if (ui->pass) vkDestroyRenderPass(ui->device, ui->pass, nullptr);
    delete ui;
}

bool viewer_ui_wants_mouse(const viewer_ui *ui) { return ui && ImGui::GetIO().WantCaptureMouse; }
bool viewer_ui_wants_keyboard(const viewer_ui *ui) { return ui && ImGui::GetIO().WantCaptureKeyboard; }

bool viewer_ui_record(viewer_ui *ui, VkCommandBuffer cmd, uint32_t image_index)
{
    if (image_index >= ui->framebuffer_count) return false;
    VkRenderPassBeginInfo begin = {};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = ui->pass;
    begin.framebuffer = ui->framebuffers[image_index];
    begin.renderArea.extent = ui->extent;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
    return true;
}

// ---------------------------------------------------------------------------------------------
// Panels

static void stats_panel(app *a)
{
    ImGui::Text("%s", rtpbr_context_device_name(a->ctx));
    if (a->frame_ms > 0.0) ImGui::Text("frame %.1f ms (%.2f fps)", a->frame_ms, 1000.0 / a->frame_ms);
    else ImGui::Text("frame: the first (it builds the pipelines)");
    if (a->timings.valid) {
        ImGui::Text("GPU: G-buffer %.1f ms, lighting %.1f ms", a->timings.gbuffer_ms, a->timings.lighting_ms);
        ImGui::Text("     tone map %.1f ms; panels %.2f ms", a->timings.tonemap_ms, a->win.ui_gpu_ms);
    } else {
        ImGui::TextDisabled("GPU timestamps: not available on this queue");
    }
    ImGui::Text("panels: %.2f ms CPU to build", a->ui_ms);
    ImGui::Text("%u area + %u punctual lights, %u materials, %ux%u", a->scene.light_count, a->scene.punctual_count,
                a->scene.material_count, a->renderer_w, a->renderer_h);
    if (viewer_scene_light_total(&a->scene) == 0)
        ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1.0f), "No lights: only emission and the background show\n"
                                                             "(add EXT_lights_area or KHR_lights_punctual\n"
                                                             "lights, or emissive surfaces)");
    if (!a->flip) {
        ImGui::TextDisabled("HDR-FLIP: no --reference");
        return;
    }
    int rw, rh;
    viewer_flip_size(a->flip, &rw, &rh);
    if ((uint32_t)rw != a->renderer_w || (uint32_t)rh != a->renderer_h) {
        ImGui::TextDisabled("HDR-FLIP: the reference is %dx%d, the view %ux%u", rw, rh, a->renderer_w, a->renderer_h);
        return;
    }
    double mean;
    bool busy;
    uint64_t generation = viewer_flip_result(a->flip, &mean, &busy);
    if (generation == 0) ImGui::Text("HDR-FLIP vs reference: computing...");
    else
        ImGui::Text("HDR-FLIP vs reference: %.4f%s", mean, generation != a->view_generation ? " (updating)" : "");
}

static void technique_panel(app *a)
{
    bool changed = false;
    int pass = a->monte_carlo ? 1 : 0;
    changed |= ImGui::RadioButton("LTC", &pass, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("Monte Carlo", &pass, 1);
    a->monte_carlo = pass == 1;
    if (a->monte_carlo)
        changed |= ImGui::SliderInt("samples/px/light", &a->mc_samples, 1, 256, "%d", ImGuiSliderFlags_Logarithmic);
    bool kc = !a->multiscatter_off;
    if (ImGui::Checkbox("Kulla-Conty", &kc)) a->multiscatter_off = !kc, changed = true;
    ImGui::SameLine();
    int ndf = a->ndf == RTPBR_NDF_BECKMANN_MODEL ? 1 : 0;
        if (ImGui::Combo("NDF", &ndf, "GGX\0Beckmann\0")) {
        a->ndf = ndf ? RTPBR_NDF_BECKMANN_MODEL : RTPBR_NDF_GGX_MODEL;
        changed = true;
    }
    ImGui::TextDisabled("LTC: exact clipping (sphere proxy: build flag)");
        if (ImGui::SliderFloat("exposure (EV)", &a->exposure, -8.0f, 8.0f, "%+.1f")) a->overlay_dirty = true, changed = true;
    int op = a->tonemap == RTPBR_TONEMAP_DEFAULT ? 0 : (int)a->tonemap - 1;
        if (ImGui::Combo("tone map", &op, "ACES (Narkowicz)\0Reinhard\0linear (clamp)\0")) {
        a->tonemap = (rtpbr_tonemap)(op + 1);
        a->overlay_dirty = true;
        changed = true;
    }
    if (a->reference) {
        int overlay = (int)a->overlay;
        bool flip_ok = a->flip != nullptr;
        ImGui::Text("overlay:");
        ImGui::SameLine();
        bool pick = ImGui::RadioButton("none", &overlay, VIEWER_OVERLAY_NONE);
        ImGui::SameLine();
        pick |= ImGui::RadioButton("split", &overlay, VIEWER_OVERLAY_SPLIT);
        if (flip_ok) {
            ImGui::SameLine();
            pick |= ImGui::RadioButton("FLIP heat map", &overlay, VIEWER_OVERLAY_HEATMAP);
        }
        if (pick) a->overlay = (viewer_overlay)overlay, a->overlay_dirty = true, a->flip_shown = 0;
    }
    if (changed) app_changed(a);
}

// A punctual light: what its kind has (no size, no sides; nothing of it is drawn).
static void punctual_panel(app *a, viewer_punctual *p)
{
    bool point = p->type == RTPBR_LIGHT_POINT, spot = p->type == RTPBR_LIGHT_SPOT;
    ImGui::TextDisabled("%s light (punctual; not drawn)", viewer_punctual_kind(p));
    bool edited = false;
    if (!spot && !point) ImGui::TextDisabled("(no position: light from one direction)");
    else edited |= ImGui::DragFloat3("position", p->position, 0.01f);
    if (!point) {
        // Turns as two angles (degrees): azimuth about +Y from +Z, elevation above the horizon.
        float azimuth, elevation;
        viewer_punctual_angles(p, &azimuth, &elevation);
        float angles[2] = {azimuth * 57.2957795f, elevation * 57.2957795f};
        if (ImGui::DragFloat2("azimuth, elev.", angles, 0.5f, -180.0f, 180.0f, "%.1f deg")) {
            viewer_punctual_set_angles(p, angles[0] * 0.0174532925f, std::fmax(-90.0f, std::fmin(90.0f, angles[1])) * 0.0174532925f);
            edited = true;
        }
    }
    edited |= ImGui::ColorEdit3("colour", p->color, ImGuiColorEditFlags_Float);
    edited |= ImGui::DragFloat(point || spot ? "intensity (cd)" : "illum. (lux)", &p->intensity, 0.05f, 0.0f,
                               1e5f, "%.2f");
    if (point || spot)
        edited |= ImGui::DragFloat("range (m)", &p->range, 0.05f, 0.0f, 1e4f, p->range > 0.0f ? "%.2f" : "infinite");
    if (point) // the sphere's radius: 0 a true point
        edited |= ImGui::DragFloat("radius (m)", &p->radius, 0.005f, 0.0f, 100.0f, p->radius > 0.0f ? "%.3f" : "a point");
    if (point && p->radius > 0.0f) // a capsule's length (a tube light): 0 a sphere
        edited |= ImGui::DragFloat("length (m)", &p->length, 0.01f, 0.0f, 100.0f, p->length > 0.0f ? "%.2f" : "a sphere");
    if (!point && !spot) // the disk's angular diameter: 0.53 degrees is the sun's; 0 a true direction
        edited |= ImGui::SliderAngle("disk diameter", &p->angular_diameter, 0.0f, 10.0f, "%.2f deg");
    if (spot) {
        edited |= ImGui::SliderAngle("inner cone", &p->inner_cone_angle, 0.0f, 90.0f);
        edited |= ImGui::SliderAngle("outer cone", &p->outer_cone_angle, 0.0f, 90.0f);
    }
    if (edited) {
        viewer_punctual_clamp(p);
        app_light_edited(a);
    }
}

static void light_panel(app *a)
{
    viewer_scene *s = &a->scene;
    // Add a light of each kind (I cycles them) or remove the selected one (X); short labels,
    // in two rows (the flat area lights; the sphere, the tube and the punctual ones) that fit
    // the panel's 300 pixels.
    static const char *const labels[] = {"quad", "disk", "sphere", "spot", "point", "sun", "tube", "ellipse",
                                         "screen"}; // viewer_new_light_kind
    static_assert(sizeof labels / sizeof *labels == VIEWER_NEW_LIGHT_KINDS, "a label for each kind");
    static const int order[] = {VIEWER_NEW_QUAD,   VIEWER_NEW_DISK, VIEWER_NEW_ELLIPSE, VIEWER_NEW_SCREEN,
                                VIEWER_NEW_SPHERE, VIEWER_NEW_TUBE, VIEWER_NEW_SPOT,    VIEWER_NEW_POINT,
                                VIEWER_NEW_DIRECTIONAL};
    static_assert(sizeof order / sizeof *order == VIEWER_NEW_LIGHT_KINDS, "each kind in the rows");
    ImGui::TextUnformatted("add");
    float row_start = 0.0f;
    for (int kind : order) {
        if (kind == VIEWER_NEW_SPHERE) ImGui::SetCursorPosX(row_start); // the second row, under the first
        else ImGui::SameLine();
        if (kind == VIEWER_NEW_QUAD) row_start = ImGui::GetCursorPosX();
        if (ImGui::SmallButton(labels[kind])) app_add_light(a, kind);
    }
    uint32_t total = viewer_scene_light_total(s);
    if (total == 0) {
        ImGui::TextDisabled("no lights");
        return;
    }
    if (ImGui::SmallButton("remove this light")) {
        app_remove_light(a);
        total = viewer_scene_light_total(s);
        if (total == 0) return;
    }
    int index = (int)a->light;
        if (ImGui::SliderInt("light", &index, 0, (int)total - 1)) a->light = (uint32_t)index;
    if (viewer_punctual *p = app_punctual_light(a)) {
        punctual_panel(a, p);
        return;
    }
    viewer_light *l = app_area_light(a);
    if (!l) return;
    bool disk = l->type == RTPBR_LIGHT_DISK, edited = false;
    ImGui::TextDisabled("%s light", viewer_light_kind(l));
    float radius = viewer_light_radius(l);
    if (disk) {
        float r = radius; // the disk's own radius, as the engine shades it (an ellipse's along its axis)
        if (ImGui::DragFloat("radius (m)", &r, 0.005f, VIEWER_MIN_DISK_RADIUS, VIEWER_MAX_DISK_RADIUS, "%.3f") &&
            r > 0.0f) {
            viewer_light_scale(l, r / radius); // both half-axes: the shape kept
            edited = true;
        }
        float r2 = viewer_light_radius2(l); // across the axis: a circle's radius, stretched into an ellipse
        if (ImGui::DragFloat("across (m)", &r2, 0.005f, VIEWER_MIN_DISK_RADIUS, VIEWER_MAX_DISK_RADIUS, "%.3f") &&
            r2 > 0.0f) {
            viewer_light_set_radius2(l, r2);
            edited = true;
        }
    } else {
        int n = (int)l->vertex_count;
        if (ImGui::SliderInt("vertices", &n, 3, (int)RTPBR_MAX_POLYGON_VERTICES)) {
            viewer_light_set_vertex_count(l, (uint32_t)n);
            edited = true;
        }
        float size = 2.0f * radius; // twice the vertices' mean distance from the centre
        if (ImGui::DragFloat("size (m)", &size, 0.01f, 0.01f, 100.0f, "%.2f") && size > 0.0f && radius > 0.0f) {
            viewer_light_scale(l, 0.5f * size / radius);
            edited = true;
        }
    }
    float center[3];
    viewer_light_center(l, center);
    float position[3] = {center[0], center[1], center[2]};
    if (ImGui::DragFloat3("position", position, 0.01f)) {
        float d[3] = {position[0] - center[0], position[1] - center[1], position[2] - center[2]};
        viewer_light_translate(l, d);
        edited = true;
    }
    // Turns about the world axes through the centre: the drag's change in degrees.
    float turn[3] = {0.0f, 0.0f, 0.0f};
    if (ImGui::DragFloat3("turn (deg)", turn, 0.5f)) {
        for (int axis = 0; axis < 3; ++axis)
            if (turn[axis] != 0.0f) viewer_light_rotate(l, axis, turn[axis] * 0.0174532925f);
        edited = true;
    }
    edited |= ImGui::ColorEdit3("colour", l->color, ImGuiColorEditFlags_Float);
    edited |= ImGui::DragFloat("intensity", &l->intensity, 0.05f, 0.0f, 1e4f, "%.2f");
    edited |= ImGui::Checkbox("two-sided", &l->two_sided);
    if (edited) app_light_edited(a);
}

// A slider over a material value whose glTF zero is a flag (rtpbr_material_flags; the viewer's
// materials come from rtpbr_material_desc_from_loaded, which writes every value as the file
// has it): it shows 0 while the flag is set, and an edit to 0 sets the flag.
static bool flagged_slider(const char *label, float *value, float lo, float hi, uint32_t *flags, uint32_t flag)
{
    float shown = (*flags & flag) ? 0.0f : *value;
    if (!ImGui::SliderFloat(label, &shown, lo, hi)) return false;
    *value = shown;
    *flags = shown == 0.0f ? (*flags | flag) : (*flags & ~flag);
    return true;
}

static void material_panel(app *a)
{
    viewer_scene *s = &a->scene;
    if (s->material_count == 0) {
        ImGui::TextDisabled("no materials");
        return;
    }
    int index = (int)a->material;
        if (ImGui::SliderInt("material", &index, 0, (int)s->material_count - 1)) a->material = (uint32_t)index;
    rtpbr_material_desc *m = &s->materials[a->material];
    bool e = false;
    e |= ImGui::ColorEdit3("base colour", m->base_color, ImGuiColorEditFlags_Float);
    e |= ImGui::SliderFloat("metallic", &m->metallic, 0.0f, 1.0f);
    e |= ImGui::SliderFloat("roughness", &m->roughness, 0.0f, 1.0f);
    if (m->model == RTPBR_MATERIAL_DISNEY) {
        ImGui::TextDisabled("Disney principled BRDF (Burley 2012)");
        rtpbr_disney_params *d = &m->disney;
        e |= ImGui::SliderFloat("subsurface", &d->subsurface, 0.0f, 1.0f);
        e |= flagged_slider("specular", &d->specular, 0.0f, 1.0f, &m->flags, RTPBR_MATERIAL_DISNEY_NO_SPECULAR);
        e |= ImGui::SliderFloat("specular tint", &d->specular_tint, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("sheen", &d->sheen, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("sheen tint", &d->sheen_tint, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("clearcoat", &d->clearcoat, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("clearcoat gloss", &d->clearcoat_gloss, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("anisotropic", &d->anisotropic, 0.0f, 1.0f);
    } else {
        ImGui::TextDisabled("glTF metallic-roughness + KHR_materials_*");
        e |= flagged_slider("ior", &m->ior, 1.0f, 3.0f, &m->flags, RTPBR_MATERIAL_FRESNEL_ONE);
        e |= flagged_slider("specular", &m->specular_factor, 0.0f, 1.0f, &m->flags, RTPBR_MATERIAL_NO_SPECULAR);
        e |= ImGui::ColorEdit3("specular colour", m->specular_color, ImGuiColorEditFlags_Float);
        e |= ImGui::SliderFloat("clearcoat", &m->clearcoat_factor, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("clearcoat rough.", &m->clearcoat_roughness_factor, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("anisotropy", &m->anisotropy_strength, 0.0f, 1.0f);
        e |= ImGui::SliderAngle("aniso. rotation", &m->anisotropy_rotation, -180.0f, 180.0f);
        e |= ImGui::ColorEdit3("sheen colour", m->sheen_color_factor, ImGuiColorEditFlags_Float);
        e |= ImGui::SliderFloat("sheen roughness", &m->sheen_roughness_factor, 0.0f, 1.0f);
    }
    if (ImGui::ColorEdit3("emission", m->emission, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) e = true;
    if (e) app_material_edited(a);
}

void viewer_ui_build(viewer_ui *ui, app *a)
{
    (void)ui;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(370.0f, 0.0f), ImGuiCond_Once);
    ImGui::Begin("rtpbr viewer", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(200.0f); // fixed: the windows size themselves to their content
    stats_panel(a);
    if (ImGui::CollapsingHeader("Technique", ImGuiTreeNodeFlags_DefaultOpen)) technique_panel(a);
    ImGui::TextDisabled("click: select an area light or surface; H: keys");
    ImGui::PopItemWidth();
    ImGui::End();
    // The selection on the right: the clicked light or material opens its own panel.
    // In a window too narrow for both (the default is 960 pixels) it starts collapsed.
    float width = ImGui::GetIO().DisplaySize.x;
    ImGui::SetNextWindowPos(ImVec2(width - 308.0f, 8.0f), ImGuiCond_Once);
    ImGui::SetNextWindowCollapsed(width < 700.0f, ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(300.0f, 0.0f), ImGuiCond_Once);
    ImGui::Begin("selection", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(170.0f);
    ImGui::SetNextItemOpen(a->light_selected, ImGuiCond_Always);
    bool open = ImGui::CollapsingHeader("Light");
    if (ImGui::IsItemClicked()) a->light_selected = true; // one of the two panels is open
    if (open) light_panel(a);
    ImGui::SetNextItemOpen(!a->light_selected, ImGuiCond_Always);
    open = ImGui::CollapsingHeader("Material");
    if (ImGui::IsItemClicked()) a->light_selected = false;
    if (open) material_panel(a);
    ImGui::PopItemWidth();
    ImGui::End();
    ImGui::Render();
}
