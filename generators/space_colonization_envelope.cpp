// Envelopes for space colonization: analytic shapes and closed OBJ meshes, seeded uniform sampling, outlines.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>

#include "generators/history.h"
#include "generators/space_colonization.h"

namespace sylva {
namespace {

// A triangle soup normalised into [-1,1]^3 with a (y,z) bin grid for +x ray casts.
struct envelope_mesh_data {
  std::vector<glm::vec3> v;
  std::vector<glm::ivec3> tri;
  std::vector<std::pair<int, int>> edges;  // unique undirected edges, for the outline
  int bins = 1;
  std::vector<int> bin_begin, bin_tri;
};

// Reads a regular file of at most max_envelope_mesh_bytes: a device such as /dev/zero or a FIFO
// would otherwise be read until memory runs out. The type is checked before opening, so a FIFO
// without a writer cannot block; the read itself also stops at the limit.
std::string read_envelope_text(const std::string& path, std::string& text) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) return "cannot open envelope mesh '" + path + "'";
  const std::string limit = std::to_string(max_envelope_mesh_bytes >> 20) + " MB limit";
  if (!fs::is_regular_file(st))
    return "envelope mesh '" + path + "' is not a regular file (a folder, device, FIFO or socket)";
  if (fs::file_size(path, ec) > max_envelope_mesh_bytes && !ec)
    return "envelope mesh '" + path + "' is larger than the " + limit;
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open envelope mesh '" + path + "'";
  char buf[1 << 16];
  while (in.read(buf, sizeof buf), in.gcount() > 0) {
    text.append(buf, size_t(in.gcount()));
    if (text.size() > max_envelope_mesh_bytes) return "envelope mesh '" + path + "' is larger than the " + limit;
  }
  if (in.bad()) return "cannot read envelope mesh '" + path + "'";
  return "";
}

// Reads positions and faces; welds equal positions so that UV seams do not look like holes.
// `what` names the source in messages ("envelope mesh 'path'").
std::string parse_envelope_obj(std::string_view text, const std::string& what, envelope_mesh_data& m) {
  std::vector<glm::vec3> raw;
  std::vector<int> weld;
  std::map<std::tuple<float, float, float>, int> seen;
  int line_no = 0;
  for (size_t pos = 0; pos < text.size();) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string line(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      glm::vec3 q;
      if (!(ls >> q.x >> q.y >> q.z) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        return what + " line " + std::to_string(line_no) + ": bad vertex";
      raw.push_back(q);
      auto [it, fresh] = seen.emplace(std::make_tuple(q.x, q.y, q.z), int(m.v.size()));
      if (fresh) m.v.push_back(q);
      weld.push_back(it->second);
    } else if (tag == "f") {
      std::vector<int> f;
      std::string tok;
      while (ls >> tok) {
        long idx = std::strtol(tok.c_str(), nullptr, 10);  // "7/2/5" -> 7
        if (idx < 0) idx += long(raw.size()) + 1;           // OBJ relative indices
        if (idx < 1 || idx > long(raw.size()))
          return what + " line " + std::to_string(line_no) + ": face index out of range";
        f.push_back(weld[size_t(idx - 1)]);
      }
      if (f.size() < 3) return what + " line " + std::to_string(line_no) + ": face with < 3 vertices";
      for (size_t k = 1; k + 1 < f.size(); ++k) m.tri.push_back({f[0], f[k], f[k + 1]});
    }
  }
  if (m.tri.empty()) return what + " has no faces";
  // Closed (watertight) means every edge is shared by exactly two triangles; the parity inside test
  // below is only meaningful then.
  std::map<std::pair<int, int>, int> count;
  for (const glm::ivec3& t : m.tri)
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      if (a == b) continue;
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [e, c] : count)
    if (c != 2)
      return what + " is not closed: edge " + std::to_string(e.first + 1) + "-" +
             std::to_string(e.second + 1) + " is shared by " + std::to_string(c) +
             " face(s), not 2; the inside test needs a watertight mesh";
  for (const auto& [e, c] : count) m.edges.push_back(e);
  // Normalise into [-1,1]^3 so that `size` and `offset` place it like the analytic shapes.
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& q : m.v) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const glm::vec3 ext = hi - lo;
  if (!(ext.x > 0 && ext.y > 0 && ext.z > 0)) return what + " is flat: it encloses no volume";
  if (!std::isfinite(ext.x) || !std::isfinite(ext.y) || !std::isfinite(ext.z))
    return what + " spans more than a float can hold";
  for (glm::vec3& q : m.v) q = (q - lo) / ext * 2.0f - 1.0f;
  // Bin triangles by their (y,z) bounds, padded for the ray's slight tilt.
  m.bins = std::clamp(int(std::sqrt(float(m.tri.size()))), 1, 128);
  const float pad = 2e-3f, scale = float(m.bins) / 2.0f;
  auto bin_of = [&](float c) { return std::clamp(int((c + 1.0f) * scale), 0, m.bins - 1); };
  std::vector<std::vector<int>> bins(size_t(m.bins * m.bins));
  for (size_t k = 0; k < m.tri.size(); ++k) {
    const glm::vec3 a = m.v[m.tri[k][0]], b = m.v[m.tri[k][1]], c = m.v[m.tri[k][2]];
    const int y0 = bin_of(std::min({a.y, b.y, c.y}) - pad), y1 = bin_of(std::max({a.y, b.y, c.y}) + pad);
    const int z0 = bin_of(std::min({a.z, b.z, c.z}) - pad), z1 = bin_of(std::max({a.z, b.z, c.z}) + pad);
    for (int z = z0; z <= z1; ++z)
      for (int y = y0; y <= y1; ++y) bins[size_t(z * m.bins + y)].push_back(int(k));
  }
  m.bin_begin.assign(bins.size() + 1, 0);
  for (size_t b = 0; b < bins.size(); ++b) m.bin_begin[b + 1] = m.bin_begin[b] + int(bins[b].size());
  for (const auto& b : bins) m.bin_tri.insert(m.bin_tri.end(), b.begin(), b.end());
  return "";
}

