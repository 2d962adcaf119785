// Preset JSON (docs/design/10-files.md) driven by visit_params (`--set`: preset_set.cpp; file
// writes: render/files.cpp).
#include "render/io/preset.h"
#include "render/io/preset_detail.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

#include "generators/lsystem_engine.h"

namespace sylva {
namespace {

using namespace preset_detail;

using json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Numbers: floats are written in their shortest round-trip form, so 0.77f saves as 0.77 rather
// than 0.7699999809265137 and loads back to the identical float.

double float_for_json(float f) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, f);
  *r.ptr = 0;
  return std::strtod(buf, nullptr);
}

const char* json_type_name(const json& j) {
  if (j.is_string()) return "a string";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_array()) return "an array";
  if (j.is_object()) return "an object";
  if (j.is_null()) return "null";
  return "an unsupported value";
}

// ---------------------------------------------------------------------------------------------
// Limits on what a document may hold (preset.h); a value's own limits are in preset_detail.h.

// Counts values and checks nesting and string sizes before the document is built, so a hostile
// file is refused while it still costs nothing. Syntax errors are left to the real parse.
struct preset_size_check : nlohmann::json_sax<json> {
  size_t values = 0;
  int depth = 0;
  std::string error;
  bool value() {
    if (++values <= max_preset_values) return true;
    error = "the preset holds more than " + std::to_string(max_preset_values) + " values (the limit)";
    return false;
  }
  bool text(const std::string& s) {
    if (s.size() <= max_preset_text_bytes) return value();
    error = "a string of " + mb_text(s.size()) + " is longer than the " + mb_text(max_preset_text_bytes) + " limit";
    return false;
  }
  bool open() {
    if (++depth <= 32) return value();
    error = "nested deeper than 32 levels";
    return false;
  }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t& s) override { return text(s); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(); }
  bool key(string_t& s) override { return text(s); }
  bool end_object() override { --depth; return true; }
  bool start_array(std::size_t) override { return open(); }
  bool end_array() override { --depth; return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }
};

// ---------------------------------------------------------------------------------------------
// One value <-> JSON, for every type params.h allows.

template <class T>
json value_to_json(const T& v, const param_info& info) {
  if constexpr (std::is_same_v<T, float>) {
    return float_for_json(v);
  } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, bool> || std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_enum_v<T>) {
    const int i = int(v);
    if (i >= 0 && i < option_count(info)) return info.options[i];
    return i;
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    return json::array({float_for_json(v.x), float_for_json(v.y), float_for_json(v.z)});
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    json a = json::array();
    for (float f : v) a.push_back(float_for_json(f));
    return a;
  } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
    json a = json::array();
    for (const glm::vec3& c : v) a.push_back(value_to_json(c, info));
    return a;
  } else {
    static_assert(sizeof(T) == 0, "value type not supported by preset JSON (see params.h)");
  }
}

bool json_to_float(const json& j, float& out) {
  if (!j.is_number()) return false;
  out = float(j.get<double>());  // beyond float's range becomes ±inf, which the clamp catches
  return true;
}

bool json_to_vec3(const json& j, glm::vec3& out) {
  if (!j.is_array() || j.size() != 3) return false;
  glm::vec3 v;
  for (int i = 0; i < 3; ++i)
    if (!json_to_float(j[size_t(i)], v[i])) return false;
  out = v;
  return true;
}

