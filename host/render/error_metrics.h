// Error of a rendered image against a reference: the numbers of `vkpath render --reference REF`
// (docs/performance.md "Measuring one render"), and the CSV log of `--error-log`.
#pragma once
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/image.h"

namespace vkp {

/// The epsilon of relMSE's denominator: relmse = mean((x - y)^2 / (y^2 + kRelMseEpsilon)), the
/// relative MSE of the adaptive-rendering literature (e.g. Rousselle, Knaus and Zwicker, "Adaptive
/// sampling and reconstruction using greedy error minimization", 2011). It keeps black reference
/// pixels from dividing by zero and weighs errors in dark regions as the eye does.
inline constexpr double kRelMseEpsilon = 0.01;

/// Errors of an image x against a reference y, both linear radiance. Every mean runs over all
/// pixels and the three channels (3 * width * height values), in double precision.
struct ErrorMetrics {
    double rmse = 0.0;    ///< sqrt(mean((x - y)^2)), in radiance units
    double relmse = 0.0;  ///< mean((x - y)^2 / (y^2 + kRelMseEpsilon)), dimensionless
    double mean[3] = {0.0, 0.0, 0.0};  ///< mean of x per channel (R, G, B): shows a bias at a glance
};

/// The errors of `image` against `reference`. Throws std::invalid_argument if their sizes differ or
/// either is empty (callers check sizes first and report them as input errors).
ErrorMetrics computeErrorMetrics(const Image& image, const Image& reference);

/// Reads a reference image (.exr, .pfm or .hdr) and checks it: the size must be width x height and
/// every value finite. Throws InputError "<path>: ..." with the sizes (or the first bad pixel)
/// otherwise, or if the file cannot be read.
Image readReferenceImage(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height);

/// The CSV log of `--error-log`: a header row `spp,seconds,rmse,relmse,mean_r,mean_g,mean_b`, then
/// one row per append(). The file is created (truncated) by the constructor and every row is flushed
/// as soon as it is written, so a killed render keeps the rows so far; unlike images it is NOT
/// written atomically (a log that appears only at the end would lose them).
class ErrorLog {
public:
    /// Creates `path` and writes the header. Throws InputError "<path>: cannot create: <reason>".
    /// `denoised`: the rows also hold the denoised image's errors (errorLogDenoisedColumns).
    explicit ErrorLog(const std::filesystem::path& path, bool denoised = false);
    ~ErrorLog();
    ErrorLog(const ErrorLog&) = delete;
    ErrorLog& operator=(const ErrorLog&) = delete;

    /// Appends one row: `seconds` is wall time since the process started (s). Throws InputError
    /// "<path>: write failed: <reason>" on an I/O error.
    void append(std::uint32_t spp, double seconds, const ErrorMetrics& m);
    /// A row of a log with denoised columns: `denoised` are the denoised image's errors, made
    /// `denoiseSeconds` after `seconds`.
    void append(std::uint32_t spp, double seconds, const ErrorMetrics& m, const ErrorMetrics& denoised, double denoiseSeconds);
    std::size_t rows() const { return rows_; }

private:
    void writeLine(const std::string& line);
    std::filesystem::path path_;
    std::FILE* file_ = nullptr;
    std::size_t rows_ = 0;
    bool denoised_ = false;
};

/// The columns a log with denoised images adds: ",rmse_denoised,relmse_denoised,denoise_seconds"
/// (the denoised image is ready at seconds + denoise_seconds; it is biased, the raw one is not).
const char* errorLogDenoisedColumns();

/// The header row of the error log (without the newline).
const char* errorLogHeader();

/// One CSV row of the error log (without the newline), e.g. "16,2.500000,0.0123,0.00456,0.16,0.15,0.14".
std::string errorLogRow(std::uint32_t spp, double seconds, const ErrorMetrics& m);

}  // namespace vkp
