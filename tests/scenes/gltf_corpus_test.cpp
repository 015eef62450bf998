// The committed corpus of malformed glTF files (tests/scenes/malformed/, written by its
// generate.py; the loader's fuzzer starts from it too): every file is a one-line hmb::Error
// that starts with the path, never a crash or a scene.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "tests/scenes/malformed_corpus.h"

namespace hmb::scene {
namespace {

TEST(GltfCorpusTest, EveryMalformedFileIsAOneLineError) {
  const std::vector<std::filesystem::path> files = test::malformedCorpusFiles();
  ASSERT_GE(files.size(), test::kMalformedCorpusMinFiles)
      << "the corpus is missing: run tests/scenes/malformed/generate.py";
  for (const std::filesystem::path& path : files) {
    try {
      (void)loadScene(path.string());
      ADD_FAILURE() << path.filename() << " loaded; every corpus file is malformed";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path.string(), 0), 0u) << path.filename() << ": " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << path.filename() << ": " << message;
      EXPECT_GT(message.size(), path.string().size() + 4) << path.filename() << ": says nothing";
    } catch (const std::exception& e) {
      ADD_FAILURE() << path.filename() << " threw something other than hmb::Error: " << e.what();
    }
  }
}

}  // namespace
}  // namespace hmb::scene
