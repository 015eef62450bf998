// Packed nodes on the host (bvh/packed_node.cpp, the twin of kernels/bvh/packed_node.glsl):
// a frame spans its root box, packed bounds hold the exact ones and are the tightest that do,
// and the index word round-trips; on random boxes and on frames far from the origin, tiny,
// flat, and as wide as a float goes.
#include "bvh/packed_node.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace hmb::bvh::test {
namespace {

constexpr float kMax = std::numeric_limits<float>::max();

// Root boxes: ordinary, ones whose plain step falls short, far from the origin (ulp(1e7) = 1 is far coarser than a
// step), tiny, flat on one axis, a point, and the widest finite box.
std::vector<Aabb> adversarialRoots() {
  return {Aabb{{-1, -2, -3}, {4, 5, 6}},
          // Boxes whose plain step, (hi - lo) / 65535 rounded, stops short of hi.
          Aabb{{-70.648819f, -20.6465073f, 11.7379684f}, {-68.2879257f, -11.2911167f, 16.0449543f}},
          Aabb{{1e7f, -1e7f, 3e7f}, {1e7f + 1e-3f, -1e7f + 8.0f, 3e7f + 4.0f}},
          Aabb{{1e-30f, 2e-30f, 0}, {3e-30f, 2.5e-30f, 1e-30f}}, Aabb{{0, 5, 0}, {10, 5, 10}},
          Aabb{{2, 2, 2}, {2, 2, 2}}, Aabb{{-kMax, -kMax, -kMax}, {kMax, kMax, kMax}}};
}

// A random box inside `root` (its corners drawn along each axis).
Aabb randomBoxIn(const Aabb& root, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Aabb box;
  for (int a = 0; a < 3; ++a) {
    const float u = unit(rng), v = unit(rng);
    // root.min + t * (max - min) may round past the root: clamp the drawn corner into it.
    const auto at = [&](float t) {
      return std::clamp(root.min[a] * (1.0f - t) + root.max[a] * t, root.min[a], root.max[a]);
    };
    box.min[a] = std::min(at(u), at(v));  // the rounded mix is not monotonic in t
    box.max[a] = std::max(at(u), at(v));
  }
  return box;
}

TEST(PackedNode, FramesSpanTheirRootBox) {
  for (const Aabb& root : adversarialRoots()) {
    const gpu::BvhFrame frame = frameOf(root);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(boundAt(0, frame.origin[a], frame.step[a]), root.min[a]) << "axis " << a;
      EXPECT_GE(boundAt(HMB_BVH_QUANTUM_MAX, frame.origin[a], frame.step[a]), root.max[a]) << "axis " << a;
      EXPECT_GE(frame.step[a], 0.0f);
    }
  }
}

TEST(PackedNode, PackedBoundsHoldTheExactOnesAndAreTheTightestThatDo) {
  std::mt19937 rng(17);
  for (const Aabb& root : adversarialRoots()) {
    const gpu::BvhFrame frame = frameOf(root);
    for (int i = 0; i < 2000; ++i) {
      const Aabb box = i == 0 ? root : randomBoxIn(root, rng);
      Node node{};
      setBounds(node, box);
      const Aabb packed = boundsOf(unpackNode(packNode(node, frame), frame));
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(packed.min[a], box.min[a]) << "axis " << a << ", box " << i;
        ASSERT_GE(packed.max[a], box.max[a]) << "axis " << a << ", box " << i;
        // One step fewer would leave the exact bound out.
        const uint32_t below = stepsBelow(box.min[a], frame.origin[a], frame.step[a]);
        const uint32_t above = stepsAbove(box.max[a], frame.origin[a], frame.step[a]);
        if (below < HMB_BVH_QUANTUM_MAX) {
          ASSERT_GT(boundAt(below + 1, frame.origin[a], frame.step[a]), box.min[a]);
        }
        if (above > 0) {
          ASSERT_LT(boundAt(above - 1, frame.origin[a], frame.step[a]), box.max[a]);
        }
      }
    }
  }
}

