#include "bench/embree_reference.h"

#include "hmblur/error.h"

#ifndef HMB_HAVE_EMBREE

namespace hmb::bench {

bool embreeAvailable() { return false; }
std::string embreeVersion() { return ""; }

EmbreeRun runEmbree(const bvh::TriangleList&, std::span<const bvh::Ray>, int, int, int) {
  throw Error("Embree reference: built without Embree (install libembree-dev and reconfigure)");
}

}  // namespace hmb::bench

#else

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>

#include <embree3/rtcore.h>

namespace hmb::bench {
namespace {

// Our SAH constants and leaf size (bvh::SahCosts and bvh::BuildOptions defaults), so the tree
// Embree builds is judged by the cost it optimised.
constexpr unsigned kMaxLeafSize = 4;
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;
// Rays a tracing thread takes at a time: large enough that the shared counter is cheap, small
// enough that threads finish together.
constexpr size_t kRaysPerChunk = 1024;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Embree reports errors through a callback, possibly from its worker threads, where throwing
// is not safe; the first one is kept and thrown after the call that caused it returns.
class ErrorLog {
 public:
  static void record(void* log, RTCError code, const char* message) {
    auto& self = *static_cast<ErrorLog*>(log);
    const std::scoped_lock lock(self.mutex_);
    if (self.first_.empty())
      self.first_ = "error " + std::to_string(static_cast<int>(code)) + (message ? std::string(": ") + message : "");
  }
  void throwIfAny(const char* during) {
    const std::scoped_lock lock(mutex_);
    if (!first_.empty()) throw Error(std::string("Embree ") + during + ": " + first_);
  }

 private:
  std::mutex mutex_;
  std::string first_;
};

struct DeviceDeleter {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneDeleter {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
struct BvhDeleter {
  void operator()(RTCBVH bvh) const { rtcReleaseBVH(bvh); }
};
using DeviceHandle = std::unique_ptr<std::remove_pointer_t<RTCDevice>, DeviceDeleter>;
using SceneHandle = std::unique_ptr<std::remove_pointer_t<RTCScene>, SceneDeleter>;
using BvhHandle = std::unique_ptr<std::remove_pointer_t<RTCBVH>, BvhDeleter>;

// A device whose errors land in `log`, which must outlive it.
DeviceHandle newDevice(int threads, ErrorLog& log) {
  const std::string config = "threads=" + std::to_string(threads) + ",verbose=0";
  DeviceHandle device(rtcNewDevice(config.c_str()));
  if (!device)
    throw Error("Embree device could not be created (error " + std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) +
                ")");
  rtcSetDeviceErrorFunction(device.get(), &ErrorLog::record, &log);
  return device;
}

// Embree loads vertices 16 bytes at a time, so the last one needs 4 readable bytes after it,
// which a span of glm::vec3 does not promise: the positions are shared from a padded copy.
std::vector<glm::vec3> paddedPositions(std::span<const glm::vec3> positions) {
  std::vector<glm::vec3> padded(positions.begin(), positions.end());
  padded.emplace_back(0.0f);
  return padded;
}

// A scene of one triangle geometry over shared buffers, not yet committed.
SceneHandle newTriangleScene(RTCDevice device, std::span<const glm::vec3> padded, std::span<const uint32_t> indices,
                             ErrorLog& log) {
  SceneHandle scene(rtcNewScene(device));
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, padded.data(), 0,
                             sizeof(glm::vec3), padded.size() - 1);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices.data(), 0,
                             3 * sizeof(uint32_t), indices.size() / 3);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);  // the scene holds it now
  log.throwIfAny("scene setup");
  return scene;
}

// rtcBuildBVH's user nodes: it allocates them from its own arena, calling back from its worker
// threads; they live until the RTCBVH is released, long enough to be converted.
struct BuildNode {
  bool leaf;
};
struct InteriorBuildNode : BuildNode {
  const BuildNode* children[2];
  Aabb childBounds[2];
};
struct LeafBuildNode : BuildNode {
  unsigned count;
  uint32_t primitives[kMaxLeafSize];
  Aabb bounds;
};

