// The setting descriptions (include/hmblur/setting.h): each table reads, applies, checks and shows its
// settings consistently; the render's descriptions (the command line's options) come from them;
// the hybrid's settings contain the blur they extend; every filter in the registry builds.
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/hybrid_settings.h"
#include "hmblur/post_process_filter.h"
#include "hmblur/post_process_settings.h"
#include "hmblur/renderer.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/reference_stage.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

std::vector<std::string> splitNames(const std::string& accepts) {
  std::vector<std::string> names;
  size_t start = 0;
  for (size_t bar = accepts.find('|'); bar != std::string::npos; bar = accepts.find('|', start)) {
    names.push_back(accepts.substr(start, bar - start));
    start = bar + 1;
  }
  names.push_back(accepts.substr(start));
  return names;
}

void expectOneLineErrorNaming(const std::function<void()>& f, const std::string& name, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << what << " was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(name), std::string::npos) << what << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << what << ": " << message;
  }
}

// Every setting of a table: its defaults pass its check; text that is no value of it fails to
// read, naming it; each name of a named setting reads, applies and shows as itself; a number
// read outside its range (NaN, or past a finite end) is caught by the check, naming it.
template <class Choices, class Settings>
void expectTableConsistent(const settings::Table<Choices, Settings>& table, const Settings& defaults) {
  std::set<std::string_view> names;
  for (const auto& setting : table) {
    SCOPED_TRACE(std::string(setting.name));
    EXPECT_TRUE(names.insert(setting.name).second) << "named twice";
    EXPECT_FALSE(setting.help.empty());
    EXPECT_FALSE(setting.methods.empty());
    EXPECT_FALSE(setting.defaultText.empty());
    EXPECT_EQ(setting.problem(defaults), "");
    if (setting.flag) {
      Choices choices{};
      setting.read(choices, "true");
      Settings applied = defaults;
      setting.apply(choices, applied);
      EXPECT_EQ(setting.show(applied), "on");
      continue;
    }
    if (setting.valueName == "FILE") continue;
    Choices junk{};
    expectOneLineErrorNaming([&] { setting.read(junk, "not-a-value"); }, std::string(setting.name), "junk text");
    if (setting.valueName == "NAME") {
      for (const std::string& name : splitNames(setting.accepts)) {
        Choices choices{};
        setting.read(choices, name);
        Settings applied = defaults;
        setting.apply(choices, applied);
        EXPECT_EQ(setting.show(applied), name);
        EXPECT_EQ(setting.problem(applied), "");
      }
      continue;
    }
    // Numbers: a choice not made leaves the default; NaN reads (it is a number) but never passes.
    Settings untouched = defaults;
    setting.apply(Choices{}, untouched);
    EXPECT_EQ(setting.show(untouched), setting.show(defaults));
    if (setting.valueName == "X") {
      Choices choices{};
      setting.read(choices, "nan");
      Settings applied = defaults;
      setting.apply(choices, applied);
      const std::string problem = setting.problem(applied);
      EXPECT_NE(problem.find(setting.name), std::string::npos) << problem;
    } else {
      Choices choices{};
      expectOneLineErrorNaming([&] { setting.read(choices, "-1"); }, std::string(setting.name), "a negative count");
      expectOneLineErrorNaming([&] { setting.read(choices, "1.5"); }, std::string(setting.name), "a fraction");
    }
  }
}

TEST(SettingTablesTest, EveryTableIsConsistent) {
  expectTableConsistent(passes::postProcessSettingTable(), passes::PostProcessSettings{});
  expectTableConsistent(passes::hybridSettingTable(), passes::HybridSettings{});
  expectTableConsistent(passes::referenceSettingTable(), passes::ReferenceSettings{});
}

TEST(SettingTablesTest, RangesAreCheckedAtTheirEnds) {
  const auto& table = passes::postProcessSettingTable();
  const auto find = [&](std::string_view name) {
    for (const auto& s : table)
      if (s.name == name) return &s;
    throw std::runtime_error("no setting " + std::string(name));
  };
  const auto problemWith = [&](std::string_view name, const std::string& text) {
    passes::PostProcessChoices choices;
    find(name)->read(choices, text);
    passes::PostProcessSettings s;
    find(name)->apply(choices, s);
    return find(name)->problem(s);
  };
  EXPECT_EQ(problemWith("samples", "1"), "");
  EXPECT_EQ(problemWith("samples", "255"), "");
  EXPECT_NE(problemWith("samples", "0"), "");
  EXPECT_NE(problemWith("samples", "256"), "");
  EXPECT_EQ(problemWith("neighborhood", "31"), "");
  EXPECT_NE(problemWith("neighborhood", "4"), "");
  EXPECT_NE(problemWith("neighborhood", "33"), "");
  EXPECT_NE(problemWith("soft-z-extent", "0"), "");
  EXPECT_NE(problemWith("soft-z-extent", "inf"), "");
  EXPECT_EQ(problemWith("soft-z-extent", "1e-9"), "");
  EXPECT_NE(problemWith("foreground-boost", "0"), "");
  EXPECT_EQ(problemWith("foreground-boost", "1e6"), "");
  EXPECT_NE(problemWith("foreground-boost", "1.5e6"), "");
}