// Reads one value. Returns "" or a type error (without the key); appends soft problems to `notes`.
template <class T>
std::string json_to_value(const json& j, T& out, const param_info& info, std::vector<std::string>& notes) {
  if constexpr (std::is_same_v<T, float>) {
    if (!json_to_float(j, out)) return std::string("expected a number, got ") + json_type_name(j);
  } else if constexpr (std::is_same_v<T, int>) {
    if (!j.is_number()) return std::string("expected an integer, got ") + json_type_name(j);
    double d = j.get<double>();
    if (j.is_number_float() && d != std::floor(d)) {
      notes.push_back(format_number(d) + " is not an integer; rounded");
      d = std::round(d);
    }
    // Far outside int's range: park at the limits so the declared range clamps with a warning.
    d = std::clamp(d, double(std::numeric_limits<int>::min()), double(std::numeric_limits<int>::max()));
    out = int(d);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!j.is_boolean()) return std::string("expected true or false, got ") + json_type_name(j);
    out = j.get<bool>();
  } else if constexpr (std::is_enum_v<T>) {
    const int n = option_count(info);
    if (j.is_string()) {
      const std::string s = j.get<std::string>();
      for (int i = 0; i < n; ++i)
        if (s == info.options[i]) { out = T(i); return ""; }
      std::string names;
      for (int i = 0; i < n; ++i) names += std::string(i ? ", " : "") + info.options[i];
      notes.push_back("unknown option \"" + s + "\" (expected one of " + names + "); kept " +
                      (int(out) >= 0 && int(out) < n ? info.options[int(out)] : "the default"));
    } else if (j.is_number_integer()) {
      out = T(int(std::clamp<int64_t>(j.get<int64_t>(), -1, n)));  // the clamp below reports it
    } else {
      return std::string("expected an option name, got ") + json_type_name(j);
    }
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    if (!json_to_vec3(j, out)) return "expected [x, y, z]";
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!j.is_string()) return std::string("expected a string, got ") + json_type_name(j);
    if (std::string e = check_text(j.get_ref<const std::string&>()); !e.empty()) return e;
    out = j.get<std::string>();
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    if (!j.is_array()) return std::string("expected an array of numbers, got ") + json_type_name(j);
    if (j.size() > max_preset_list) return "more than " + std::to_string(max_preset_list) + " entries (the limit)";
    std::vector<float> v(j.size());
    for (size_t i = 0; i < j.size(); ++i)
      if (!json_to_float(j[i], v[i])) return "expected an array of numbers";
    out = std::move(v);
  } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
    if (!j.is_array()) return std::string("expected an array of [x, y, z], got ") + json_type_name(j);
    if (j.size() > max_preset_list) return "more than " + std::to_string(max_preset_list) + " entries (the limit)";
    std::vector<glm::vec3> v(j.size());
    for (size_t i = 0; i < j.size(); ++i)
      if (!json_to_vec3(j[i], v[i])) return "expected an array of [x, y, z]";
    out = std::move(v);
  } else {
    static_assert(sizeof(T) == 0, "value type not supported by preset JSON (see params.h)");
  }
  return "";
}

template <class P>
json params_to_json(const P& p) {
  json o = json::object();
  visit_params(p, [&](const auto& value, const param_info& info) { o[info.key] = value_to_json(value, info); });
  return o;
}

// Reads a section object into p. Returns "" or the first type error (naming section.key).
template <class P>
std::string params_from_json(const json& o, const std::string& section, P& p, std::vector<std::string>& warnings) {
  if (!o.is_object()) return quote_text(section) + " must be an object, got " + json_type_name(o);
  std::set<std::string> known;
  std::string error;
  visit_params(p, [&](auto& value, const param_info& info) {
    known.insert(info.key);
    if (!error.empty()) return;
    auto it = o.find(info.key);
    if (it == o.end()) return;  // missing: keeps its default
    const std::string name = section + "." + info.key;
    std::vector<std::string> notes;
    auto v = value;
    if (std::string e = json_to_value(*it, v, info, notes); !e.empty()) {
      error = name + ": " + e;
      return;
    }
    for (const std::string& n : notes) warnings.push_back(name + ": " + n);
    if (!clamp_param(v, info)) {
      std::string shown = it->dump();
      if (shown.size() > 40) shown = shown.substr(0, 37) + "...";
      warnings.push_back(name + ": " + shown + " is outside " + range_text(info) + "; clamped");
    }
    value = std::move(v);
  });
  if (!error.empty()) return error;
  for (auto it = o.begin(); it != o.end(); ++it)
    if (!known.count(it.key())) warnings.push_back(section + "." + it.key() + ": unknown key, ignored");
  return "";
}

// ---------------------------------------------------------------------------------------------
// Growth phases: "keyframes": [{"step": k, "key": "...", "value": v}], v typed as its parameter.