// Ray parity along a slightly tilted +x ray (the tilt keeps it off edges and vertices of axis-aligned
// meshes); Möller & Trumbore 1997 ray-triangle test.
bool inside_mesh(const envelope_mesh_data& m, const glm::vec3& q) {
  const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 3.1e-4f, 1.7e-4f));
  const float scale = float(m.bins) / 2.0f;
  const int by = std::clamp(int((q.y + 1.0f) * scale), 0, m.bins - 1);
  const int bz = std::clamp(int((q.z + 1.0f) * scale), 0, m.bins - 1);
  const int b = bz * m.bins + by;
  int hits = 0;
  for (int k = m.bin_begin[b]; k < m.bin_begin[b + 1]; ++k) {
    const glm::ivec3 t = m.tri[size_t(m.bin_tri[size_t(k)])];
    const glm::vec3 a = m.v[t[0]], e1 = m.v[t[1]] - a, e2 = m.v[t[2]] - a;
    const glm::vec3 pv = glm::cross(dir, e2);
    const float det = glm::dot(e1, pv);
    if (std::fabs(det) < 1e-12f) continue;
    const float inv = 1.0f / det;
    const glm::vec3 tv = q - a;
    const float u = glm::dot(tv, pv) * inv;
    if (u < 0 || u > 1) continue;
    const glm::vec3 qv = glm::cross(tv, e1);
    const float w = glm::dot(dir, qv) * inv;
    if (w < 0 || u + w > 1) continue;
    if (glm::dot(e2, qv) * inv > 0) ++hits;
  }
  return hits & 1;
}

// The flame's radius (share of the half-width) at t = 0 (bottom) .. 1 (top): a quarter ellipse up
// to its widest at t = 0.25, then (1 - u)^0.6 over the remaining height u, an ogive to the point.
// With 0.85 (nearly a cone) the top tenth held so few attraction points that the poplar's leader
// rose through it as a bare whip with a few leaves (rounds 32-35: "the leader ends in a bare
// whippy stem with a few floating leaves"); 0.6 gives that tenth about three times the volume.
float flame_radius(float t) {
  constexpr float widest = 0.25f;
  if (t < 0.0f || t > 1.0f) return 0.0f;
  if (t < widest) {
    const float d = (widest - t) / widest;
    return std::sqrt(std::max(0.0f, 1.0f - d * d));
  }
  return std::pow(1.0f - (t - widest) / (1.0f - widest), 0.6f);
}

