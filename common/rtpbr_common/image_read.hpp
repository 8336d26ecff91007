// Image reading (OpenImageIO) of rtpbr-diff, the viewer, the Monte Carlo bench, the bad-input
// tests and the fuzzer (fuzz/fuzz_image.cpp): one function, so each exercises what the others run.
#pragma once

#include <string>
#include <vector>

namespace rtpbr {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // linear
};

// Largest image read (width × height): 8192 × 8192. rtpbr-diff keeps about 30 floats per pixel
// of the two images, so this bounds its memory to a few GB; past it read_image fails with a
// message instead of letting a corrupt or hostile header claim arbitrary memory.
constexpr long long kMaxImagePixels = 1LL << 26;

struct ImageReadOptions {
    // Silences the codecs' own stderr chatter (libpng) while reading; OpenImageIO also
    // returns it through geterror(), which is reported. The fuzzer turns it off so that
    // sanitizer reports stay visible.
    bool quiet = true;
    // Images with more pixels are refused (see kMaxImagePixels); 0 = kMaxImagePixels.
    long long max_pixels = kMaxImagePixels;
};

// The size read_image would return, from the header alone, after the same checks (regular
// file, container sizes, pixel limit): no pixel is read, so a caller can count its memory
// need first. On failure returns false with a one-sentence reason in error.
bool read_image_size(const std::string& path, int& width, int& height, std::string& error,
                     const ImageReadOptions& options = ImageReadOptions());

// Reads PNG, JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PNM/PFM (recognised by their signatures, so a
// misnamed file reads) and TGA (by its .tga extension) into linear RGB; other formats are refused
// with a message (OpenImageIO's other readers never run). Integer formats are taken as sRGB and
// decoded, float formats as linear, grey is replicated, alpha and extra channels ignored.
// Memory: the image's floats plus at most 20 MiB of rows in flight (scanline files), or one
// tile's (tiled files; a tile larger than both the image and 256 x 256 pixels is refused).
// On failure returns false with a one-sentence reason in error.
bool read_image(const std::string& path, Image& image, std::string& error,
                const ImageReadOptions& options = ImageReadOptions());

}  // namespace rtpbr
