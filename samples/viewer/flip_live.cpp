// The live HDR-FLIP (see flip_live.h): one worker thread, one job at a time.
#include "flip_live.h"

#include "rtpbr_common/flip.hpp"
#include "rtpbr_common/colormap.hpp"
#include "rtpbr_common/image.hpp"
#include "rtpbr_common/image_read.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <vector>

struct viewer_flip {
    rtpbr::Image reference;
    std::mutex mutex;
    std::condition_variable wake, finished;
    std::thread worker;
    bool quit = false;
    bool busy = false;                // a job is queued or running
    std::vector<float> job_rgb;       // the submitted image (RGB)
    uint64_t job_generation = 0;
    std::vector<float> error_map;     // the latest result
    uint64_t result_generation = 0;
    double result_mean = 0.0;
};

static void rgb_of(const float *rgba, int w, int h, std::vector<float> &rgb)
{
    size_t n = static_cast<size_t>(w) * h;
    rgb.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = rgba[4 * i + c];
}

static void run_worker(viewer_flip *f)
{
    std::unique_lock<std::mutex> lock(f->mutex);
    for (;;) {
        f->wake.wait(lock, [f] { return f->quit || f->busy; });
        if (f->quit) return;
        std::vector<float> test = f->job_rgb;
        uint64_t generation = f->job_generation;
        lock.unlock();
        std::vector<float> map;
        rtpbr::FlipResult r = rtpbr::flip_hdr(f->reference.rgb.data(), test.data(), f->reference.width,
                                              f->reference.height, rtpbr::kFlipDefaultPpd, map);
        double mean = r == rtpbr::FlipResult::ok ? rtpbr::flip_stats(map).mean : -1.0;
        if (r != rtpbr::FlipResult::ok)
            std::fprintf(stderr, "rtpbr-viewer: FLIP failed: %s\n", rtpbr::flip_result_string(r));
        lock.lock();
        if (r == rtpbr::FlipResult::ok) f->error_map.swap(map);
        f->result_generation = generation;
        f->result_mean = mean;
        f->busy = false;
        f->finished.notify_all();
    }
}

viewer_flip *viewer_flip_create(const char *reference_path)
{
    viewer_flip *f = new (std::nothrow) viewer_flip;
    if (!f) return nullptr;
    std::string error;
    if (!rtpbr::read_image(reference_path, f->reference, error)) {
        std::fprintf(stderr, "rtpbr-viewer: reference %s: %s\n", reference_path, error.c_str());
        delete f;
        return nullptr;
    }
    f->worker = std::thread(run_worker, f);
    return f;
}

void viewer_flip_destroy(viewer_flip *f)
{
    if (!f) return;
    {
        std::lock_guard<std::mutex> lock(f->mutex);
        f->quit = true;
    }
    f->wake.notify_all();
    f->worker.join();
    delete f;
}

void viewer_flip_size(const viewer_flip *f, int *width, int *height)
{
    *width = f->reference.width;
    *height = f->reference.height;
}

bool viewer_flip_submit(viewer_flip *f, const float *rgba, int w, int h, uint64_t generation)
{
    if (w != f->reference.width || h != f->reference.height) return false;
    std::lock_guard<std::mutex> lock(f->mutex);
    if (f->busy) return false;
    rgb_of(rgba, w, h, f->job_rgb);
    f->job_generation = generation;
    f->busy = true;
    f->wake.notify_all();
    return true;
}

uint64_t viewer_flip_result(viewer_flip *f, double *mean, bool *busy)
{
    std::lock_guard<std::mutex> lock(f->mutex);
    *mean = f->result_mean;
    *busy = f->busy;
    return f->result_generation;
}

void viewer_flip_wait(viewer_flip *f)
{
    std::unique_lock<std::mutex> lock(f->mutex);
    f->finished.wait(lock, [f] { return !f->busy; });
}

void viewer_flip_heatmap(viewer_flip *f, uint8_t *dst, int w, int h, bool bgra)
{
    std::lock_guard<std::mutex> lock(f->mutex);
    int mw = f->reference.width, mh = f->reference.height;
    bool have = f->error_map.size() == static_cast<size_t>(mw) * mh;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float e = have ? f->error_map[static_cast<size_t>(y) * mh / h * mw + static_cast<size_t>(x) * mw / w] : 0.0f;
            // rtpbr-diff's quantisation (--heatmap)
            uint8_t rgb[3];
            rtpbr_tools::magma(e, rgb);
            uint8_t *o = dst + 4 * (static_cast<size_t>(y) * w + x);
            o[0] = bgra ? rgb[2] : rgb[0], o[1] = rgb[1], o[2] = bgra ? rgb[0] : rgb[2], o[3] = 255;
        }
}

double viewer_flip_mean_now(const viewer_flip *f, const float *rgba, int w, int h)
{
    if (w != f->reference.width || h != f->reference.height) {
        std::fprintf(stderr, "rtpbr-viewer: FLIP: the view is %dx%d, the reference %dx%d\n", w, h, f->reference.width,
                     f->reference.height);
        return -1.0;
    }
    std::vector<float> rgb, map;
    rgb_of(rgba, w, h, rgb);
    rtpbr::FlipResult r = rtpbr::flip_hdr(f->reference.rgb.data(), rgb.data(), w, h, rtpbr::kFlipDefaultPpd, map);
    if (r != rtpbr::FlipResult::ok) {
        std::fprintf(stderr, "rtpbr-viewer: FLIP failed: %s\n", rtpbr::flip_result_string(r));
        return -1.0;
    }
    return rtpbr::flip_stats(map).mean;
}

bool viewer_write_radiance(const char *path, const float *rgba, int w, int h)
{
    std::vector<float> rgb;
    rgb_of(rgba, w, h, rgb);
    std::string error;
    if (!rtpbr_tools::write_image_float(path, w, h, 3, rgb.data(), error)) {
        std::fprintf(stderr, "rtpbr-viewer: %s\n", error.c_str());
        return false;
    }
    return true;
}
