// libknotwork_oiio.so: image output through OpenImageIO behind a C entry point, so that only
// the processes that write an image load OpenImageIO and its 260 dependencies.
#include "render/oiio/image_module.h"

#include <OpenImageIO/imageio.h>
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