json keyframes_to_json(const tree_spec& spec) {
  json a = json::array();
  for (const keyframe& k : spec.keyframes) {
    json v = float_for_json(k.value.x);
    with_keyable(spec, k.key, [&](auto& value, const param_info& info) {
      from_key_value(k.value, value);
      v = value_to_json(value, info);
    });
    a.push_back(json{{"step", k.step}, {"key", k.key}, {"value", v}});
  }
  return a;
}

// Reads the list into spec.keyframes (after its params); every keyframe passes check_keyframe.
std::string keyframes_from_json(const json& a, tree_spec& spec, std::vector<std::string>& warnings) {
  if (!a.is_array()) return std::string("keyframes: expected an array, got ") + json_type_name(a);
  if (a.size() > max_preset_list) return "keyframes: more than " + std::to_string(max_preset_list) + " entries";
  for (size_t i = 0; i < a.size(); ++i) {
    const json& o = a[i];
    const std::string at = "keyframes[" + std::to_string(i) + "]";
    if (!o.is_object()) return at + ": expected an object {\"step\", \"key\", \"value\"}, got " + json_type_name(o);
    auto step = o.find("step"), key = o.find("key"), value = o.find("value");
    if (step == o.end() || !step->is_number_integer()) return at + ": \"step\" must be an integer";
    if (key == o.end() || !key->is_string()) return at + ": \"key\" must be a string";
    if (value == o.end()) return at + ": \"value\" is missing";
    keyframe k;
    k.step = int(std::clamp<int64_t>(step->get<int64_t>(), -1, 1000000));
    k.key = key->get<std::string>();
    std::string error;
    with_keyable(spec, k.key, [&](auto& v, const param_info& info) {
      std::vector<std::string> notes;
      error = json_to_value(*value, v, info, notes);
      for (const std::string& n : notes) warnings.push_back(at + ": " + n);
      k.value = to_key_value(v);
    });
    if (!error.empty()) return at + " (" + k.key + "): " + error;
    for (auto it = o.begin(); it != o.end(); ++it)
      if (it.key() != "step" && it.key() != "key" && it.key() != "value")
        warnings.push_back(at + "." + it.key() + ": unknown key, ignored");
    // check_keyframe also refuses a second value for a key at one step (set_keyframe would replace it).
    if (std::string e = check_keyframe(spec, k); !e.empty()) return e;
    set_keyframe(spec, k);
  }
  return "";
}

// Pruning: "cuts": [{"step": k, "shape": "branch", "point": [x, y, z], "reach": r}] or, for a
// brush, {"step": k, "shape": "outside_box", "point": [...], "size": [...]}.
json cuts_to_json(const tree_spec& spec) {
  json a = json::array();
  for (const prune_cut& c : spec.cuts) {
    json o = {{"step", c.step}, {"shape", prune_shape_names[int(c.shape)]},
              {"point", json::array({float_for_json(c.point.x), float_for_json(c.point.y), float_for_json(c.point.z)})}};
    if (c.shape == prune_shape::branch) o["reach"] = float_for_json(c.reach);
    else o["size"] = json::array({float_for_json(c.size.x), float_for_json(c.size.y), float_for_json(c.size.z)});
    a.push_back(std::move(o));
  }
  return a;
}

