// rtpbr oracle: accumulators (merge, resolve, files) and image output.
#include "oracle.h"

#include "internal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rtpbr_common/image.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace rtpbr_oracle {

Result merge(Accumulator *a, const Accumulator &b, std::string *error) {
    if (a->width != b.width || a->height != b.height || a->seed != b.seed || a->settingsHash != b.settingsHash ||
        a->samples.size() != b.samples.size() || a->sum.size() != b.sum.size() ||
        a->sumSquares.size() != b.sumSquares.size()) {
        if (error)
            *error = "accumulators differ in image size, seed or render settings";
        return Result::Incompatible;
    }
    for (size_t i = 0; i < a->samples.size(); i++)
        a->samples[i] += b.samples[i];
    for (size_t i = 0; i < a->sum.size(); i++) {
        a->sum[i] += b.sum[i];
        a->sumSquares[i] += b.sumSquares[i];
    }
    a->nonFinite += b.nonFinite;
    a->clamped += b.clamped;
    return Result::Success;
}

void resolve(const Accumulator &acc, std::vector<float> *rgb, std::vector<float> *stderrRgb) {
    size_t npix = acc.samples.size();
    rgb->assign(3 * npix, 0.0f);
    if (stderrRgb)
        stderrRgb->assign(3 * npix, 0.0f);
    for (size_t i = 0; i < npix; i++) {
        double n = double(acc.samples[i]);
        if (n <= 0.0)
            continue;
        for (int c = 0; c < 3; c++) {
            double mean = std::ldexp(double(acc.sum[3 * i + size_t(c)]), -64) / n;
            (*rgb)[3 * i + size_t(c)] = float(mean);
            if (stderrRgb && n > 1.0) {
                double var = (acc.sumSquares[3 * i + size_t(c)] - n * mean * mean) / (n - 1.0);
                (*stderrRgb)[3 * i + size_t(c)] = float(std::sqrt(std::max(var, 0.0) / n));
            }
        }
    }
}

// ---- accumulator files -----------------------------------------------------------------------
// Layout (host byte order, little-endian on every platform rtpbr targets):
//   char magic[8] = "RTPBRAC1"; uint32 width, height; uint64 seed, settingsHash, nonFinite,
//   clamped; uint32 samples[w*h]; int128 sum[3*w*h]; double sumSquares[3*w*h].

namespace {
constexpr char kMagic[8] = {'R', 'T', 'P', 'B', 'R', 'A', 'C', '1'};

struct FileCloser {
    void operator()(FILE *f) const {
        if (f)
            fclose(f);
    }
};
} // namespace

Result writeAccumulator(const std::string &path, const Accumulator &acc, std::string *error) {
    std::unique_ptr<FILE, FileCloser> f(fopen(path.c_str(), "wb"));
    if (!f) {
        *error = "cannot open " + path + " for writing: " + strerror(errno);
        return Result::Io;
    }
    bool ok = fwrite(kMagic, 1, 8, f.get()) == 8;
    uint32_t dims[2] = {acc.width, acc.height};
    uint64_t meta[4] = {acc.seed, acc.settingsHash, acc.nonFinite, acc.clamped};
    ok = ok && fwrite(dims, sizeof dims, 1, f.get()) == 1 && fwrite(meta, sizeof meta, 1, f.get()) == 1;
    ok = ok && fwrite(acc.samples.data(), sizeof(uint32_t), acc.samples.size(), f.get()) == acc.samples.size();
    ok = ok && fwrite(acc.sum.data(), sizeof(__int128), acc.sum.size(), f.get()) == acc.sum.size();
    ok = ok && fwrite(acc.sumSquares.data(), sizeof(double), acc.sumSquares.size(), f.get()) == acc.sumSquares.size();
    FILE *raw = f.release();
    ok = (fclose(raw) == 0) && ok;
    if (!ok) {
        *error = "cannot write " + path;
        return Result::Io;
    }
    return Result::Success;
}

