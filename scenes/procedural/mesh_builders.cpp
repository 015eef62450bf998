#include "scenes/procedural/mesh_builders.h"

#include <cmath>
#include <utility>

#include <glm/gtc/constants.hpp>

namespace hmb::scene::procedural {
namespace {

// Winds every triangle so that its face normal agrees with its vertex normals (outward),
// and drops zero-area triangles (at the poles of revolved surfaces).
void orientAndClean(Mesh& mesh) {
  std::vector<uint32_t> kept;
  kept.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::vec3 face = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (glm::dot(face, face) <= 1e-20f) continue;
    const glm::vec3 shading = mesh.normals[a] + mesh.normals[b] + mesh.normals[c];
    if (glm::dot(face, shading) < 0.0f) std::swap(b, c);
    kept.insert(kept.end(), {a, b, c});
  }
  mesh.indices = std::move(kept);
}

// Quads between consecutive rows of a (rows x columns) vertex grid.
void addGridIndices(Mesh& mesh, uint32_t first, uint32_t rows, uint32_t columns) {
  for (uint32_t r = 0; r + 1 < rows; ++r)
    for (uint32_t c = 0; c + 1 < columns; ++c) {
      const uint32_t v00 = first + r * columns + c, v01 = v00 + 1, v10 = v00 + columns, v11 = v10 + 1;
      mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
    }
}

void addVertex(Mesh& mesh, const glm::vec3& p, const glm::vec3& n, const glm::vec2& uv) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(n);
  mesh.uvs.push_back(uv);
}

}  // namespace

Mesh makeBox(const glm::vec3& h, uint32_t material) {
  Mesh mesh;
  mesh.name = "box";
  mesh.material = material;
  // Each face: normal axis, and two in-plane axes whose cross product is the normal.
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f}) {
      const glm::vec3 n = axes[axis] * sign;
      const glm::vec3 u = axes[(axis + 1) % 3] * sign;
      const glm::vec3 v = axes[(axis + 2) % 3];
      const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
      for (int corner = 0; corner < 4; ++corner) {
        const float su = (corner == 1 || corner == 2) ? 1.0f : -1.0f;
        const float sv = corner >= 2 ? 1.0f : -1.0f;
        addVertex(mesh, (n + u * su + v * sv) * h, n, glm::vec2(0.5f * (su + 1.0f), 0.5f * (sv + 1.0f)));
      }
      mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    }
  orientAndClean(mesh);
  return mesh;
}