std::string cuts_from_json(const json& a, tree_spec& spec, std::vector<std::string>& warnings) {
  if (!a.is_array()) return std::string("cuts: expected an array, got ") + json_type_name(a);
  if (a.size() > max_preset_list) return "cuts: more than " + std::to_string(max_preset_list) + " entries";
  for (size_t i = 0; i < a.size(); ++i) {
    const json& o = a[i];
    const std::string at = "cuts[" + std::to_string(i) + "]";
    if (!o.is_object()) return at + ": expected an object, got " + json_type_name(o);
    prune_cut c;
    auto step = o.find("step");
    if (step == o.end() || !step->is_number_integer()) return at + ": \"step\" must be an integer";
    c.step = int(std::clamp<int64_t>(step->get<int64_t>(), -1, 1000000));
    if (auto it = o.find("shape"); it != o.end()) {
      int shape = -1;
      for (int k = 0; it->is_string() && prune_shape_names[k]; ++k)
        if (it->get<std::string>() == prune_shape_names[k]) shape = k;
      if (shape < 0) return at + ": \"shape\" must be one of branch, outside_ellipsoid, outside_box";
      c.shape = prune_shape(shape);
    }
    auto point = o.find("point");
    if (point == o.end() || !json_to_vec3(*point, c.point)) return at + ": \"point\" must be [x, y, z]";
    if (auto it = o.find("size"); it != o.end() && !json_to_vec3(*it, c.size)) return at + ": \"size\" must be [x, y, z]";
    if (auto it = o.find("reach"); it != o.end() && !json_to_float(*it, c.reach)) return at + ": \"reach\" must be a number";
    for (auto it = o.begin(); it != o.end(); ++it)
      if (it.key() != "step" && it.key() != "shape" && it.key() != "point" && it.key() != "size" && it.key() != "reach")
        warnings.push_back(at + "." + it.key() + ": unknown key, ignored");
    // A branch cut has a reach and a brush a size; the other is not saved, so it is not kept.
    const bool branch = c.shape == prune_shape::branch;
    if (o.contains(branch ? "size" : "reach")) {
      warnings.push_back(at + (branch ? ".size: a branch cut has a reach, not a size; ignored"
                                      : ".reach: a brush has a size, not a reach; ignored"));
      if (branch) c.size = prune_cut{}.size;
      else c.reach = prune_cut{}.reach;
    }
    if (std::string e = add_cut(spec, c); !e.empty()) return at + ": " + e;
  }
  return "";
}

// ---------------------------------------------------------------------------------------------
// Versions. upgrade_steps[v - 1] turns a version-v document into version v+1; when the schema
// changes, bump preset_version and append one step (renamed keys, changed units ...), so a file
// of any older version is walked forward one version at a time before it is read.

using upgrade_step = std::function<void(json&, std::vector<std::string>&)>;
const std::vector<upgrade_step>& upgrade_steps() {
  static const std::vector<upgrade_step> steps;  // version 1 is the first schema: nothing to upgrade yet
  return steps;
}

std::string newer_version_text(const std::string& version) {
  return "written by a newer Sylva (preset version " + version + ", this one reads " + std::to_string(preset_version) +
         "); unknown keys are ignored";
}

std::string upgrade_preset(json& doc, int64_t version, std::vector<std::string>& warnings) {
  if (version < 1) return "sylva_preset version " + std::to_string(version) + " is not valid (expected >= 1)";
  if (version > preset_version) {
    warnings.push_back(newer_version_text(std::to_string(version)));
    return "";
  }
  for (int64_t v = version; v < preset_version; ++v) {
    if (size_t(v - 1) >= upgrade_steps().size()) return "no upgrade from preset version " + std::to_string(v);
    upgrade_steps()[size_t(v - 1)](doc, warnings);
    warnings.push_back("upgraded from preset version " + std::to_string(v) + " to " + std::to_string(v + 1));
  }
  return "";
}

std::string parse_error_text(std::string_view text, const nlohmann::json::parse_error& e) {
  // nlohmann reports a byte offset (1-based, one past the failure); turn it into line:column.
  const size_t byte = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
  size_t line = 1, col = 1;
  for (size_t i = 0; i < byte; ++i) {
    if (text[i] == '\n') { ++line; col = 1; }
    else ++col;
  }
  std::string what = e.what();
  // Keep only the reason after nlohmann's own "parse error at line L, column C: " prefix.
  if (auto p = what.find(": "); p != std::string::npos && what.compare(0, 15, "[json.exception") == 0)
    what = what.substr(p + 2);
  const bool truncated = byte >= text.size();
  return "malformed JSON at line " + std::to_string(line) + ", column " + std::to_string(col) +
         (truncated ? " (the file ends too early)" : "") + ": " + what;
}

