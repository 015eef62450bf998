#include "runtime/metrics/error_sources.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hmblur/error.h"

namespace hmb::metrics {
namespace {

// The largest value within `reach` pixels along x, then along y (a square window); infinity
// (a point behind the camera) is kept, and NaN counts as infinity.
std::vector<float> squareMax(std::span<const float> values, uint32_t width, uint32_t height, uint32_t reach) {
  // One axis: `count` positions `step` apart in each line.
  const auto along = [&](std::span<const float> in, uint32_t count, size_t step, size_t lineStep, uint32_t lines) {
    std::vector<float> out(in.size());
    for (uint32_t line = 0; line < lines; ++line)
      for (uint32_t at = 0; at < count; ++at) {
        float m = 0.0f;
        for (uint32_t k = at > reach ? at - reach : 0; k <= std::min(count - 1, at + reach); ++k)
          m = std::max(m, std::isnan(in[line * lineStep + k * step]) ? INFINITY : in[line * lineStep + k * step]);
        out[line * lineStep + at * step] = m;
      }
    return out;
  };
  const std::vector<float> rows = along(values, width, 1, width, height);
  return along(rows, height, width, 1, width);
}

double pixelSquaredError(const DisplayImage& a, const DisplayImage& b, size_t i) {
  double sum = 0.0;
  for (size_t c = 0; c < 3; ++c) {
    const double d = double(a.rgb[3 * i + c]) - double(b.rgb[3 * i + c]);
    sum += d * d;
  }
  return sum / 3.0;
}

}  // namespace

const char* errorSourceName(ErrorSource source) {
  switch (source) {
    case ErrorSource::Outside: return "outside";
    case ErrorSource::CurvedPath: return "curved-path";
    case ErrorSource::InnerTraced: return "inner-traced";
    case ErrorSource::InnerNotTraced: return "inner-not-traced";
    case ErrorSource::OuterBlur: return "outer-blur";
    case ErrorSource::Other: return "other";
  }
  return "?";
}

std::array<uint8_t, 3> errorSourceColor(ErrorSource source) {
  switch (source) {
    case ErrorSource::Outside: return {0, 0, 0};
    case ErrorSource::CurvedPath: return {255, 150, 0};      // orange
    case ErrorSource::InnerTraced: return {40, 200, 70};      // green
    case ErrorSource::InnerNotTraced: return {50, 110, 255};  // blue
    case ErrorSource::OuterBlur: return {230, 40, 200};       // magenta
    case ErrorSource::Other: return {235, 235, 235};          // near white
  }
  return {0, 0, 0};
}

// Each class's row is rows[class - 1]: kErrorSources lists the classes in their order.
static_assert(size_t(kErrorSources.front()) == 1 && size_t(kErrorSources.back()) == kErrorSources.size());

ErrorSources explainErrorSources(const ErrorSourceInputs& in, const ErrorSourceSettings& settings) {
  if (!in.reference || !in.test || !in.region) throw Error("error sources: the reference, test and region are required");
  const uint32_t width = in.reference->width, height = in.reference->height;
  const size_t pixels = size_t(width) * height;
  const auto sized = [&](size_t n) { return n == pixels; };
  if (in.test->width != width || in.test->height != height || !sized(in.region->inside.size()) ||
      !sized(in.pathLength.size()) || !sized(in.pathBend.size()) || !(in.rayMask.empty() || sized(in.rayMask.size())) ||
      !(in.referenceNoise.empty() || sized(in.referenceNoise.size())))
    throw Error("error sources: the images, region, paths, mask and noise must be " + std::to_string(width) + "x" +
                std::to_string(height));
  ErrorSources out;
  out.width = width;
  out.height = height;
  float longest = 0.0f;
  for (const float l : in.pathLength)
    if (std::isfinite(l)) longest = std::max(longest, l);
  out.reachPixels = std::min(settings.maxReachPixels, static_cast<uint32_t>(std::ceil(longest)));
  const std::vector<float> lengthNear = squareMax(in.pathLength, width, height, out.reachPixels);
  const std::vector<float> bendNear = squareMax(in.pathBend, width, height, out.reachPixels);

  out.perPixel.assign(pixels, ErrorSource::Outside);
  for (const ErrorSource s : kErrorSources) {
    ErrorSourceRow row;
    row.source = s;
    if (!in.referenceNoise.empty()) row.noise = 0.0;
    out.rows.push_back(row);
  }
  if (!in.referenceNoise.empty()) out.noise = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    if (!in.region->inside[i]) continue;
    ErrorSource s = ErrorSource::Other;
    if (!(bendNear[i] <= settings.bendPixels))
      s = ErrorSource::CurvedPath;
    else if (in.pathLength[i] >= settings.movingPixels)
      s = !in.rayMask.empty() && in.rayMask[i] != 0u ? ErrorSource::InnerTraced : ErrorSource::InnerNotTraced;
    else if (lengthNear[i] >= settings.movingPixels)
      s = ErrorSource::OuterBlur;
    out.perPixel[i] = s;
    const double error = pixelSquaredError(*in.reference, *in.test, i);
    ErrorSourceRow& row = out.rows[size_t(s) - 1];
    ++row.pixels;
    row.squaredError += error;
    ++out.regionPixels;
    out.squaredError += error;
    if (!in.referenceNoise.empty()) {
      *row.noise += in.referenceNoise[i];
      *out.noise += in.referenceNoise[i];
    }
  }
  for (ErrorSourceRow& row : out.rows) row.share = out.squaredError > 0.0 ? row.squaredError / out.squaredError : 0.0;
  return out;
}

