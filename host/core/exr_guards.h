// Owners of what tinyexr allocates (Debian's libtinyexr), for every EXR reader and writer of vkpath
// (core/image_exr.cpp, render/accum_file.cpp). Include after <tinyexr.h>.
#pragma once
#include <tinyexr.h>

#include <string>

namespace vkp::exr {

/// The error string tinyexr may allocate.
struct ExrError {
    const char* msg = nullptr;
    ExrError() = default;
    ExrError(const ExrError&) = delete;
    ExrError& operator=(const ExrError&) = delete;
    ~ExrError() {
        if (msg) FreeEXRErrorMessage(msg);
    }
    /// The message, with tinyexr's return code when it is not 0.
    std::string text(int code = 0) const {
        return (msg ? std::string(msg) : std::string("error")) + (code ? " (tinyexr code " + std::to_string(code) + ")" : "");
    }
};

/// A parsed header (FreeEXRHeader on destruction).
struct HeaderGuard {
    EXRHeader h;
    HeaderGuard() { InitEXRHeader(&h); }
    HeaderGuard(const HeaderGuard&) = delete;
    HeaderGuard& operator=(const HeaderGuard&) = delete;
    ~HeaderGuard() { FreeEXRHeader(&h); }
};

/// Decoded pixels (FreeEXRImage on destruction).
struct ImageGuard {
    EXRImage i;
    ImageGuard() { InitEXRImage(&i); }
    ImageGuard(const ImageGuard&) = delete;
    ImageGuard& operator=(const ImageGuard&) = delete;
    ~ImageGuard() { FreeEXRImage(&i); }
};

}  // namespace vkp::exr
