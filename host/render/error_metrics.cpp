#include "render/error_metrics.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/errors.h"
#include "core/image_io.h"

namespace vkp {

ErrorMetrics computeErrorMetrics(const Image& image, const Image& reference) {
    if (image.empty() || reference.empty()) throw std::invalid_argument("computeErrorMetrics: empty image");
    if (image.width != reference.width || image.height != reference.height)
        throw std::invalid_argument("computeErrorMetrics: image " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " against reference " +
                                    std::to_string(reference.width) + "x" + std::to_string(reference.height));
    image.checkConsistent();
    reference.checkConsistent();
    double se = 0.0, rel = 0.0, sum[3] = {0.0, 0.0, 0.0};
    const std::size_t n = image.rgb.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double x = image.rgb[i], y = reference.rgb[i];
        const double d2 = (x - y) * (x - y);
        se += d2;
        rel += d2 / (y * y + kRelMseEpsilon);
        sum[i % 3] += x;
    }
    ErrorMetrics m;
    m.rmse = std::sqrt(se / double(n));
    m.relmse = rel / double(n);
    for (int c = 0; c < 3; ++c) m.mean[c] = sum[c] / double(image.pixelCount());
    return m;
}

Image readReferenceImage(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height) {
    Image ref = readImage(path);
    if (ref.width != width || ref.height != height)
        throw InputError(path.string() + ": reference is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                         " but the render is " + std::to_string(width) + "x" + std::to_string(height) +
                         " (set --width/--height to the reference's size)");
    for (std::size_t i = 0; i < ref.rgb.size(); ++i) {
        if (!std::isfinite(ref.rgb[i])) {
            const std::size_t p = i / 3;
            throw InputError(path.string() + ": reference pixel (" + std::to_string(p % width) + ", " +
                             std::to_string(p / width) + ") is not finite");
        }
    }
    return ref;
}

const char* errorLogHeader() { return "spp,seconds,rmse,relmse,mean_r,mean_g,mean_b"; }

std::string errorLogRow(std::uint32_t spp, double seconds, const ErrorMetrics& m) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%u,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g", spp, seconds, m.rmse, m.relmse, m.mean[0],
                  m.mean[1], m.mean[2]);
    return buf;
}

ErrorLog::ErrorLog(const std::filesystem::path& path, bool denoised) : path_(path), denoised_(denoised) {
    file_ = std::fopen(path.c_str(), "w");
    if (!file_) throw InputError(path.string() + ": cannot create: " + std::strerror(errno));
    writeLine(std::string(errorLogHeader()) + (denoised ? errorLogDenoisedColumns() : ""));
}

const char* errorLogDenoisedColumns() { return ",rmse_denoised,relmse_denoised,denoise_seconds"; }

void ErrorLog::append(std::uint32_t spp, double seconds, const ErrorMetrics& m, const ErrorMetrics& d, double denoiseSeconds) {
    if (!denoised_) throw std::logic_error("ErrorLog::append: a log without denoised columns");
    char buf[96];
    std::snprintf(buf, sizeof buf, ",%.9g,%.9g,%.6f", d.rmse, d.relmse, denoiseSeconds);
    writeLine(errorLogRow(spp, seconds, m) + buf);
    ++rows_;
}

ErrorLog::~ErrorLog() {
    if (file_) std::fclose(file_);
}

void ErrorLog::append(std::uint32_t spp, double seconds, const ErrorMetrics& m) {
    if (denoised_) throw std::logic_error("ErrorLog::append: the log wants the denoised image's errors");
    writeLine(errorLogRow(spp, seconds, m));
    ++rows_;
}

void ErrorLog::writeLine(const std::string& line) {
    // One fwrite of the whole line, then a flush: the line reaches the file in one write(2).
    const std::string l = line + "\n";
    if (std::fwrite(l.data(), 1, l.size(), file_) != l.size() || std::fflush(file_) != 0)
        throw InputError(path_.string() + ": write failed: " + std::strerror(errno));
}

}  // namespace vkp
