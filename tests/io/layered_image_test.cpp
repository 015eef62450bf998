#include <gtest/gtest.h>

#include "hmblur/image.h"

namespace hmb::io {
namespace {

TEST(LayeredImage, FindReturnsTheNamedLayerOrNull) {
  LayeredImage image;
  image.layers.push_back({.name = "", .channels = {"R", "G", "B", "A"}});
  image.layers.push_back({.name = "depth", .channels = {"Z"}});
  ASSERT_NE(image.find(""), nullptr);
  EXPECT_EQ(image.find("")->channels.size(), 4u);
  ASSERT_NE(image.find("depth"), nullptr);
  EXPECT_EQ(image.find("depth")->channels.front(), "Z");
  EXPECT_EQ(image.find("normal"), nullptr);
  EXPECT_EQ(LayeredImage{}.find(""), nullptr);
}

}  // namespace
}  // namespace hmb::io
