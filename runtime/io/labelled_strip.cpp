#include "runtime/io/labelled_strip.h"

#include <algorithm>
#include <memory>
#include <optional>

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include "hmblur/error.h"

namespace hmb::io {
namespace {

constexpr uint8_t kBand = 32, kText = 235;

// The file of the system's best match for "sans-serif", if fontconfig knows any font.
std::optional<std::string> sansSerifFile() {
  FcConfig* config = FcInitLoadConfigAndFonts();
  if (!config) return std::nullopt;
  std::optional<std::string> file;
  FcPattern* pattern = FcNameParse(reinterpret_cast<const FcChar8*>("sans-serif"));
  FcConfigSubstitute(config, pattern, FcMatchPattern);
  FcDefaultSubstitute(pattern);
  FcResult result = FcResultNoMatch;
  if (FcPattern* match = FcFontMatch(config, pattern, &result)) {
    FcChar8* path = nullptr;
    if (FcPatternGetString(match, FC_FILE, 0, &path) == FcResultMatch && path)
      file = std::string(reinterpret_cast<const char*>(path));
    FcPatternDestroy(match);
  }
  FcPatternDestroy(pattern);
  FcConfigDestroy(config);
  return file;
}

class Typesetter {
 public:
  // Null when FreeType or the font cannot be opened.
  static std::unique_ptr<Typesetter> open(uint32_t pixelHeight) {
    const std::optional<std::string> file = sansSerifFile();
    if (!file) return nullptr;
    auto typesetter = std::unique_ptr<Typesetter>(new Typesetter);
    if (FT_Init_FreeType(&typesetter->library_) != 0) return nullptr;
    if (FT_New_Face(typesetter->library_, file->c_str(), 0, &typesetter->face_) != 0) return nullptr;
    if (FT_Set_Pixel_Sizes(typesetter->face_, 0, pixelHeight) != 0) return nullptr;
    return typesetter;
  }
  ~Typesetter() {
    if (face_) FT_Done_Face(face_);
    if (library_) FT_Done_FreeType(library_);
  }
  Typesetter(const Typesetter&) = delete;
  Typesetter& operator=(const Typesetter&) = delete;

  // Draws `text` (bytes above 126 as '?') with its baseline at y, from x, clipped to
  // [x, right) and to the image.
  void draw(Rgba8Image& image, int x, int baseline, int right, const std::string& text) const {
    int penX = x;
    for (char byte : text) {
      const unsigned char c = byte >= 32 && byte <= 126 ? static_cast<unsigned char>(byte) : '?';
      if (FT_Load_Char(face_, c, FT_LOAD_RENDER) != 0) continue;
      const FT_GlyphSlot glyph = face_->glyph;
      const FT_Bitmap& bitmap = glyph->bitmap;
      for (unsigned row = 0; row < bitmap.rows; ++row)
        for (unsigned col = 0; col < bitmap.width; ++col) {
          const int px = penX + glyph->bitmap_left + int(col), py = baseline - glyph->bitmap_top + int(row);
          if (px < x || px >= right || px < 0 || py < 0 || px >= int(image.width) || py >= int(image.height)) continue;
          const unsigned coverage = bitmap.buffer[row * unsigned(bitmap.pitch) + col];
          uint8_t* pixel = image.pixels.data() + (size_t(py) * image.width + size_t(px)) * 4;
          for (int ch = 0; ch < 3; ++ch)
            pixel[ch] = uint8_t((pixel[ch] * (255 - coverage) + kText * coverage + 127) / 255);
        }
      penX += int(glyph->advance.x >> 6);
      if (penX >= right) break;
    }
  }

 private:
  Typesetter() = default;
  FT_Library library_ = nullptr;
  FT_Face face_ = nullptr;
};

}  // namespace

LabelledStrip labelledStrip(const std::vector<CaptionedImage>& panels) {
  LabelledStrip strip;
  if (panels.empty()) return strip;
  const uint32_t width = panels[0].image.width, height = panels[0].image.height;
  for (const CaptionedImage& panel : panels)
    if (panel.image.width != width || panel.image.height != height || panel.image.pixels.size() != size_t(width) * height * 4)
      throw Error("a labelled strip takes images of one size");
  size_t lines = 1;
  for (const CaptionedImage& panel : panels) lines = std::max(lines, panel.caption.size());
  // Text a twentieth of the image's height, readable from 9 pixels up.
  const uint32_t textPixels = std::clamp<uint32_t>(height / 20, 9, 40);
  const uint32_t lineHeight = textPixels * 5 / 4, margin = std::max<uint32_t>(2, textPixels / 3);
  const uint32_t band = uint32_t(lines) * lineHeight + 2 * margin;
  strip.image.width = width * uint32_t(panels.size());
  strip.image.height = height + band;
  strip.image.pixels.assign(size_t(strip.image.width) * strip.image.height * 4, 255);
  for (size_t i = 0; i < panels.size(); ++i)
    for (uint32_t y = 0; y < strip.image.height; ++y) {
      uint8_t* row = strip.image.pixels.data() + (size_t(y) * strip.image.width + i * width) * 4;
      if (y < height) {
        std::copy_n(panels[i].image.pixels.begin() + size_t(y) * width * 4, size_t(width) * 4, row);
      } else {
        for (uint32_t x = 0; x < width; ++x) {
          row[x * 4 + 0] = row[x * 4 + 1] = row[x * 4 + 2] = kBand;
          row[x * 4 + 3] = 255;
        }
      }
    }
  const std::unique_ptr<Typesetter> typesetter = Typesetter::open(textPixels);
  if (!typesetter) return strip;
  strip.captioned = true;
  for (size_t i = 0; i < panels.size(); ++i) {
    const int left = int(i * width + margin), right = int((i + 1) * width - margin);
    for (size_t line = 0; line < panels[i].caption.size(); ++line) {
      const int baseline = int(height + margin + (line + 1) * lineHeight - lineHeight / 5);
      typesetter->draw(strip.image, left, baseline, right, panels[i].caption[line]);
    }
  }
  return strip;
}

}  // namespace hmb::io
