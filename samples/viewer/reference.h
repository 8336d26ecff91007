// Reading the oracle's reference image (an EXR of linear radiance) for the split view.
#ifndef RTPBR_VIEWER_REFERENCE_H
#define RTPBR_VIEWER_REFERENCE_H

#ifdef __cplusplus
extern "C" {
#endif

// Reads any image OpenImageIO can read as RGBA float (missing channels: G = B = R, A = 1).
// Returns a malloc'ed width * height * 4 array (rows top to bottom) or NULL with a message.
float *viewer_reference_load(const char *path, int *width, int *height);

#ifdef __cplusplus
}
#endif

#endif