// Shape problems seen in the callbacks (which must not throw into Embree), reported afterwards.
struct BuildCheck {
  std::atomic<bool> notBinary{false};
  std::atomic<bool> leafTooLarge{false};
};

Aabb toAabb(const RTCBounds& b) { return Aabb{{b.lower_x, b.lower_y, b.lower_z}, {b.upper_x, b.upper_y, b.upper_z}}; }

void* createInterior(RTCThreadLocalAllocator allocator, unsigned childCount, void* check) {
  if (childCount != 2) static_cast<BuildCheck*>(check)->notBinary = true;
  void* memory = rtcThreadLocalAlloc(allocator, sizeof(InteriorBuildNode), alignof(InteriorBuildNode));
  return new (memory) InteriorBuildNode{{false}, {nullptr, nullptr}, {}};
}

void setChildren(void* node, void** children, unsigned childCount, void*) {
  auto& interior = *static_cast<InteriorBuildNode*>(node);
  for (unsigned i = 0; i < std::min(childCount, 2u); ++i) interior.children[i] = static_cast<const BuildNode*>(children[i]);
}

void setChildBounds(void* node, const RTCBounds** bounds, unsigned childCount, void*) {
  auto& interior = *static_cast<InteriorBuildNode*>(node);
  for (unsigned i = 0; i < std::min(childCount, 2u); ++i) interior.childBounds[i] = toAabb(*bounds[i]);
}

void* createLeaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives, size_t count, void* check) {
  if (count > kMaxLeafSize) static_cast<BuildCheck*>(check)->leafTooLarge = true;
  void* memory = rtcThreadLocalAlloc(allocator, sizeof(LeafBuildNode), alignof(LeafBuildNode));
  auto* leaf = new (memory) LeafBuildNode{{true}, 0, {}, {}};
  leaf->count = static_cast<unsigned>(std::min<size_t>(count, kMaxLeafSize));
  for (unsigned i = 0; i < leaf->count; ++i) {
    leaf->primitives[i] = primitives[i].primID;
    leaf->bounds.grow(Aabb{{primitives[i].lower_x, primitives[i].lower_y, primitives[i].lower_z},
                           {primitives[i].upper_x, primitives[i].upper_y, primitives[i].upper_z}});
  }
  return leaf;
}

// Our layout from Embree's tree: depth first, each interior node's two children side by side,
// leaves' primitives appended in visiting order. Bounds are the ones Embree built with.
bvh::Bvh convert(const BuildNode* root, size_t primitiveCount) {
  bvh::Bvh out;
  if (!root) return out;
  if (root->leaf && static_cast<const LeafBuildNode*>(root)->count == 0) return out;
  out.primitiveIndices.reserve(primitiveCount);
  out.nodes.reserve(2 * primitiveCount);
  struct Pending {
    const BuildNode* node;
    uint32_t index;
    Aabb bounds;
  };
  Aabb rootBounds;
  if (root->leaf) {
    rootBounds = static_cast<const LeafBuildNode*>(root)->bounds;
  } else {
    const auto* interior = static_cast<const InteriorBuildNode*>(root);
    rootBounds = interior->childBounds[0];
    rootBounds.grow(interior->childBounds[1]);
  }
  out.nodes.push_back({});
  std::vector<Pending> pending{{root, HMB_BVH_ROOT, rootBounds}};
  while (!pending.empty()) {
    const Pending item = pending.back();
    pending.pop_back();
    bvh::Node node{};
    bvh::setBounds(node, item.bounds);
    if (item.node->leaf) {
      const auto* leaf = static_cast<const LeafBuildNode*>(item.node);
      node.leftOrFirst = static_cast<uint32_t>(out.primitiveIndices.size());
      node.count = leaf->count;
      out.primitiveIndices.insert(out.primitiveIndices.end(), leaf->primitives, leaf->primitives + leaf->count);
    } else {
      const auto* interior = static_cast<const InteriorBuildNode*>(item.node);
      node.leftOrFirst = static_cast<uint32_t>(out.nodes.size());
      node.count = 0;
      out.nodes.resize(out.nodes.size() + 2);
      for (uint32_t i = 0; i < 2; ++i) pending.push_back({interior->children[i], node.leftOrFirst + i, interior->childBounds[i]});
    }
    out.nodes[item.index] = node;
  }
  return out;
}