Result readAccumulator(const std::string &path, Accumulator *acc, std::string *error, uint64_t memoryLimit) {
    // Regular files only: opening a FIFO for reading would block until a writer comes, so it
    // is opened non-blocking and refused by fstat before anything is read.
    int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        *error = "cannot open " + path + ": " + strerror(errno);
        return Result::Io;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        *error = path + ": not a regular file";
        return Result::Io;
    }
    std::unique_ptr<FILE, FileCloser> f(fdopen(fd, "rb"));
    if (!f) {
        close(fd);
        *error = "cannot open " + path + ": " + strerror(errno);
        return Result::Io;
    }
    char magic[8];
    uint32_t dims[2];
    uint64_t meta[4];
    if (fread(magic, 1, 8, f.get()) != 8 || std::memcmp(magic, kMagic, 8) != 0 ||
        fread(dims, sizeof dims, 1, f.get()) != 1 || fread(meta, sizeof meta, 1, f.get()) != 1) {
        *error = path + ": not an rtpbr-oracle accumulator file";
        return Result::Io;
    }
    if (dims[0] == 0 || dims[1] == 0 || dims[0] > 65536 || dims[1] > 65536 ||
        uint64_t(dims[0]) * dims[1] > (1ull << 28)) {
        *error = path + ": bad image size in header";
        return Result::Io;
    }
    size_t npix = size_t(dims[0]) * dims[1];
    const uint64_t fileBytes = 8 + sizeof dims + sizeof meta + uint64_t(npix) * (4 + 48 + 24);
    if (uint64_t(st.st_size) != fileBytes) {
        *error = fmt("%s: %llu bytes, a %ux%u accumulator has %llu", path.c_str(), (unsigned long long)st.st_size,
                     dims[0], dims[1], (unsigned long long)fileBytes);
        return Result::Io;
    }
    if (!checkMemory(uint64_t(npix) * kBytesPerPixel, memoryLimit, path, error))
        return Result::Io;
    acc->width = dims[0];
    acc->height = dims[1];
    acc->seed = meta[0];
    acc->settingsHash = meta[1];
    acc->nonFinite = meta[2];
    acc->clamped = meta[3];
    acc->samples.resize(npix);
    acc->sum.resize(3 * npix);
    acc->sumSquares.resize(3 * npix);
    if (fread(acc->samples.data(), sizeof(uint32_t), npix, f.get()) != npix ||
        fread(acc->sum.data(), sizeof(__int128), 3 * npix, f.get()) != 3 * npix ||
        fread(acc->sumSquares.data(), sizeof(double), 3 * npix, f.get()) != 3 * npix) {
        *error = path + ": truncated accumulator file";
        return Result::Io;
    }
    return Result::Success;
}

// ---- images ----------------------------------------------------------------------------------

Result writeImage(const std::string &path, uint32_t width, uint32_t height, const std::vector<float> &rgb,
                  float exposure, std::string *error) {
    std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
    for (char &c : ext)
        c = char(std::tolower(c));
    bool hdr = ext == ".exr" || ext == ".hdr";
    rtpbr_tools::ImageWrite image;
    image.width = int(width), image.height = int(height), image.channels = 3;
    std::vector<uint8_t> ldr;
    if (hdr) {
        image.pixels = rgb.data();
        image.attributes = {{"compression", "zip"}};
    } else {
        ldr.resize(rgb.size());
        for (size_t i = 0; i < rgb.size(); i++) {
            float v = std::min(std::max(rgb[i] * exposure, 0.0f), 1.0f);
            // IEC 61966-2-1 sRGB encoding.
            v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
            ldr[i] = uint8_t(std::lround(v * 255.0f));
        }
        image.pixels = ldr.data();
        image.pixel_type = image.file_type = rtpbr_tools::PixelType::UInt8;
    }
    image.attributes.push_back({"DateTime", ""}); // no write date: the same render gives a byte-identical file
    if (!rtpbr_tools::write_image(path, image, *error))
        return Result::Io;
    return Result::Success;
}

} // namespace rtpbr_oracle