TEST(SettingTablesTest, HybridSettingsContainTheBlurTheyExtend) {
  const passes::HybridSettings defaults;
  EXPECT_NO_THROW(passes::validate(defaults));
  EXPECT_EQ(defaults.blur.filter, passes::PostProcessFilter::McGuire);
  EXPECT_EQ(defaults.blur.range, passes::GatherRange::Adapted);
  // The hybrid's boost falls with the tile's speed: k / |v_N|, at least 1, |v_N| at least 1 px.
  EXPECT_FALSE(defaults.blur.foregroundBoost);
  EXPECT_EQ(defaults.blur.foregroundBoostPixels, passes::kHybridForegroundBoostPixels);
  EXPECT_EQ(defaults.blur.foregroundBoostAt(8.0f), passes::kHybridForegroundBoostPixels / 8.0f);
  EXPECT_EQ(defaults.blur.foregroundBoostAt(0.25f), passes::kHybridForegroundBoostPixels);
  EXPECT_EQ(defaults.blur.foregroundBoostAt(1e6f), 1.0f);
  EXPECT_EQ(passes::PostProcessSettings{}.foregroundBoostAt(8.0f), 30.0f);  // post-process: the paper's constant
  // With K time slices the boost follows the whole shutter's blur: k / K against a slice's |v_N|.
  passes::PostProcessSettings sliced = defaults.blur;
  sliced.timeSlices = 4;
  EXPECT_EQ(sliced.foregroundBoostPixelsPerSlice(), passes::kHybridForegroundBoostPixels / 4.0f);
  EXPECT_EQ(sliced.foregroundBoostAt(5.0f), passes::kHybridForegroundBoostPixels / 20.0f);
  EXPECT_EQ(passes::gatherParams(sliced, 64, 36).foregroundBoostPixels, passes::kHybridForegroundBoostPixels / 4.0f);
  EXPECT_EQ(passes::gatherParams(passes::PostProcessSettings{}, 64, 36).foregroundBoostPixels, 0.0f);

  scene::Settings scene;
  scene.softZExtent = 0.25f;
  scene.edgeThreshold = 0.5f;
  scene.fps = 30.0f;
  const passes::HybridSettings fromScene = passes::HybridSettings::fromScene(scene);
  EXPECT_EQ(fromScene.blur.softZExtent, 0.25f);
  EXPECT_EQ(fromScene.blur.fps, 30.0f);
  EXPECT_EQ(fromScene.edgeThreshold, 0.5f);
  EXPECT_EQ(fromScene.blur.foregroundBoostPixels, passes::kHybridForegroundBoostPixels);
  EXPECT_FALSE(fromScene.blur.foregroundBoost);

  const std::vector<std::pair<std::string, std::function<void(passes::HybridSettings&)>>> absurd = {
      {"mask-background-boost", [](auto& s) { s.maskBackgroundBoost = -3.0f; }},
      {"mask-foreground-divide", [](auto& s) { s.maskForegroundDivide = 0.0f; }},
      {"edge-threshold", [](auto& s) { s.edgeThreshold = 1.0f; }},
      {"max-recursion", [](auto& s) { s.maxRecursion = 65; }},
      {"McGuire", [](auto& s) { s.blur.filter = passes::PostProcessFilter::Jimenez; }},
      {"adapted", [](auto& s) { s.blur.range = passes::GatherRange::Centered; }},
      {"samples", [](auto& s) { s.blur.samples = 0; }},
      {"foreground-boost-pixels", [](auto& s) { s.blur.foregroundBoostPixels = 0.0f; }},
      {"exclude each other", [](auto& s) { s.blur.foregroundBoost = 3.0f; }},
  };
  for (const auto& [name, breakIt] : absurd) {
    passes::HybridSettings s;
    breakIt(s);
    expectOneLineErrorNaming([&] { passes::validate(s); }, name, name);
  }
  passes::HybridSettings weightsCentred;
  weightsCentred.composite = passes::HybridComposite::Weights;
  weightsCentred.blur.range = passes::GatherRange::Centered;
  EXPECT_NO_THROW(passes::validate(weightsCentred));
}