TEST(PackedNode, PackedBoxesAreAsSmallAsTheirStepsAllow) {
  // An ordinary frame: a box gains less than a step on each side.
  const Aabb root{{-1, -2, -3}, {4, 5, 6}};
  const gpu::BvhFrame frame = frameOf(root);
  std::mt19937 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Aabb box = randomBoxIn(root, rng);
    Node node{};
    setBounds(node, box);
    const Aabb packed = boundsOf(unpackNode(packNode(node, frame), frame));
    for (int a = 0; a < 3; ++a) {
      EXPECT_LT(box.min[a] - packed.min[a], frame.step[a] * 1.01f);
      EXPECT_LT(packed.max[a] - box.max[a], frame.step[a] * 1.01f);
    }
  }
}

// The searches start from the quotient's guess; the answer must be the plain binary search's
// over every step, wherever x falls: inside the frame, on its bounds, outside it, far from it,
// infinite or NaN, in frames tiny, huge and far from the origin.
TEST(PackedNode, GuessedSearchesAnswerAsTheFullSearch) {
  const auto fullBelow = [](float x, float origin, float step) {
    uint32_t low = 0, high = HMB_BVH_QUANTUM_MAX;
    while (low < high) {
      const uint32_t middle = (low + high + 1) >> 1;
      if (boundAt(middle, origin, step) <= x) low = middle;
      else high = middle - 1;
    }
    return low;
  };
  const auto fullAbove = [](float x, float origin, float step) {
    uint32_t low = 0, high = HMB_BVH_QUANTUM_MAX;
    while (low < high) {
      const uint32_t middle = (low + high) >> 1;
      if (boundAt(middle, origin, step) >= x) high = middle;
      else low = middle + 1;
    }
    return low;
  };
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> unit(-0.1f, 1.1f);
  std::uniform_int_distribution<uint32_t> steps(0, HMB_BVH_QUANTUM_MAX);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (const Aabb& root : adversarialRoots()) {
    const gpu::BvhFrame frame = frameOf(root);
    for (int a = 0; a < 3; ++a) {
      const float origin = frame.origin[a], step = frame.step[a];
      std::vector<float> xs = {root.min[a], root.max[a], -kMax, kMax, -kInf, kInf, std::nanf(""), 0.0f, -0.0f};
      for (int i = 0; i < 3000; ++i) {
        const float t = unit(rng);
        xs.push_back(root.min[a] * (1.0f - t) + root.max[a] * t);
        const float bound = boundAt(steps(rng), origin, step);  // a bound, and its neighbours
        xs.insert(xs.end(), {bound, std::nextafter(bound, -kInf), std::nextafter(bound, kInf)});
      }
      for (const float x : xs) {
        ASSERT_EQ(stepsBelow(x, origin, step), fullBelow(x, origin, step)) << "x " << x << ", axis " << a;
        ASSERT_EQ(stepsAbove(x, origin, step), fullAbove(x, origin, step)) << "x " << x << ", axis " << a;
      }
    }
  }
}

TEST(PackedNode, EmptyBoxesStayEmptyAndIndicesRoundTrip) {
  const gpu::BvhFrame frame = frameOf(Aabb{{0, 0, 0}, {1, 1, 1}});
  Node empty{};
  setBounds(empty, Aabb{});
  empty.leftOrFirst = HMB_BVH_PACKED_INDEX_LIMIT - 1;
  empty.count = HMB_BVH_PACKED_MAX_COUNT;
  const gpu::BvhPackedNode packed = packNode(empty, frame);
  EXPECT_EQ(packed.x, HMB_BVH_QUANTUM_MAX);
  const Node unpacked = unpackNode(packed, frame);
  EXPECT_TRUE(boundsOf(unpacked).empty());
  EXPECT_EQ(unpacked.leftOrFirst, HMB_BVH_PACKED_INDEX_LIMIT - 1);
  EXPECT_EQ(unpacked.count, HMB_BVH_PACKED_MAX_COUNT);
  // An empty tree's frame still unpacks the empty box as empty.
  EXPECT_TRUE(boundsOf(unpackNode(packNode(empty, frameOf(Aabb{})), frameOf(Aabb{}))).empty());
}

}  // namespace
}  // namespace hmb::bvh::test
