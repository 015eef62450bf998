// A reference split into shards and merged from the command line: render --shard I/K writes a
// part (its checkpoint), merge joins the parts into the file a single render writes, byte for
// byte; wrong shards and wrong parts are one line each.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/cli_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

const std::string kReference = "--quiet render --scene living-room --method reference --width 64 --height 36 --spp 8";

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string part(const fs::path& dir, int i) { return (dir / ("part-" + std::to_string(i) + ".hmbpart")).string(); }

TEST(ShardMergeCliTest, ShardsMergeIntoTheSingleRendersFile) {
  const fs::path dir = tempDir("shard_merge");
  ASSERT_EQ(hmblur(kReference + " --out " + (dir / "single.exr").string()).exitCode, 0);
  for (int i = 0; i < 3; ++i) {
    const CliRun run = hmblur(kReference + " --shard " + std::to_string(i) + "/3 --out " + part(dir, i));
    ASSERT_EQ(run.exitCode, 0) << run.output;
  }
  // The same command again finds its part finished and leaves it as it was.
  const std::string before = bytesOf(part(dir, 1));
  ASSERT_EQ(hmblur(kReference + " --shard 1/3 --out " + part(dir, 1)).exitCode, 0);
  EXPECT_EQ(bytesOf(part(dir, 1)), before);

  const CliRun run = hmblur("merge " + part(dir, 2) + " " + part(dir, 0) + " " + part(dir, 1) + " --out " +
                            (dir / "merged.exr").string() + " --report " + (dir / "merge.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("merge: 3 of 3 shards, 8 of 8 samples per pixel"), std::string::npos) << run.output;
  EXPECT_EQ(bytesOf(dir / "merged.exr"), bytesOf(dir / "single.exr"));
  nlohmann::json report;
  std::ifstream(dir / "merge.json") >> report;
  EXPECT_EQ(report["samples_merged"], 8);
  EXPECT_EQ(report["parts"].size(), 3u);
  EXPECT_EQ(report["parts"][0]["shard"], "2/3");
  EXPECT_EQ(report["render"]["scene"], "living-room");
  EXPECT_TRUE(report["system"].contains("LP_NUM_THREADS"));

  // Two of three: refused, or merged and said so.
  expectOneLineError(hmblur("--quiet merge " + part(dir, 0) + " " + part(dir, 2) + " --out " +
                            (dir / "partial.exr").string()),
                     "shard 1/3 is missing (--allow-partial");
  const CliRun partial = hmblur("merge --allow-partial " + part(dir, 0) + " " + part(dir, 2) + " --out " +
                                (dir / "partial.exr").string());
  EXPECT_EQ(partial.exitCode, 0) << partial.output;
  EXPECT_NE(partial.output.find("merged 2 of 3 shards (--allow-partial): 5 of 8 samples per pixel"), std::string::npos)
      << partial.output;
  expectOneLineError(hmblur("--quiet merge " + part(dir, 0) + " " + part(dir, 0) + " --out " +
                            (dir / "twice.exr").string()),
                     "shard 0/3 is given twice");
}

TEST(ShardMergeCliTest, ShardArgumentsAreCheckedInOneLine) {
  const fs::path dir = tempDir("shard_arguments");
  const std::string out = " --out " + (dir / "p.hmbpart").string();
  expectOneLineError(hmblur(kReference + " --shard 4/4" + out), "I must be below K");
  expectOneLineError(hmblur(kReference + " --shard 0/9" + out), "9 shards of 8 samples per pixel would leave some empty");
  expectOneLineError(hmblur(kReference + " --shard 1-4" + out), "'1-4' is not I/K");
  expectOneLineError(hmblur(kReference + " --shard 1/x" + out), "is not I/K");
  expectOneLineError(hmblur(kReference + " --shard 1/4 --out " + (dir / "p.exr").string()), "(.hmbpart)");
  expectOneLineError(hmblur(kReference + " --shard 1/4"), "(.hmbpart)");
  expectOneLineError(hmblur(kReference + " --shard 1/4 --checkpoint " + (dir / "c.bin").string() + out),
                     "leave out --checkpoint");
  expectOneLineError(hmblur(kReference + " --shard 1/4 --frames 1:2" + out), "do not apply");
  expectOneLineError(hmblur("--quiet render --method sharp --shard 1/4" + out), "is a setting of --method reference");
  EXPECT_FALSE(fs::exists(dir / "p.hmbpart"));
}

TEST(ShardMergeCliTest, PartsThatAreNoPartsAreOneLineErrors) {
  const fs::path dir = tempDir("merge_inputs");
  const std::string out = " --out " + (dir / "m.exr").string();
  expectOneLineError(hmblur("--quiet merge " + (dir / "none.hmbpart").string() + out), "cannot be read");
  std::ofstream(dir / "image.png") << "\x89PNG\r\n\x1a\n not a part at all";
  expectOneLineError(hmblur("--quiet merge " + (dir / "image.png").string() + out), "is not a reference partial");
  ASSERT_EQ(hmblur(kReference + " --shard 0/1 --out " + part(dir, 0)).exitCode, 0);
  fs::resize_file(part(dir, 0), fs::file_size(part(dir, 0)) / 2);
  expectOneLineError(hmblur("--quiet merge " + part(dir, 0) + out), "is truncated");
  expectOneLineError(hmblur("--quiet merge " + part(dir, 0) + " --out " + (dir / "m.png").string()), ".exr");
  EXPECT_NE(hmblur("--quiet merge --out " + (dir / "m.exr").string()).exitCode, 0);
  EXPECT_FALSE(fs::exists(dir / "m.exr"));
}

TEST(ShardMergeCliTest, MergeHelpGivesTheRecipes) {
  const CliRun run = hmblur("merge --help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* text : {"--shard I/K", "sbatch --parsable --array", "--dependency=afterok", "parallel -S",
                           "need no merge", "2 log2(N) + 1", "--allow-partial"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
  EXPECT_NE(hmblur("--help").output.find("merge"), std::string::npos);
}

}  // namespace
}  // namespace hmb::test