std::vector<RTCBuildPrimitive> buildPrimitives(const bvh::TriangleList& triangles) {
  const bvh::PrimitiveBounds input = bvh::triangleBounds(triangles);
  std::vector<RTCBuildPrimitive> primitives(input.bounds.size());
  for (size_t i = 0; i < primitives.size(); ++i) {
    const Aabb& box = input.bounds[i];
    primitives[i] = RTCBuildPrimitive{box.min.x, box.min.y, box.min.z, 0, box.max.x, box.max.y, box.max.z,
                                      static_cast<unsigned>(i)};
  }
  return primitives;
}

// One rtcBuildBVH, timed alone (the builder reorders its input, so each build gets a fresh
// copy first). Returns the converted tree when `keep` is set.
double buildUserBvh(RTCDevice device, std::span<const RTCBuildPrimitive> input, ErrorLog& log, bvh::Bvh* keep) {
  std::vector<RTCBuildPrimitive> primitives(input.begin(), input.end());
  BvhHandle handle(rtcNewBVH(device));
  log.throwIfAny("rtcNewBVH");
  BuildCheck check;
  RTCBuildArguments arguments = rtcDefaultBuildArguments();
  // MEDIUM is Embree's binned SAH builder. HIGH differs only by spatial splits, which put one
  // primitive in several leaves (our layout allows one) and need a split callback; without
  // them HIGH runs the same binned builder.
  arguments.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  arguments.maxBranchingFactor = 2;
  arguments.maxDepth = 64;  // leave depth to the SAH: the reference builder has no limit
  arguments.sahBlockSize = 1;
  arguments.minLeafSize = 1;
  arguments.maxLeafSize = kMaxLeafSize;
  arguments.traversalCost = kTraversalCost;
  arguments.intersectionCost = kIntersectionCost;
  arguments.bvh = handle.get();
  arguments.primitives = primitives.data();
  arguments.primitiveCount = primitives.size();
  arguments.primitiveArrayCapacity = primitives.size();
  arguments.createNode = &createInterior;
  arguments.setNodeChildren = &setChildren;
  arguments.setNodeBounds = &setChildBounds;
  arguments.createLeaf = &createLeaf;
  arguments.userPtr = &check;

  const Clock::time_point start = Clock::now();
  const void* root = rtcBuildBVH(&arguments);
  const double seconds = secondsSince(start);
  log.throwIfAny("rtcBuildBVH");
  if (check.notBinary) throw Error("Embree rtcBuildBVH made a node without exactly two children");
  if (check.leafTooLarge) throw Error("Embree rtcBuildBVH made a leaf larger than " + std::to_string(kMaxLeafSize));
  if (keep) *keep = convert(static_cast<const BuildNode*>(root), primitives.size());
  return seconds;
}

bool traceable(const bvh::Ray& ray) {
  const glm::vec3& d = ray.direction;
  return std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z) && d != glm::vec3(0.0f) &&
         std::isfinite(ray.origin.x) && std::isfinite(ray.origin.y) && std::isfinite(ray.origin.z) &&
         ray.tMin <= ray.tMax;
}

gpu::BvhHit missFor(const bvh::Ray& ray) { return {ray.tMax, 0.0f, 0.0f, HMB_NO_HIT, HMB_NO_HIT, 0, 0, 0}; }

