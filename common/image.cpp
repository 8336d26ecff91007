// rtpbr common: writing images through OpenImageIO (see rtpbr_common/image.hpp).
#include "rtpbr_common/image.hpp"

#include <OpenImageIO/imageio.h>

namespace rtpbr_tools {

namespace {

OIIO::TypeDesc type_desc(PixelType t) {
    switch (t) {
    case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelType::Half: return OIIO::TypeDesc::HALF;
    case PixelType::Float: return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::UNKNOWN;
}

} // namespace

bool write_image(const std::string &path, const ImageWrite &image, std::string &error) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 || !image.pixels ||
        image.pixel_type == PixelType::Half) {
        error = "cannot write " + path + ": invalid image (size " + std::to_string(image.width) + " x " +
                std::to_string(image.height) + ", " + std::to_string(image.channels) + " channels)";
        return false;
    }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        error = "cannot write " + path + ": " + OIIO::geterror();
        return false;
    }
    OIIO::ImageSpec spec(image.width, image.height, image.channels, type_desc(image.file_type));
    if (!image.channel_names.empty())
        spec.channelnames = image.channel_names;
    for (const auto &[name, value] : image.attributes)
        spec.attribute(name, value);
    if (!out->open(path, spec)) {
        error = "cannot write " + path + ": " + out->geterror();
        return false;
    }
    const bool written = out->write_image(type_desc(image.pixel_type), image.pixels);
    const bool closed = out->close();
    if (!written || !closed) {
        error = "cannot write " + path + ": " + out->geterror();
        return false;
    }
    return true;
}

bool write_image_u8(const std::string &path, int width, int height, int channels, const uint8_t *pixels,
                    std::string &error) {
    ImageWrite image;
    image.width = width, image.height = height, image.channels = channels, image.pixels = pixels;
    image.pixel_type = image.file_type = PixelType::UInt8;
    return write_image(path, image, error);
}

bool write_image_float(const std::string &path, int width, int height, int channels, const float *pixels,
                       std::string &error) {
    ImageWrite image;
    image.width = width, image.height = height, image.channels = channels, image.pixels = pixels;
    return write_image(path, image, error);
}

} // namespace rtpbr_tools
