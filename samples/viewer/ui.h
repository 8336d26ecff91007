// The viewer's on-screen panels: Dear ImGui (Debian's libimgui-dev 1.86, with its GLFW and
// Vulkan backends) drawn by one small render pass over the swapchain image after the engine's
// frame. Hidden with --no-ui (then none of this is created).
#ifndef RTPBR_VIEWER_UI_H
#define RTPBR_VIEWER_UI_H

#include "app.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct viewer_ui viewer_ui;

// After the window and the app's GLFW callbacks exist (ImGui chains to them). False with a
// message on stderr.
bool viewer_ui_create(viewer_ui **out, viewer_window *w);
void viewer_ui_destroy(viewer_ui *ui); // NULL: no-op; the device must be idle
// Framebuffers for the current swapchain images (after each viewer_window_resize).
bool viewer_ui_resize(viewer_ui *ui, viewer_window *w);
// Builds this frame's panels, editing the app (then calling app_changed & co).
void viewer_ui_build(viewer_ui *ui, app *a);
// Records the panels' render pass into the acquired swapchain image.
bool viewer_ui_record(viewer_ui *ui, VkCommandBuffer cmd, uint32_t image_index);
// Whether ImGui takes the mouse / keyboard (the viewer's camera and keys then keep still).
bool viewer_ui_wants_mouse(const viewer_ui *ui);
bool viewer_ui_wants_keyboard(const viewer_ui *ui);

#ifdef __cplusplus
}
#endif

#endif