std::vector<float> referenceNoise(const DisplayImage& a, const DisplayImage& b) {
  if (a.width != b.width || a.height != b.height) throw Error("reference noise: the two halves differ in size");
  std::vector<float> noise(a.pixelCount());
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<float>(pixelSquaredError(a, b, i) / 4.0);
  return noise;
}

io::Rgba8Image errorSourceImage(const ErrorSources& sources, const DisplayImage& reference) {
  if (reference.width != sources.width || reference.height != sources.height)
    throw Error("error sources: the reference is not the sources' size");
  io::Rgba8Image image{.width = sources.width, .height = sources.height};
  image.pixels.resize(size_t(sources.width) * sources.height * 4);
  for (size_t i = 0; i < sources.perPixel.size(); ++i) {
    const ErrorSource s = sources.perPixel[i];
    if (s == ErrorSource::Outside) {
      const float luma =
          0.2126f * reference.rgb[3 * i] + 0.7152f * reference.rgb[3 * i + 1] + 0.0722f * reference.rgb[3 * i + 2];
      const auto grey = static_cast<uint8_t>(std::lround(std::clamp(luma, 0.0f, 1.0f) * 90.0f));
      image.pixels[4 * i] = image.pixels[4 * i + 1] = image.pixels[4 * i + 2] = grey;
    } else {
      const std::array<uint8_t, 3> color = errorSourceColor(s);
      for (size_t c = 0; c < 3; ++c) image.pixels[4 * i + c] = color[c];
    }
    image.pixels[4 * i + 3] = 255;
  }
  return image;
}

nlohmann::json errorSourcesJson(const ErrorSources& sources) {
  const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json classes = nlohmann::json::array();
  for (const ErrorSourceRow& row : sources.rows)
    classes.push_back({{"class", errorSourceName(row.source)},
                       {"pixels", row.pixels},
                       {"squared_error", row.squaredError},
                       {"share", row.share},
                       {"noise", optional(row.noise)}});
  return {{"reach_pixels", sources.reachPixels},
          {"region_pixels", sources.regionPixels},
          {"squared_error", sources.squaredError},
          {"noise", optional(sources.noise)},
          {"classes", std::move(classes)}};
}

}  // namespace hmb::metrics