// Inside test in the envelope's normalised box [-1,1]^3.
bool inside_shape(envelope_shape s, const glm::vec3& q, const envelope_mesh_data* m) {
  switch (s) {
    case envelope_shape::box:
    case envelope_shape::slab: return true;
    case envelope_shape::sphere:
    case envelope_shape::ellipsoid: return glm::dot(q, q) <= 1.0f;
    case envelope_shape::hemisphere: {  // flat base at y = -1, dome up to y = +1
      const float y = (q.y + 1.0f) * 0.5f;
      return q.x * q.x + y * y + q.z * q.z <= 1.0f;
    }
    case envelope_shape::cylinder: return q.x * q.x + q.z * q.z <= 1.0f;
    case envelope_shape::cone: {  // base at y = -1, apex at y = +1
      const float f = (1.0f - q.y) * 0.5f;
      return q.x * q.x + q.z * q.z <= f * f;
    }
    case envelope_shape::mesh: return m && inside_mesh(*m, q);
    case envelope_shape::flame: {
      const float r = flame_radius((q.y + 1.0f) * 0.5f);
      return q.x * q.x + q.z * q.z <= r * r;
    }
  }
  return false;
}

glm::vec3 half_extent(const space_colonization_params& p) {
  switch (p.envelope) {
    case envelope_shape::sphere: return glm::vec3(p.size.x * 0.5f);
    case envelope_shape::slab: return glm::vec3(p.size.x, p.size.y, p.slab_thickness) * 0.5f;
    default: return p.size * 0.5f;
  }
}

// Appends an elliptic arc centre + cos·a + sin·b for t in [t0, t1] as line pairs.
void add_arc(std::vector<glm::vec3>& out, glm::vec3 c, glm::vec3 a, glm::vec3 b, float t0, float t1, int segs) {
  for (int i = 0; i < segs; ++i) {
    const float u0 = t0 + (t1 - t0) * float(i) / float(segs), u1 = t0 + (t1 - t0) * float(i + 1) / float(segs);
    out.push_back(c + std::cos(u0) * a + std::sin(u0) * b);
    out.push_back(c + std::cos(u1) * a + std::sin(u1) * b);
  }
}

// The outline in normalised coordinates.
std::vector<glm::vec3> outline_shape(envelope_shape s, const envelope_mesh_data* m) {
  std::vector<glm::vec3> o;
  const float pi = 3.14159265f;
  const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1), O(0);
  auto box = [&] {
    for (int axis = 0; axis < 3; ++axis)
      for (int a = -1; a <= 1; a += 2)
        for (int b = -1; b <= 1; b += 2) {
          glm::vec3 p0(0), p1(0);
          p0[axis] = -1, p1[axis] = 1;
          p0[(axis + 1) % 3] = p1[(axis + 1) % 3] = float(a);
          p0[(axis + 2) % 3] = p1[(axis + 2) % 3] = float(b);
          o.push_back(p0), o.push_back(p1);
        }
  };
  switch (s) {
    case envelope_shape::box:
    case envelope_shape::slab: box(); break;
    case envelope_shape::sphere:
    case envelope_shape::ellipsoid:
      add_arc(o, O, X, Z, 0, 2 * pi, 48), add_arc(o, O, X, Y, 0, 2 * pi, 48), add_arc(o, O, Z, Y, 0, 2 * pi, 48);
      break;
    case envelope_shape::hemisphere:
      add_arc(o, -Y, X, Z, 0, 2 * pi, 48), add_arc(o, -Y, X, 2.0f * Y, 0, pi, 24), add_arc(o, -Y, Z, 2.0f * Y, 0, pi, 24);
      break;
    case envelope_shape::cylinder:
      add_arc(o, -Y, X, Z, 0, 2 * pi, 48), add_arc(o, Y, X, Z, 0, 2 * pi, 48);
      for (glm::vec3 d : {X, -X, Z, -Z}) o.push_back(d - Y), o.push_back(d + Y);
      break;
    case envelope_shape::cone:
      add_arc(o, -Y, X, Z, 0, 2 * pi, 48);
      for (glm::vec3 d : {X, -X, Z, -Z}) o.push_back(d - Y), o.push_back(Y);
      break;
    case envelope_shape::flame: {   // the widest ring and two profiles
      add_arc(o, -0.5f * Y, X, Z, 0, 2 * pi, 48);
      for (glm::vec3 d : {X, -X, Z, -Z})
        for (int i = 0; i < 24; ++i) {
          const float t0 = float(i) / 24, t1 = float(i + 1) / 24;
          o.push_back(d * flame_radius(t0) + Y * (2 * t0 - 1)), o.push_back(d * flame_radius(t1) + Y * (2 * t1 - 1));
        }
      break;
    }
    case envelope_shape::mesh:
      if (m)
        for (size_t k = 0; k < m->edges.size() && k < 50000; ++k)
          o.push_back(m->v[size_t(m->edges[k].first)]), o.push_back(m->v[size_t(m->edges[k].second)]);
      break;
  }
  return o;
}

}  // namespace