TEST(SettingTablesTest, RenderDescriptionsComeFromTheTables) {
  const std::vector<RenderSettingDescription> descriptions = renderSettingDescriptions();
  std::set<std::string> names;
  for (const RenderSettingDescription& d : descriptions) EXPECT_TRUE(names.insert(d.name).second) << d.name;
  size_t tableSettings = 0;
  std::set<std::string_view> tableNames;
  for (const auto& s : passes::postProcessSettingTable()) tableNames.insert(s.name), ++tableSettings;
  for (const auto& s : passes::hybridSettingTable()) tableNames.insert(s.name), ++tableSettings;
  for (const auto& s : passes::referenceSettingTable()) tableNames.insert(s.name), ++tableSettings;
  EXPECT_EQ(names.size(), tableNames.size());

  const auto describe = [&](const std::string& name) -> const RenderSettingDescription& {
    for (const RenderSettingDescription& d : descriptions)
      if (d.name == name) return d;
    throw std::runtime_error("no description " + name);
  };
  // Defaults in the help are the structs' own.
  EXPECT_NE(describe("samples").help.find("default " + std::to_string(passes::PostProcessSettings{}.samples)),
            std::string::npos);
  EXPECT_NE(describe("spp").help.find("default " + std::to_string(passes::ReferenceSettings{}.samplesPerPixel)),
            std::string::npos);
  // The hybrid's own default of a blur setting is said where it differs.
  EXPECT_NE(describe("foreground-boost-pixels")
                .help.find("hybrid " + settings::formatNumber(passes::kHybridForegroundBoostPixels)),
            std::string::npos)
      << describe("foreground-boost-pixels").help;
  for (const passes::FilterDescription& filter : passes::kFilters)
    EXPECT_NE(describe("filter").help.find(std::string(filter.name)), std::string::npos);

  // One name in several tables reads into each.
  RenderSettings settings;
  describe("seed").read(settings, "77");
  EXPECT_EQ(settings.postprocess.seed, 77u);
  EXPECT_EQ(settings.reference.seed, 77u);
  describe("filter").read(settings, "jimenez");
  EXPECT_EQ(settings.postprocess.filter, passes::PostProcessFilter::Jimenez);
  describe("reveal-stop").read(settings, "luminance");
  EXPECT_EQ(settings.hybrid.stop, passes::RevealStop::Luminance);
  describe("pixel-jitter").read(settings, "true");
  EXPECT_TRUE(settings.reference.pixelJitter);
  expectOneLineErrorNaming([&] { describe("samples").read(settings, "15x"); }, "samples", "15x");
}

// A chosen tile size is taken as it is; else it is the filter's, scaled with the image height.
TEST(SettingTablesTest, TileSizesFollowTheFilterAndTheImage) {
  scene::Scene scene;
  scene.settings.softZExtent = 0.1f;
  RenderSettings settings;
  settings.height = 1440;
  for (const passes::FilterDescription& filter : passes::kFilters) {
    settings.postprocess.filter = filter.filter;
    EXPECT_EQ(postProcessSettingsFor(scene, settings).effectiveTileSize(), 2 * filter.tileSize) << filter.name;
  }
  settings.postprocess.tileSize = 17;
  EXPECT_EQ(postProcessSettingsFor(scene, settings).effectiveTileSize(), 17u);
  EXPECT_EQ(hybridSettingsFor(scene, RenderSettings{}).blur.effectiveTileSize(),
            passes::describe(passes::PostProcessFilter::McGuire).tileSize);
}

using FilterRegistryTest = VulkanTest;

// Every filter has one row, found by its enumerator, and builds a gather with a pass name of
// its own.
TEST_F(FilterRegistryTest, EveryFilterBuilds) {
  std::set<std::string_view> names, passNames;
  for (const passes::FilterDescription& filter : passes::kFilters) {
    EXPECT_EQ(&passes::describe(filter.filter), &filter);
    EXPECT_TRUE(names.insert(filter.name).second);
    EXPECT_GE(filter.tileSize, 1u);
    const std::unique_ptr<passes::GatherFilter> gather = filter.make(context());
    ASSERT_TRUE(gather);
    EXPECT_TRUE(passNames.insert(gather->passName()).second) << gather->passName();
  }
}

}  // namespace
}  // namespace hmb::test
