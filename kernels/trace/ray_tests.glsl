// Robust ray-box and ray-triangle tests, the GLSL twins of bvh/ray_intersection.cpp.
#ifndef HMB_KERNELS_TRACE_RAY_TESTS_GLSL
#define HMB_KERNELS_TRACE_RAY_TESTS_GLSL

// Relative widening of a box's far end: covers the box test's and the triangle test's
// rounding, so a hit is never culled by its own leaf's box (bvh::kBoxSlack).
const float kBoxSlack = 1.0 / 65536.0;
// A largest angle this close to 180 degrees (sine): planeHitDistance keeps the edge functions'
// distance (bvh::kSliverSine).
const float kSliverSine = 1.0 / 1024.0;

struct PreparedRay {
  vec3 origin;
  vec3 direction;
  vec3 inverseDirection;  // +-inf for a zero component, by its sign
  bvec3 negative;         // direction < 0 (or -0) per axis: the box planes swap
  bool valid;             // false for a zero or non-finite direction: it hits nothing
  // Watertight triangle test (Woop, Benthin, Wald 2013): kz is the dominant axis, kx and ky
  // the other two in an order that keeps the winding; the shear maps the ray to +z.
  uint kx, ky, kz;
  vec3 shear;
};

PreparedRay prepareRay(vec3 origin, vec3 direction) {
  PreparedRay r;
  r.origin = origin;
  r.direction = direction;
  r.inverseDirection = 1.0 / direction;
  r.negative = lessThan(r.inverseDirection, vec3(0.0));
  r.valid = !any(isnan(direction)) && !any(isinf(direction)) && any(notEqual(direction, vec3(0.0)));
  const vec3 a = abs(direction);
  r.kz = a.x >= a.y ? (a.x >= a.z ? 0u : 2u) : (a.y >= a.z ? 1u : 2u);
  r.kx = r.kz == 2u ? 0u : r.kz + 1u;
  r.ky = r.kx == 2u ? 0u : r.kx + 1u;
  if (direction[r.kz] < 0.0) {
    const uint swap = r.kx;
    r.kx = r.ky;
    r.ky = swap;
  }
  r.shear = vec3(direction[r.kx] / direction[r.kz], direction[r.ky] / direction[r.kz], 1.0 / direction[r.kz]);
  return r;
}

// True when [tMin, tMax] meets three slabs, each given by the distances where the ray enters
// and leaves it. A NaN distance (0 * inf: a ray in a slab's boundary plane) leaves the interval
// as it was. `near` is where the ray enters them all (at least tMin).
bool slabsMeet(vec3 entry, vec3 exit, float tMin, float tMax, out float near) {
  float far = tMax;
  near = tMin;
  for (uint a = 0; a < 3; ++a) {
    near = entry[a] > near ? entry[a] : near;
    far = exit[a] < far ? exit[a] : far;
  }
  far += abs(far) * kBoxSlack;
  return near <= far;
}

// True when the ray's [tMin, tMax] meets the box; an empty box (min > max) is never met.
// `near` is where the ray enters the box (at least tMin).
bool intersectBoxEntry(PreparedRay r, vec3 lo, vec3 hi, float tMin, float tMax, out float near) {
  const vec3 entryPlane = mix(lo, hi, r.negative), exitPlane = mix(hi, lo, r.negative);
  return slabsMeet((entryPlane - r.origin) * r.inverseDirection, (exitPlane - r.origin) * r.inverseDirection, tMin,
                   tMax, near);
}

bool intersectBox(PreparedRay r, vec3 lo, vec3 hi, float tMin, float tMax) {
  float near;
  return intersectBoxEntry(r, lo, hi, tMin, tMax, near);
}

// Watertight test, both sides. t, u (weight of v1) and v (of v2) are written on a hit.
// Edge functions are computed unfused (precise), so a shared edge gives exact negatives in its
// two triangles; a zero edge function counts as inside for both, so a ray through an edge or a
// vertex hits at least one of the triangles sharing it (the host's test redoes zeros in double
// to pick exactly one; here both may hit, and the closest-hit order settles it).
bool intersectTriangle(PreparedRay r, vec3 v0, vec3 v1, vec3 v2, out float t, out float u, out float v) {
  const vec3 a = v0 - r.origin, b = v1 - r.origin, c = v2 - r.origin;
  precise const float ax = a[r.kx] - r.shear.x * a[r.kz], ay = a[r.ky] - r.shear.y * a[r.kz];
  precise const float bx = b[r.kx] - r.shear.x * b[r.kz], by = b[r.ky] - r.shear.y * b[r.kz];
  precise const float cx = c[r.kx] - r.shear.x * c[r.kz], cy = c[r.ky] - r.shear.y * c[r.kz];
  precise const float e0 = cx * by - cy * bx;  // weight of v0
  precise const float e1 = ax * cy - ay * cx;  // weight of v1
  precise const float e2 = bx * ay - by * ax;  // weight of v2
  if ((e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)) return false;
  precise const float det = e0 + e1 + e2;
  if (det == 0.0 || isnan(det)) return false;
  // precise as the edge functions: the host reference's rounding on any device (Vulkan lets a
  // driver fuse products into multiply-adds where a result is not precise).
  precise const float scaledT = e0 * (r.shear.z * a[r.kz]) + e1 * (r.shear.z * b[r.kz]) + e2 * (r.shear.z * c[r.kz]);
  precise const float inverseDet = 1.0 / det;
  precise const float hitT = scaledT * inverseDet, hitU = e1 * inverseDet, hitV = e2 * inverseDet;
  t = hitT;
  u = hitU;
  v = hitV;
  return true;
}

// The distance to the plane of a triangle the ray hits, to float precision; `shearedT` for a
// sliver or a ray in its plane (bvh::planeHitDistance explains). Taken for the closest hit only.
float planeHitDistance(PreparedRay r, vec3 v0, vec3 v1, vec3 v2, float shearedT) {
  precise const vec3 edge0 = v1 - v0, edge1 = v2 - v1, edge2 = v0 - v2;
  precise const float length0 = dot(edge0, edge0), length1 = dot(edge1, edge1), length2 = dot(edge2, edge2);
  // The two edges other than the longest, chosen by selects: lavapipe would compute all three
  // branches' cross products under masks.
  const bool longest0 = length0 >= length1 && length0 >= length2, longest1 = !longest0 && length1 >= length2;
  const vec3 first = longest0 ? edge1 : (longest1 ? edge2 : edge0);
  const vec3 second = longest0 ? edge2 : (longest1 ? edge0 : edge1);
  const vec3 vertex = longest0 ? v2 : (longest1 ? v0 : v1);
  precise const float lengths = longest0 ? length1 * length2 : (longest1 ? length2 * length0 : length0 * length1);
  precise const vec3 normal = cross(first, second);
  precise const float towards = dot(normal, r.direction);
  precise const float area2 = dot(normal, normal);
  if (!(towards != 0.0 && !isinf(towards) && !isnan(towards) && area2 >= kSliverSine * kSliverSine * lengths))
    return shearedT;
  precise const float facing = dot(normal, vertex - r.origin);
  return facing / towards;
}

#endif
