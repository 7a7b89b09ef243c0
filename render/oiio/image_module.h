// The C interface between render/image_writer.cpp and libknotwork_oiio.so, the module that
// holds OpenImageIO (260 shared libraries), loaded only when an image is written.
#pragma once

#include <cstddef>

extern "C" {

/// One image to write. `pixels`: width * height * channels values, rows top first, unsigned
/// bytes (isFloat 0) or 32-bit floats (isFloat 1). `channelNames`: null for OIIO's defaults, or
/// `channels` names. `jpegQuality`: 0 for the writer's default. `compression`: null for the
/// default, else an OIIO "compression" attribute (e.g. "zip").
struct KwImageWrite {
    const char* path;
    int width;
    int height;
    int channels;
    int isFloat;
    const void* pixels;
    const char* const* channelNames;
    int jpegQuality;
    const char* compression;
};

/// Writes the image with the format its path's extension names. Returns 1 on success, 0 with a
/// NUL-terminated message (naming neither the path nor the module) in error[0..errorSize).
using KwImageWriteFn = int (*)(const KwImageWrite* image, char* error, size_t errorSize);

/// The symbol libknotwork_oiio.so exports.
#define KW_IMAGE_WRITE_SYMBOL "kw_oiio_write_image"

} // extern "C"