// One ray at a time with rtcIntersect1: on random rays it was at least as fast as 16-wide
// packets (rtcIntersect16) and rtcIntersect1M streams, whose lanes diverge after the first nodes
// (with the coherent hint, packets were three times slower); on camera rays in 4x4 tiles those
// gained no more than a few percent.
void traceChunk(RTCScene scene, const bvh::TriangleList& triangles, std::span<const bvh::Ray> rays,
                std::span<gpu::BvhHit> hits) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (size_t i = 0; i < rays.size(); ++i) {
    const bvh::Ray& ray = rays[i];
    if (!traceable(ray)) {  // Embree leaves invalid rays undefined; ours hit nothing
      hits[i] = missFor(ray);
      continue;
    }
    RTCRayHit query;
    query.ray.org_x = ray.origin.x, query.ray.org_y = ray.origin.y, query.ray.org_z = ray.origin.z;
    query.ray.tnear = ray.tMin;
    query.ray.dir_x = ray.direction.x, query.ray.dir_y = ray.direction.y, query.ray.dir_z = ray.direction.z;
    query.ray.time = 0.0f;
    query.ray.tfar = ray.tMax;
    query.ray.mask = ~0u;
    query.ray.id = 0;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &query);
    hits[i] = query.hit.geomID == RTC_INVALID_GEOMETRY_ID
                  ? missFor(ray)
                  : gpu::BvhHit{query.ray.tfar, query.hit.u,  query.hit.v, query.hit.primID,
                                triangles.objectId(query.hit.primID), 0, 0, 0};
  }
}

// Splits the rays over `threads` threads that take chunks from a shared counter; thread start
// and join are inside the timing, as they are part of answering a batch.
double traceAll(RTCScene scene, const bvh::TriangleList& triangles, std::span<const bvh::Ray> rays, int threads,
                std::span<gpu::BvhHit> hits) {
  std::atomic<size_t> nextChunk{0};
  const auto work = [&] {
    for (;;) {
      const size_t begin = nextChunk.fetch_add(kRaysPerChunk, std::memory_order_relaxed);
      if (begin >= rays.size()) return;
      const size_t count = std::min(kRaysPerChunk, rays.size() - begin);
      traceChunk(scene, triangles, rays.subspan(begin, count), hits.subspan(begin, count));
    }
  };
  const Clock::time_point start = Clock::now();
  std::vector<std::jthread> workers;
  for (int i = 1; i < threads; ++i) workers.emplace_back(work);
  work();
  workers.clear();  // joins
  return secondsSince(start);
}

}  // namespace

bool embreeAvailable() { return true; }

std::string embreeVersion() {
  ErrorLog log;
  const DeviceHandle device = newDevice(1, log);
  const auto part = [&](RTCDeviceProperty property) {
    return std::to_string(rtcGetDeviceProperty(device.get(), property));
  };
  return part(RTC_DEVICE_PROPERTY_VERSION_MAJOR) + "." + part(RTC_DEVICE_PROPERTY_VERSION_MINOR) + "." +
         part(RTC_DEVICE_PROPERTY_VERSION_PATCH);
}

EmbreeRun runEmbree(const bvh::TriangleList& triangles, std::span<const bvh::Ray> rays, int threads, int warmup,
                    int repeats) {
  if (threads < 1) throw Error("Embree reference: threads must be at least 1");
  if (warmup < 0 || repeats < 1) throw Error("Embree reference: needs warmup >= 0 and repeats >= 1");
  ErrorLog log;  // declared first: outlives the device that reports into it
  const DeviceHandle device = newDevice(threads, log);
  EmbreeRun run;

  const std::vector<glm::vec3> positions = paddedPositions(triangles.positions);
  SceneHandle scene;
  for (int i = 0; i < warmup + repeats; ++i) {
    scene = newTriangleScene(device.get(), positions, triangles.indices, log);
    const Clock::time_point start = Clock::now();
    rtcCommitScene(scene.get());
    const double seconds = secondsSince(start);
    log.throwIfAny("rtcCommitScene");
    if (i >= warmup) run.sceneBuildSeconds.push_back(seconds);
  }

  const std::vector<RTCBuildPrimitive> primitives = buildPrimitives(triangles);
  for (int i = 0; i < warmup + repeats; ++i) {
    const bool last = i + 1 == warmup + repeats;
    const double seconds = buildUserBvh(device.get(), primitives, log, last ? &run.bvh : nullptr);
    if (i >= warmup) run.bvhBuildSeconds.push_back(seconds);
  }

  run.hits.resize(rays.size());
  for (int i = 0; i < warmup + repeats; ++i) {
    const double seconds = traceAll(scene.get(), triangles, rays, threads, run.hits);
    log.throwIfAny("rtcIntersect1");
    if (i >= warmup) run.traceSeconds.push_back(seconds);
  }
  return run;
}

}  // namespace hmb::bench

#endif
