// The C interface between render/image_writer.cpp, render/image_reader.cpp and
// libknotwork_oiio.so, the module that holds OpenImageIO (260 shared libraries), loaded only
// when an image is written or a file image (an environment map) is read.
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

/// Storage for a decoded image, provided by the caller so that memory never crosses the
/// module's allocator: returns room for `count` floats (null to give up, e.g. too large).
using KwImageAllocFn = float* (*)(void* context, size_t count);

/// One image to read: the first subimage of `path` in any format OpenImageIO reads (EXR, HDR,
/// PNG, JPEG, TIFF, ...). On success *width, *height and *channels (1..4: the file's first
/// channels, e.g. RGB of RGBA) are set and width * height * channels floats, rows top first,
/// were written to the buffer from `allocate`; 8/16-bit files are scaled to [0, 1].
struct KwImageRead {
    const char* path;
    KwImageAllocFn allocate;
    void* context;
    int* width;
    int* height;
    int* channels;
};

/// Reads the image. Returns 1 on success, 0 with a NUL-terminated message (naming neither the
/// path nor the module) in error[0..errorSize).
using KwImageReadFn = int (*)(const KwImageRead* image, char* error, size_t errorSize);

/// The read entry libknotwork_oiio.so exports.
#define KW_IMAGE_READ_SYMBOL "kw_oiio_read_image"

} // extern "C"
