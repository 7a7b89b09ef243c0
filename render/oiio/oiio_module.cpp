// libknotwork_oiio.so: image output and input through OpenImageIO behind C entry points, so
// that only the processes that write an image or read an environment file load OpenImageIO and
// its 260 dependencies.
#include "render/oiio/image_module.h"

#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cstring>
#include <string>

namespace {

int fail(const std::string& why, char* error, size_t errorSize) {
    if (errorSize > 0) {
        std::strncpy(error, why.c_str(), errorSize - 1);
        error[errorSize - 1] = '\0';
    }
    return 0;
}

} // namespace

extern "C" __attribute__((visibility("default"))) int
kw_oiio_write_image(const KwImageWrite* image, char* error, size_t errorSize) {
    OIIO::ImageSpec spec(image->width, image->height, image->channels,
                         image->isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    if (image->channelNames) {
        spec.channelnames.clear();
        for (int c = 0; c < image->channels; ++c)
            spec.channelnames.emplace_back(image->channelNames[c]);
    }
    if (image->jpegQuality > 0)
        spec.attribute("CompressionQuality", image->jpegQuality);
    if (image->compression)
        spec.attribute("compression", image->compression);
    auto out = OIIO::ImageOutput::create(image->path);
    if (!out)
        return fail("no image writer for this format (" + OIIO::geterror() + ")", error, errorSize);
    if (!out->open(image->path, spec) || !out->write_image(spec.format, image->pixels) ||
        !out->close())
        return fail("could not write image: " + out->geterror(), error, errorSize);
    return 1;
}

extern "C" __attribute__((visibility("default"))) int
kw_oiio_read_image(const KwImageRead* image, char* error, size_t errorSize) {
    auto in = OIIO::ImageInput::open(image->path);
    if (!in)
        return fail("cannot open image (" + OIIO::geterror() + ")", error, errorSize);
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
        return fail("not a 2D image (" + std::to_string(spec.width) + " x " +
                        std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) +
                        " channels)",
                    error, errorSize);
    const int channels = std::min(spec.nchannels, 4);
    const size_t count = size_t(spec.width) * size_t(spec.height) * size_t(channels);
    float* pixels = image->allocate(image->context, count);
    if (!pixels)
        return fail("image too large (" + std::to_string(spec.width) + " x " +
                        std::to_string(spec.height) + ")",
                    error, errorSize);
    // Tiled and scanline files alike; chbegin..chend keeps the first channels only.
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels))
        return fail("cannot decode image: " + in->geterror(), error, errorSize);
    *image->width = spec.width;
    *image->height = spec.height;
    *image->channels = channels;
    return 1;
}