load_result load_preset_doc(json& doc, preset& out) {
  load_result r;
  auto fail = [&](std::string e) { r.error = std::move(e); r.ok = false; return r; };
  if (!doc.is_object()) return fail(std::string("a preset must be a JSON object, got ") + json_type_name(doc));

  int64_t version = preset_version;
  if (auto it = doc.find("sylva_preset"); it == doc.end()) {
    r.warnings.push_back("no \"sylva_preset\" version; read as version " + std::to_string(preset_version));
  } else if (!it->is_number_integer()) {
    return fail(std::string("sylva_preset: expected an integer version, got ") + json_type_name(*it));
  } else if (it->is_number_unsigned() && it->get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max())) {
    // Read as int64_t, 18446744073709551615 would become -1 and be called invalid.
    r.warnings.push_back(newer_version_text(std::to_string(it->get<uint64_t>())));
    version = preset_version;
  } else {
    version = it->get<int64_t>();
  }
  if (std::string e = upgrade_preset(doc, version, r.warnings); !e.empty()) return fail(e);

  preset p;  // built aside so `out` stays untouched on error
  auto get_string = [&](const char* key, std::string& dst) -> std::string {
    auto it = doc.find(key);
    if (it == doc.end()) return "";
    if (!it->is_string()) return std::string(key) + ": expected a string, got " + json_type_name(*it);
    if (std::string e = check_text(it->get_ref<const std::string&>()); !e.empty()) return std::string(key) + ": " + e;
    dst = it->get<std::string>();
    return "";
  };
  if (std::string e = get_string("name", p.name); !e.empty()) return fail(e);
  if (std::string e = get_string("description", p.description); !e.empty()) return fail(e);
  if (auto it = doc.find("tags"); it != doc.end()) {
    if (!it->is_array()) return fail(std::string("tags: expected an array of strings, got ") + json_type_name(*it));
    if (it->size() > max_preset_tags)
      return fail("tags: " + std::to_string(it->size()) + " tags, more than the limit of " +
                  std::to_string(max_preset_tags));
    for (const json& t : *it) {
      if (!t.is_string()) return fail("tags: expected an array of strings");
      if (std::string e = check_text(t.get_ref<const std::string&>()); !e.empty()) return fail("tags: " + e);
      p.tags.push_back(t.get<std::string>());
    }
  }
  if (auto it = doc.find("generator"); it != doc.end()) {
    if (!it->is_string()) return fail(std::string("generator: expected a string, got ") + json_type_name(*it));
    const int g = generator_index(it->get<std::string>());
    if (g < 0) {
      std::string names;
      for (int i = 0; generator_names[i]; ++i) names += std::string(i ? ", " : "") + generator_names[i];
      return fail("generator: unknown generator \"" + it->get<std::string>() + "\" (expected one of " + names + ")");
    }
    p.spec.params = default_params(g);
  }
  if (auto it = doc.find("seed"); it != doc.end()) {
    if (it->is_number_unsigned()) p.spec.seed = it->get<uint64_t>();
    else if (it->is_number_integer()) {
      r.warnings.push_back("seed: " + it->dump() + " is negative; clamped to 0");
      p.spec.seed = 0;
    } else return fail(std::string("seed: expected a non-negative integer, got ") + json_type_name(*it));
  }
  static const json empty = json::object();
  auto section = [&](const char* key) -> const json& {
    auto it = doc.find(key);
    return it == doc.end() ? empty : *it;
  };
  std::string e = std::visit([&](auto& gp) { return params_from_json(section("params"), "params", gp, r.warnings); },
                             p.spec.params);
  if (!e.empty()) return fail(e);
  if (e = params_from_json(section("mesh"), "mesh", p.mesh, r.warnings); !e.empty()) return fail(e);
  if (e = params_from_json(section("render"), "render", p.render, r.warnings); !e.empty()) return fail(e);
  // A preset without a "wood" section (every preset older than the bending pass) loads with the pass off.
  if (e = params_from_json(section("wood"), "wood", p.spec.wood, r.warnings); !e.empty()) return fail(e);

  if (auto it = doc.find("keyframes"); it != doc.end())
    if (e = keyframes_from_json(*it, p.spec, r.warnings); !e.empty()) return fail(e);
  if (auto it = doc.find("cuts"); it != doc.end())
    if (e = cuts_from_json(*it, p.spec, r.warnings); !e.empty()) return fail(e);

  static const std::set<std::string> top = {"sylva_preset", "name", "description", "tags", "generator",
                                            "seed",         "params", "mesh",      "render",    "wood", "keyframes", "cuts"};
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (!top.count(it.key())) r.warnings.push_back(it.key() + ": unknown key, ignored");

  out = std::move(p);
  r.ok = true;
  return r;
}

}  // namespace