std::string check_envelope_obj(std::string_view text, const std::vector<glm::vec3>& queries,
                               std::vector<bool>* inside) {
  envelope_mesh_data mesh;
  if (std::string e = parse_envelope_obj(text, "envelope mesh", mesh); !e.empty()) return e;
  if (inside) {
    inside->clear();
    for (const glm::vec3& q : queries) inside->push_back(inside_mesh(mesh, q));
  }
  return "";
}

// Seeded dents: bays cut into the envelope from outside. Each dent is a direction c in the
// normalised box and a depth; a point in direction d (from the box centre) is kept only within the
// shape scaled by 1 - depth * bump(d.c), bump rising smoothly from 0 at the cap's rim to 1 on its
// axis. The caps together cover about a third of the directions, whatever their count.
namespace {
struct envelope_dents {
  std::vector<glm::vec3> dir;
  std::vector<float> depth;
  float rim = 1;  // cosine of the caps' half-angle

  envelope_dents(int count, float depth_max, uint64_t seed) {
    if (count <= 0 || !(depth_max > 0)) return;
    rim = 1.0f - 0.7f / float(count);
    rng r(seed ^ 0xd3e7b5a1c0ffee11ull);
    for (int k = 0; k < count; ++k) {
      // A uniform direction on the sphere (z uniform in [-1, 1], azimuth uniform).
      const float z = r.uniform(-1, 1), a = r.uniform(0, 6.2831853f), rho = std::sqrt(std::max(0.0f, 1 - z * z));
      dir.emplace_back(rho * std::cos(a), z, rho * std::sin(a));
      depth.push_back(depth_max * r.uniform(0.5f, 1.0f));
    }
  }
  // The factor on the shape's radius in the direction of q (1: no dent there).
  float scale(const glm::vec3& q) const {
    const float len = glm::length(q);
    if (dir.empty() || !(len > 1e-6f)) return 1.0f;
    float cut = 0;
    for (size_t k = 0; k < dir.size(); ++k) {
      const float u = std::clamp((glm::dot(q, dir[k]) / len - rim) / (1 - rim), 0.0f, 1.0f);
      cut = std::max(cut, depth[k] * u * u * (3 - 2 * u));
    }
    return 1.0f - cut;
  }
};
}  // namespace

envelope_sample sample_envelope(const space_colonization_params& p_in, uint64_t seed, bool want_outline) {
  space_colonization_params p = p_in;
  clamp_all_params(p);
  envelope_sample out;
  envelope_mesh_data mesh;
  const bool is_mesh = p.envelope == envelope_shape::mesh;
  if (is_mesh) {
    if (p.envelope_mesh.empty()) {
      out.error = "envelope is 'mesh' but envelope_mesh (an OBJ path) is empty";
      return out;
    }
    std::string text;
    out.error = read_envelope_text(p.envelope_mesh, text);
    if (out.error.empty()) out.error = parse_envelope_obj(text, "envelope mesh '" + p.envelope_mesh + "'", mesh);
    if (!out.error.empty()) return out;
  }
  const glm::vec3 h = half_extent(p);
  // Rejection sampling from the bounding box is uniform inside the shape; the attempt limit keeps a
  // mesh with a tiny volume from spinning forever.
  rng r(seed ^ 0xe1e7e10feull);
  const envelope_dents dents(p.envelope_dents, p.envelope_dent_depth, seed);
  const glm::vec3 open = open_side_direction(p.open_side);
  out.points.reserve(size_t(p.points));
  const int64_t max_tries = int64_t(p.points) * 200 + 1000;
  for (int64_t tries = 0; int64_t(out.points.size()) < p.points && tries < max_tries; ++tries) {
    const glm::vec3 q(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    const float k = dents.scale(q);
    if (!inside_shape(p.envelope, q / k, is_mesh ? &mesh : nullptr)) continue;
    // Fewer points on the shaded side of a tree that leans to open sky (history.h, Loehle 1986);
    // no draw at all without a lean, so such a tree's points are as before.
    if (p.sky_lean > 0 && !(r.uniform() < sky_keep_chance(q, p.sky_lean, open))) continue;
    out.points.push_back(p.offset + q * h);
  }
  if (int64_t(out.points.size()) < p.points)
    out.error = "the envelope mesh encloses too little volume: only " + std::to_string(out.points.size()) + " of " +
                std::to_string(p.points) + " points landed inside";
  if (want_outline) {
    out.outline = outline_shape(p.envelope, is_mesh ? &mesh : nullptr);
    for (glm::vec3& q : out.outline) q = p.offset + q * h;
  }
  return out;
}

}  // namespace sylva
