// Layered EXR files through OpenEXR 3: one FLOAT or UINT channel per layer channel, named
// "<layer>.<channel>", with the beauty layer's channels as plain "R", "G", "B", "A".
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>

#include "hmblur/error.h"
#include "runtime/io/image_files.h"

namespace hmb::io {

namespace {

// hmb::Error messages are printed as one line by the CLI; library messages may hold newlines.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

[[noreturn]] void fail(const char* action, const std::filesystem::path& path,
                       const std::string& reason) {
  throw Error(oneLine(std::string(action) + " EXR '" + path.string() + "': " + reason));
}

std::string fullChannelName(const ImageLayer& layer, const std::string& channel) {
  return layer.name.empty() ? channel : layer.name + "." + channel;
}

void validateForWrite(const std::filesystem::path& path, const LayeredImage& image) {
  if (image.width == 0 || image.height == 0) {
    fail("cannot write", path,
         "image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
             " is empty");
  }
  // OpenEXR addresses pixels with int coordinates.
  constexpr uint32_t kMaxSide = uint32_t(std::numeric_limits<int>::max());
  if (image.width > kMaxSide || image.height > kMaxSide)
    fail("cannot write", path, "image too large");
  if (image.layers.empty()) fail("cannot write", path, "the image has no layers");

  const size_t pixelCount = size_t(image.width) * image.height;
  std::set<std::string> seen;
  for (const ImageLayer& layer : image.layers) {
    const std::string label = layer.name.empty() ? "beauty layer" : "layer '" + layer.name + "'";
    if (layer.channels.empty()) fail("cannot write", path, label + " has no channels");
    for (const std::string& channel : layer.channels) {
      // A '.' in a channel name would move it into another layer when read back.
      if (channel.empty() || channel.find('.') != std::string::npos) {
        fail("cannot write", path, label + " has an invalid channel name '" + channel + "'");
      }
      const std::string full = fullChannelName(layer, channel);
      if (!seen.insert(full).second) fail("cannot write", path, "duplicate channel '" + full + "'");
    }
    const size_t expected = pixelCount * layer.channels.size();
    const size_t actual = layer.isUint ? layer.ids.size() : layer.values.size();
    if (actual != expected) {
      fail("cannot write", path,
           label + " holds " + std::to_string(actual) + " values, expected " +
               std::to_string(expected) + " (" + std::to_string(image.width) + "x" +
               std::to_string(image.height) + "x" + std::to_string(layer.channels.size()) + ")");
    }
  }
}

// Channel order inside a layer on read: the EXR header lists channels alphabetically, so put
// the usual component orders back (R,G,B,A and X,Y,Z,W) and leave anything else alphabetical.
int canonicalRank(std::string_view channel) {
  static constexpr std::array<std::string_view, 8> kOrder = {"R", "G", "B", "A",
                                                             "X", "Y", "Z", "W"};
  const auto it = std::find(kOrder.begin(), kOrder.end(), channel);
  return it == kOrder.end() ? int(kOrder.size()) : int(it - kOrder.begin());
}

struct ChannelRef {
  std::string name;      // within the layer
  std::string fullName;  // in the file
  Imf::PixelType type;
};

}  // namespace

void writeExr(const std::filesystem::path& path, const LayeredImage& image) {
  validateForWrite(path, image);
  try {
    const size_t pixelCount = size_t(image.width) * image.height;
    Imf::Header header(int(image.width), int(image.height));
    header.compression() = Imf::ZIP_COMPRESSION;

    // Float layers are copied so non-finite values can be replaced by 0 without touching the
    // caller's data; the copies must outlive writePixels.
    std::vector<std::vector<float>> finiteValues(image.layers.size());
    Imf::FrameBuffer frameBuffer;
    for (size_t layerIndex = 0; layerIndex < image.layers.size(); ++layerIndex) {
      const ImageLayer& layer = image.layers[layerIndex];
      const size_t channelCount = layer.channels.size();
      const Imf::PixelType type = layer.isUint ? Imf::UINT : Imf::FLOAT;
      const char* base = nullptr;
      if (layer.isUint) {
        base = reinterpret_cast<const char*>(layer.ids.data());
      } else {
        std::vector<float>& finite = finiteValues[layerIndex];
        finite.resize(pixelCount * channelCount);
        std::transform(layer.values.begin(), layer.values.end(), finite.begin(),
                       [](float v) { return std::isfinite(v) ? v : 0.0f; });
        base = reinterpret_cast<const char*>(finite.data());
      }
      const size_t xStride = 4 * channelCount;  // float and uint32 are both 4 bytes
      const size_t yStride = xStride * image.width;
      for (size_t c = 0; c < channelCount; ++c) {
        const std::string full = fullChannelName(layer, layer.channels[c]);
        header.channels().insert(full, Imf::Channel(type));
        frameBuffer.insert(full,
                           Imf::Slice(type, const_cast<char*>(base + 4 * c), xStride, yStride));
      }
    }

    Imf::OutputFile file(path.string().c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(int(image.height));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("cannot write", path, e.what());
  }
}

LayeredImage readExr(const std::filesystem::path& path) {
  // OpenEXR's own message for a missing file is less direct than this.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) fail("cannot read", path, "no such file");
  if (!std::filesystem::is_regular_file(status)) fail("cannot read", path, "not a regular file");

  try {
    Imf::InputFile file(path.string().c_str());
    const Imath::Box2i dataWindow = file.header().dataWindow();
    const int64_t width = int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    const int64_t height = int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width <= 0 || height <= 0) fail("cannot read", path, "empty data window");

    // Group the file's channels into layers by the prefix before the last '.'.
    std::map<std::string, std::vector<ChannelRef>> channelsByLayer;
    const Imf::ChannelList& channels = file.header().channels();
    for (auto it = channels.begin(); it != channels.end(); ++it) {
      const std::string full = it.name();
      const Imf::Channel& channel = it.channel();
      if (channel.xSampling != 1 || channel.ySampling != 1) {
        fail("cannot read", path, "subsampled channel '" + full + "' is not supported");
      }
      const size_t dot = full.rfind('.');
      const std::string layerName = dot == std::string::npos ? "" : full.substr(0, dot);
      const std::string channelName = dot == std::string::npos ? full : full.substr(dot + 1);
      channelsByLayer[layerName].push_back({channelName, full, channel.type});
    }
    if (channelsByLayer.empty()) fail("cannot read", path, "the file has no channels");

    LayeredImage image;
    std::vector<std::vector<std::string>> fileNamesByLayer;  // parallel to image.layers
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    const size_t pixelCount = size_t(width) * size_t(height);
    // std::map orders layers by name, so the beauty layer ("") comes first.
    for (auto& [layerName, refs] : channelsByLayer) {
      std::stable_sort(refs.begin(), refs.end(), [](const ChannelRef& a, const ChannelRef& b) {
        return canonicalRank(a.name) < canonicalRank(b.name);
      });
      const bool isUint = refs.front().type == Imf::UINT;
      for (const ChannelRef& ref : refs) {
        if ((ref.type == Imf::UINT) != isUint) {
          fail("cannot read", path, "layer '" + layerName + "' mixes UINT and float channels");
        }
      }
      ImageLayer& layer = image.layers.emplace_back();
      layer.name = layerName;
      layer.isUint = isUint;
      std::vector<std::string>& fileNames = fileNamesByLayer.emplace_back();
      for (const ChannelRef& ref : refs) {
        layer.channels.push_back(ref.name);
        fileNames.push_back(ref.fullName);
      }
      if (isUint) {
        layer.ids.resize(pixelCount * refs.size());
      } else {
        layer.values.resize(pixelCount * refs.size());
      }
    }

    // Second pass: the layer vector no longer grows, so its buffers can be pointed at.
    Imf::FrameBuffer frameBuffer;
    for (size_t layerIndex = 0; layerIndex < image.layers.size(); ++layerIndex) {
      ImageLayer& layer = image.layers[layerIndex];
      // HALF channels are converted to FLOAT by OpenEXR on read.
      const Imf::PixelType type = layer.isUint ? Imf::UINT : Imf::FLOAT;
      char* base = layer.isUint ? reinterpret_cast<char*>(layer.ids.data())
                                : reinterpret_cast<char*>(layer.values.data());
      const size_t xStride = 4 * layer.channels.size();
      const size_t yStride = xStride * size_t(width);
      for (size_t c = 0; c < layer.channels.size(); ++c) {
        frameBuffer.insert(fileNamesByLayer[layerIndex][c],
                           Imf::Slice::Make(type, base + 4 * c, dataWindow, xStride, yStride));
      }
    }
    file.setFrameBuffer(frameBuffer);
    file.readPixels(dataWindow.min.y, dataWindow.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("cannot read", path, e.what());
  }
}

}  // namespace hmb::io