load_result load_preset_json(std::string_view text, preset& out) {
  json doc;
  if (text.size() > max_preset_bytes) {
    load_result r;
    r.error = "the preset is larger than the " + mb_text(max_preset_bytes) + " limit";
    return r;
  }
  try {
    preset_size_check check;
    json::sax_parse(text.begin(), text.end(), &check);
    if (!check.error.empty()) {
      load_result r;
      r.error = check.error;
      return r;
    }
  } catch (const std::exception&) {  // reported with its position by the parse below
  }
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    load_result r;
    r.error = parse_error_text(text, e);
    return r;
  } catch (const std::exception& e) {  // e.g. a number beyond a double's range
    load_result r;
    std::string what = e.what();
    if (what.compare(0, 15, "[json.exception") == 0 && what.find("] ") != std::string::npos)
      what = what.substr(what.find("] ") + 2);
    r.error = "unreadable JSON: " + what;
    return r;
  }
  try {
    return load_preset_doc(doc, out);
  } catch (const std::exception& e) {  // a json type accessor we did not guard: still no throw out
    load_result r;
    r.error = std::string("unreadable preset: ") + e.what();
    return r;
  }
}

load_result load_preset_file(const std::string& path, preset& out) {
  std::string text;
  if (std::string e = read_file(path, text, max_preset_bytes); !e.empty()) {
    load_result r;
    r.error = e;
    return r;
  }
  load_result r = load_preset_json(text, out);
  if (!r.ok) r.error = path + ": " + r.error;
  return r;
}

std::string save_preset_json(const preset& p) {
  json doc = json::object();
  doc["sylva_preset"] = preset_version;
  doc["name"] = p.name;
  doc["description"] = p.description;
  doc["tags"] = p.tags;
  doc["generator"] = generator_name(p.spec);
  doc["seed"] = p.spec.seed;
  doc["params"] = std::visit([](const auto& gp) { return params_to_json(gp); }, p.spec.params);
  doc["mesh"] = params_to_json(p.mesh);
  doc["render"] = params_to_json(p.render);
  doc["wood"] = params_to_json(p.spec.wood);
  if (!p.spec.keyframes.empty()) doc["keyframes"] = keyframes_to_json(p.spec);
  if (!p.spec.cuts.empty()) doc["cuts"] = cuts_to_json(p.spec);
  return doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

std::string save_preset_file(const preset& p, const std::string& path) {
  return write_file_atomic(path, save_preset_json(p));
}

bool valid_utf8(std::string_view s) {
  const auto* b = reinterpret_cast<const unsigned char*>(s.data());
  const size_t n = s.size();
  for (size_t i = 0; i < n;) {
    const unsigned c = b[i];
    if (c < 0x80) { ++i; continue; }
    size_t len;
    unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) { len = 3; if (c == 0xE0) lo = 0xA0; if (c == 0xED) hi = 0x9F; }
    else if (c >= 0xF0 && c <= 0xF4) { len = 4; if (c == 0xF0) lo = 0x90; if (c == 0xF4) hi = 0x8F; }
    else return false;
    if (n - i < len || b[i + 1] < lo || b[i + 1] > hi) return false;
    for (size_t k = 2; k < len; ++k)
      if ((b[i + k] & 0xC0) != 0x80) return false;
    i += len;
  }
  return true;
}

preset default_preset() {
  preset p;
  p.name = "Honda tree a";
  p.description = "Honda's binary tree a (Prusinkiewicz et al. 1996, Table 1): the built-in default.";
  p.tags = {"lsystem", "honda", "paper"};
  p.spec.params = lsystem_params{};
  return p;
}

}  // namespace sylva
