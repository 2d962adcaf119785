// Binary FBX records (render/io/fbx_records.h).
#include "render/io/fbx_records.h"

#include <algorithm>
#include <cstring>

namespace sylva::fbx {
namespace {

constexpr size_t header_bytes = 27;
constexpr size_t null_record = 25;   // 64-bit offsets: end, count, bytes, name length

template <class T>
T read(const std::string& d, size_t at) {
  T v{};
  std::memcpy(&v, d.data() + at, sizeof v);
  return v;
}
template <class T>
void put(std::string& out, T v) {
  char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  out.append(b, sizeof v);
}

bool is_null(const std::string& d, size_t at) {
  if (at + null_record > d.size()) return false;
  for (size_t k = 0; k < null_record; ++k)
    if (d[at + k] != 0) return false;
  return true;
}

// One property from `at` (its type code) up to `end`; false when it runs past.
bool parse_property(const std::string& d, size_t& at, size_t end, property& p) {
  if (at >= end) return false;
  p.type = d[at++];
  size_t n = 0;
  switch (p.type) {
    case 'Y': n = 2; break;
    case 'C': n = 1; break;
    case 'I': case 'F': n = 4; break;
    case 'D': case 'L': n = 8; break;
    case 'S': case 'R':
      if (at + 4 > end) return false;
      n = 4 + size_t(read<uint32_t>(d, at));
      break;
    case 'f': case 'd': case 'l': case 'i': case 'b':
      if (at + 12 > end) return false;
      n = 12 + size_t(read<uint32_t>(d, at + 8));   // count, encoding, stored bytes
      break;
    default: return false;
  }
  if (n > end - at) return false;
  p.raw = d.substr(at, n);
  at += n;
  return true;
}

bool parse_record(const std::string& d, size_t at, size_t limit, size_t& end, record& r, int depth) {
  if (depth > 64 || at + null_record > limit) return false;
  const uint64_t e = read<uint64_t>(d, at), count = read<uint64_t>(d, at + 8), bytes = read<uint64_t>(d, at + 16);
  const size_t name = uint8_t(d[at + 24]);
  const size_t props = at + null_record + name;
  if (e > limit || props > e || bytes > e - props) return false;
  r.name = d.substr(at + null_record, name);
  size_t p = props;
  const size_t body = props + size_t(bytes);
  for (uint64_t k = 0; k < count; ++k) {
    property q;
    if (!parse_property(d, p, body, q)) return false;
    r.props.push_back(std::move(q));
  }
  if (p != body) return false;
  while (p < e) {
    if (p + null_record == e && is_null(d, p)) {
      r.closed = true;
      break;
    }
    record c;
    size_t ce = 0;
    if (!parse_record(d, p, e, ce, c, depth + 1)) return false;
    r.children.push_back(std::move(c));
    p = ce;
  }
  end = size_t(e);
  return true;
}

void write_record(const record& r, std::string& out) {
  const size_t at = out.size();
  out.append(8, '\0');   // the end offset, known once the children are written
  put<uint64_t>(out, r.props.size());
  size_t bytes = 0;
  for (const property& p : r.props) bytes += 1 + p.raw.size();
  put<uint64_t>(out, bytes);
  out.push_back(char(uint8_t(std::min<size_t>(r.name.size(), 255))));
  out.append(r.name, 0, 255);
  for (const property& p : r.props) {
    out.push_back(p.type);
    out += p.raw;
  }
  for (const record& c : r.children) write_record(c, out);
  if (!r.children.empty() || r.closed) out.append(null_record, '\0');
  const uint64_t end = out.size();
  std::memcpy(&out[at], &end, 8);
}

record prop70(std::string_view name, std::string_view type, std::string_view label, std::vector<property> values) {
  record r{"P", {str(name), str(type), str(label), str("")}, {}, false};
  for (property& v : values) r.props.push_back(std::move(v));
  return r;
}

}  // namespace

std::string parse(const std::string& d, document& out) {
  out = document{};
  if (d.size() < header_bytes + null_record || d.compare(0, 20, "Kaydara FBX Binary  ") != 0) return "not a binary FBX file";
  if (read<uint32_t>(d, 23) < 7500) return "FBX version " + std::to_string(read<uint32_t>(d, 23)) + " (32-bit offsets) is not read";
  out.header = d.substr(0, header_bytes);
  size_t p = header_bytes;
  while (!is_null(d, p)) {
    record r;
    size_t end = 0;
    if (!parse_record(d, p, d.size(), end, r, 0)) return "a record at byte " + std::to_string(p) + " does not parse";
    out.top.push_back(std::move(r));
    p = end;
    if (p + null_record > d.size()) return "the file ends before its last null record";
  }
  out.footer = d.substr(p);
  return "";
}

std::string write(const document& d) {
  std::string out = d.header;
  for (const record& r : d.top) write_record(r, out);
  out += d.footer;
  return out;
}

property str(std::string_view s) {
  property p{'S', {}};
  put<uint32_t>(p.raw, uint32_t(s.size()));
  p.raw.append(s);
  return p;
}
property i64(int64_t v) {
  property p{'L', {}};
  put(p.raw, v);
  return p;
}
property i32(int32_t v) {
  property p{'I', {}};
  put(p.raw, v);
  return p;
}
property f64(double v) {
  property p{'D', {}};
  put(p.raw, v);
  return p;
}

std::string as_string(const property& p) {
  return (p.type == 'S' || p.type == 'R') && p.raw.size() >= 4 ? p.raw.substr(4) : std::string();
}
int64_t as_int(const property& p) {
  switch (p.type) {
    case 'Y': return p.raw.size() == 2 ? read<int16_t>(p.raw, 0) : 0;
    case 'C': return p.raw.size() == 1 ? int64_t(uint8_t(p.raw[0])) : 0;
    case 'I': return p.raw.size() == 4 ? read<int32_t>(p.raw, 0) : 0;
    case 'L': return p.raw.size() == 8 ? read<int64_t>(p.raw, 0) : 0;
    default: return 0;
  }
}
double as_double(const property& p) {
  if (p.type == 'D' && p.raw.size() == 8) return read<double>(p.raw, 0);
  if (p.type == 'F' && p.raw.size() == 4) return double(read<float>(p.raw, 0));
  return double(as_int(p));
}

const record* find(const std::vector<record>& rs, std::string_view name) {
  for (const record& r : rs)
    if (r.name == name) return &r;
  return nullptr;
}
record* find(std::vector<record>& rs, std::string_view name) {
  for (record& r : rs)
    if (r.name == name) return &r;
  return nullptr;
}
const record* child(const record& r, std::string_view name) { return find(r.children, name); }
record* child(record& r, std::string_view name) { return find(r.children, name); }

std::string object_name(const record& r) {
  if (r.props.size() < 2) return "";
  const std::string n = as_string(r.props[1]);
  const size_t sep = n.find(std::string("\0\1", 2));
  return sep == std::string::npos ? n : n.substr(0, sep);
}

std::string make_lod_group(document& d, const std::string& group, const std::vector<double>& thresholds) {
  record* objects = find(d.top, "Objects");
  record* connections = find(d.top, "Connections");
  if (!objects || !connections) return "the file has no Objects or Connections";
  record* model = nullptr;
  int64_t next_id = 1;
  size_t attributes = 0;
  for (record& r : objects->children) {
    if (r.props.empty()) continue;
    next_id = std::max(next_id, as_int(r.props[0]) + 1);
    attributes += r.name == "NodeAttribute";
    if (r.name == "Model" && r.props.size() >= 3 && object_name(r) == group) model = &r;
  }
  if (!model) return "no model named " + group + " to hold the levels";
  const int64_t model_id = as_int(model->props[0]);
  size_t levels = 0;
  for (const record& c : connections->children)
    levels += c.props.size() >= 3 && as_string(c.props[0]) == "OO" && as_int(c.props[2]) == model_id;
  if (levels != thresholds.size() + 1)
    return "the model " + group + " holds " + std::to_string(levels) + " nodes, not the " + std::to_string(thresholds.size() + 1) +
           " levels (a forest's trees are levels of their own)";
  model->props[2] = str("LodGroup");

  record attr{"NodeAttribute", {i64(next_id), str(group + std::string("\0\1", 2) + "NodeAttribute"), str("LodGroup")}, {}, false};
  record p70{"Properties70", {}, {}, false};
  p70.children.push_back(prop70("Thresholds", "Compound", "", {}));
  for (size_t k = 0; k < thresholds.size(); ++k)
    p70.children.push_back(prop70("Thresholds|Level" + std::to_string(k), "Distance", "", {f64(thresholds[k]), str("cm")}));
  p70.children.push_back(prop70("ThresholdsUsedAsPercentage", "bool", "", {i32(1)}));
  p70.children.push_back(prop70("MinMaxDistance", "bool", "", {i32(0)}));
  p70.children.push_back(prop70("WorldSpace", "bool", "", {i32(0)}));
  p70.children.push_back(prop70("DisplayLevels", "Compound", "", {}));
  for (size_t k = 0; k < levels; ++k)
    p70.children.push_back(prop70("DisplayLevels|Level" + std::to_string(k), "enum", "", {i32(0)}));   // 0: UseLOD
  attr.children.push_back(std::move(p70));
  attr.children.push_back(record{"TypeFlags", {str("LodGroup")}, {}, false});
  const size_t at = size_t(model - objects->children.data());
  objects->children.insert(objects->children.begin() + std::ptrdiff_t(at), std::move(attr));
  connections->children.push_back(record{"C", {str("OO"), i64(next_id), i64(model_id)}, {}, false});

  // Definitions: the NodeAttribute count, and the total over every object type.
  if (record* defs = find(d.top, "Definitions")) {
    record* type = nullptr;
    for (record& r : defs->children)
      if (r.name == "ObjectType" && !r.props.empty() && as_string(r.props[0]) == "NodeAttribute") type = &r;
    if (!type) {
      defs->children.push_back(record{"ObjectType", {str("NodeAttribute")}, {}, false});
      type = &defs->children.back();
    }
    if (record* c = child(*type, "Count")) c->props = {i32(int32_t(attributes + 1))};
    else type->children.insert(type->children.begin(), record{"Count", {i32(int32_t(attributes + 1))}, {}, false});
    int64_t total = 0;
    for (const record& r : defs->children)
      if (r.name == "ObjectType")
        if (const record* c = child(r, "Count"); c && !c->props.empty()) total += as_int(c->props[0]);
    if (record* c = child(*defs, "Count")) c->props = {i32(int32_t(total))};
  }
  return "";
}

}  // namespace sylva::fbx