Mesh makePlane(const glm::vec2& size, uint32_t material) {
  Mesh mesh;
  mesh.name = "plane";
  mesh.material = material;
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  for (int corner = 0; corner < 4; ++corner) {
    const float u = (corner == 1 || corner == 2) ? 1.0f : 0.0f;
    const float v = corner >= 2 ? 1.0f : 0.0f;
    addVertex(mesh, glm::vec3((u - 0.5f) * size.x, 0.0f, (v - 0.5f) * size.y), n, glm::vec2(u, v));
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
  orientAndClean(mesh);
  return mesh;
}

Mesh makeLathe(const std::vector<glm::vec2>& profile, uint32_t segments, uint32_t material) {
  Mesh mesh;
  mesh.name = "lathe";
  mesh.material = material;
  const uint32_t rows = static_cast<uint32_t>(profile.size());
  const uint32_t columns = segments + 1;  // a seam column so that u runs 0..1
  for (uint32_t r = 0; r < rows; ++r) {
    // Profile normal from the neighbours' tangent, turned outward (away from the axis).
    const glm::vec2 tangent = profile[std::min(r + 1, rows - 1)] - profile[r == 0 ? 0 : r - 1];
    glm::vec2 n2(tangent.y, -tangent.x);
    const float len = glm::length(n2);
    n2 = len > 0.0f ? n2 / len : glm::vec2(1.0f, 0.0f);
    for (uint32_t c = 0; c < columns; ++c) {
      const float angle = glm::two_pi<float>() * static_cast<float>(c) / static_cast<float>(segments);
      const float cs = std::cos(angle), sn = std::sin(angle);
      addVertex(mesh, glm::vec3(profile[r].x * cs, profile[r].y, profile[r].x * sn),
                glm::normalize(glm::vec3(n2.x * cs, n2.y, n2.x * sn)),
                glm::vec2(static_cast<float>(c) / static_cast<float>(segments),
                          static_cast<float>(r) / static_cast<float>(std::max(rows - 1, 1u))));
    }
  }
  addGridIndices(mesh, 0, rows, columns);
  orientAndClean(mesh);
  return mesh;
}

Mesh makeCylinder(float radius, float height, uint32_t segments, uint32_t material, bool caps) {
  Mesh mesh = makeLathe({{radius, 0.0f}, {radius, height}}, segments, material);
  mesh.name = "cylinder";
  if (!caps) return mesh;
  for (float y : {0.0f, height}) {
    const glm::vec3 n(0.0f, y > 0.0f ? 1.0f : -1.0f, 0.0f);
    const uint32_t center = static_cast<uint32_t>(mesh.positions.size());
    addVertex(mesh, glm::vec3(0.0f, y, 0.0f), n, glm::vec2(0.5f));
    for (uint32_t c = 0; c <= segments; ++c) {
      const float angle = glm::two_pi<float>() * static_cast<float>(c) / static_cast<float>(segments);
      addVertex(mesh, glm::vec3(radius * std::cos(angle), y, radius * std::sin(angle)), n,
                glm::vec2(0.5f + 0.5f * std::cos(angle), 0.5f + 0.5f * std::sin(angle)));
      if (c > 0) mesh.indices.insert(mesh.indices.end(), {center, center + c, center + c + 1});
    }
  }
  orientAndClean(mesh);
  return mesh;
}

Mesh makeSphere(float radius, uint32_t segments, uint32_t rings, uint32_t material) {
  std::vector<glm::vec2> profile;
  for (uint32_t r = 0; r <= rings; ++r) {
    const float phi = glm::pi<float>() * (static_cast<float>(r) / static_cast<float>(rings) - 0.5f);
    profile.emplace_back(radius * std::cos(phi), radius * std::sin(phi));
  }
  profile.front().x = profile.back().x = 0.0f;  // exact poles
  Mesh mesh = makeLathe(profile, segments, material);
  mesh.name = "sphere";
  // A sphere's exact normal is its position direction, even at the poles.
  for (size_t v = 0; v < mesh.positions.size(); ++v) mesh.normals[v] = glm::normalize(mesh.positions[v]);
  return mesh;
}

Mesh makeTorus(float ringRadius, float tubeRadius, uint32_t segments, uint32_t tubeSegments, uint32_t material) {
  std::vector<glm::vec2> profile;
  for (uint32_t k = 0; k <= tubeSegments; ++k) {
    // Around the tube counter-clockwise in (radius, y), so the lathe's normals point outward.
    const float a =
        glm::two_pi<float>() * static_cast<float>(k) / static_cast<float>(tubeSegments) - glm::half_pi<float>();
    profile.emplace_back(ringRadius + tubeRadius * std::cos(a), tubeRadius * std::sin(a));
  }
  Mesh mesh = makeLathe(profile, segments, material);
  mesh.name = "torus";
  // Exact tube normals: from the tube's centre circle to the point.
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    const glm::vec3 onRing = glm::normalize(glm::vec3(p.x, 0.0f, p.z)) * ringRadius;
    mesh.normals[v] = glm::normalize(p - onRing);
  }
  orientAndClean(mesh);
  return mesh;
}

void appendMesh(Mesh& into, const Mesh& part, const glm::mat4& transform) {
  const uint32_t first = static_cast<uint32_t>(into.positions.size());
  const glm::mat3 normalTransform = glm::transpose(glm::inverse(glm::mat3(transform)));
  const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;
  for (size_t v = 0; v < part.positions.size(); ++v) {
    into.positions.push_back(glm::vec3(transform * glm::vec4(part.positions[v], 1.0f)));
    into.normals.push_back(glm::normalize(normalTransform * part.normals[v]));
    into.uvs.push_back(v < part.uvs.size() ? part.uvs[v] : glm::vec2(0.0f));
  }
  for (size_t t = 0; t + 2 < part.indices.size(); t += 3) {
    const uint32_t a = first + part.indices[t], b = first + part.indices[t + 1], c = first + part.indices[t + 2];
    if (mirrored)
      into.indices.insert(into.indices.end(), {a, c, b});
    else
      into.indices.insert(into.indices.end(), {a, b, c});
  }
}

Texture makeCheckerTexture(std::string name, uint32_t width, uint32_t height, uint32_t cellsX, uint32_t cellsY,
                           const glm::u8vec3& colorA, const glm::u8vec3& colorB) {
  Texture texture{std::move(name), width, height, std::vector<uint8_t>(size_t{width} * height * 4)};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool even = ((x * cellsX / width) + (y * cellsY / height)) % 2 == 0;
      const glm::u8vec3 c = even ? colorA : colorB;
      uint8_t* texel = &texture.rgba8[(size_t{y} * width + x) * 4];
      texel[0] = c.r;
      texel[1] = c.g;
      texel[2] = c.b;
      texel[3] = 255;
    }
  return texture;
}

Texture makeStripeTexture(std::string name, uint32_t width, uint32_t height, uint32_t stripes,
                          const glm::u8vec3& colorA, const glm::u8vec3& colorB) {
  // A checker with a single row of cells is a set of stripes.
  return makeCheckerTexture(std::move(name), width, height, stripes, 1, colorA, colorB);
}

}  // namespace hmb::scene::procedural
