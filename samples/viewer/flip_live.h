// The live HDR-FLIP of the viewer's image against a reference (common/'s FLIP code, the
// same computation as `rtpbr-diff --hdr`), evaluated on a background thread so the window
// stays interactive, plus the error map as a heat-map overlay.
#ifndef RTPBR_VIEWER_FLIP_LIVE_H
#define RTPBR_VIEWER_FLIP_LIVE_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct viewer_flip viewer_flip;

// Reads the reference with rtpbr-diff's own reader (linear RGB; alpha ignored). NULL with a
// message on stderr.
viewer_flip *viewer_flip_create(const char *reference_path);
void viewer_flip_destroy(viewer_flip *f); // waits for the worker; NULL: no-op
void viewer_flip_size(const viewer_flip *f, int *width, int *height);

// Hands the worker an RGBA float image (w x h, the engine's radiance) tagged with generation;
// false (nothing copied) when the worker is busy or the size differs from the reference's.
bool viewer_flip_submit(viewer_flip *f, const float *rgba, int w, int h, uint64_t generation);
// The latest finished evaluation: its generation (0: none yet) and mean error; *busy tells
// whether one is running.
uint64_t viewer_flip_result(viewer_flip *f, double *mean, bool *busy);
// Blocks until the running evaluation (if any) has finished.
void viewer_flip_wait(viewer_flip *f);
// The latest error map as magma colours (rtpbr-diff's heat-map palette), w x h bytes x 4 in
// R, G, B, A order or B, G, R, A with bgra, nearest-scaled to w x h.
void viewer_flip_heatmap(viewer_flip *f, uint8_t *dst, int w, int h, bool bgra);

// Synchronous HDR-FLIP mean of an RGBA float image against the reference (for scripted runs);
// negative on a size mismatch or a FLIP error (message on stderr).
double viewer_flip_mean_now(const viewer_flip *f, const float *rgba, int w, int h);
// Writes the RGB of an RGBA float image as a float EXR (any OpenImageIO format by extension).
bool viewer_write_radiance(const char *path, const float *rgba, int w, int h);

#ifdef __cplusplus
}
#endif

#endif
