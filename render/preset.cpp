// Preset JSON (DESIGN §6) driven by visit_params, `--set` assignments, and atomic file writes.
#include "render/preset.h"

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

std::string format_number(double d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", d);
  return buf;
}

// Built with += because GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
std::string range_text(const param_info& info) {
  std::string r = "[";
  r += format_number(info.min);
  r += ", ";
  r += format_number(info.max);
  r += ']';
  return r;
}

std::string quote_text(std::string_view s) {
  std::string r = "\"";
  r += s;
  r += '"';
  return r;
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
// Limits on what a value may hold (preset.h), shared by the preset loader and --set.

std::string mb_text(size_t bytes) {
  return bytes >= (1u << 20) ? std::to_string(bytes >> 20) + " MB" : std::to_string(bytes >> 10) + " KB";
}

std::string check_text(std::string_view s) {
  if (s.size() > max_preset_text_bytes) return "text longer than the " + mb_text(max_preset_text_bytes) + " limit";
  if (!valid_utf8(s)) return "text is not valid UTF-8";
  return "";
}

template <class T>
std::string check_value_limits(const T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    return check_text(v);
  } else if constexpr (std::is_same_v<T, std::vector<float>> || std::is_same_v<T, std::vector<glm::vec3>>) {
    if (v.size() > max_preset_list)
      return std::to_string(v.size()) + " entries, more than the limit of " + std::to_string(max_preset_list);
  }
  return "";
}

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

// Calls f(value, info) on the keyable generator parameter `key` of a copy of the spec's params;
// false when there is none (check_keyframe then names the problem).
template <class F>
bool with_keyable(const tree_spec& spec, std::string_view key, F&& f) {
  bool found = false;
  std::visit(
      [&](const auto& gp) {
        auto copy = gp;
        visit_params(copy, [&](auto& value, const param_info& info) {
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (keyable_type<T>)
            if (key == info.key) {
              found = true;
              f(value, info);
            }
        });
      },
      spec.params);
  return found;
}

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
  // A preset without a "wood" section (every preset before issue 12) loads with the pass off.
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

// ---------------------------------------------------------------------------------------------
// `--set`: text -> value, strict (an argument typo should stop the command, not be clamped).

bool parse_float_text(std::string_view s, float& out) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  float f = 0;
  auto r = std::from_chars(s.data(), s.data() + s.size(), f);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(f)) return false;
  out = f;
  return true;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  for (size_t i = 0; i <= s.size(); ++i)
    if (i == s.size() || s[i] == sep) {
      parts.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

bool parse_vec3_text(std::string_view s, glm::vec3& out) {
  auto parts = split(s, ',');
  if (parts.size() != 3) return false;
  glm::vec3 v;
  for (int i = 0; i < 3; ++i)
    if (!parse_float_text(parts[size_t(i)], v[i])) return false;
  out = v;
  return true;
}

template <class T>
std::string text_to_value(std::string_view s, T& out, const param_info& info) {
  if constexpr (std::is_same_v<T, float>) {
    if (!parse_float_text(s, out)) return quote_text(s) + " is not a finite number";
  } else if constexpr (std::is_same_v<T, int>) {
    float f;
    if (!parse_float_text(s, f) || f != std::floor(f) || std::fabs(f) > 2e9f)
      return quote_text(s) + " is not an integer";
    out = int(f);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (s == "true" || s == "1" || s == "on" || s == "yes") out = true;
    else if (s == "false" || s == "0" || s == "off" || s == "no") out = false;
    else return quote_text(s) + " is not true or false";
  } else if constexpr (std::is_enum_v<T>) {
    const int n = option_count(info);
    std::string names;
    for (int i = 0; i < n; ++i) {
      if (s == info.options[i]) { out = T(i); return ""; }
      names += std::string(i ? ", " : "") + info.options[i];
    }
    return quote_text(s) + " is not one of " + names;
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    if (!parse_vec3_text(s, out)) return quote_text(s) + " is not x,y,z";
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (std::string e = check_text(s); !e.empty()) return e;
    out = std::string(s);
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    std::vector<float> v;
    if (!s.empty())
      for (std::string_view part : split(s, ',')) {
        v.push_back(0);
        if (!parse_float_text(part, v.back())) return quote_text(part) + " is not a finite number";
      }
    out = std::move(v);
  } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
    std::vector<glm::vec3> v;
    if (!s.empty())
      for (std::string_view part : split(s, ';')) {
        v.emplace_back(0);
        if (!parse_vec3_text(part, v.back())) return quote_text(part) + " is not x,y,z";
      }
    out = std::move(v);
  } else {
    static_assert(sizeof(T) == 0, "value type not supported by --set (see params.h)");
  }
  return check_value_limits(out);
}

// Calls f(value, info) on the parameter `key` (optionally "params.", "mesh.", "render." or "wood."
// qualified). Returns "" or why no single parameter matched.
template <class F>
std::string with_param(preset& p, std::string_view key, F&& f) {
  std::string_view only;
  for (std::string_view s : {"params", "mesh", "render", "wood"})
    if (key.size() > s.size() && key.substr(0, s.size()) == s && key[s.size()] == '.') {
      only = s;
      key.remove_prefix(s.size() + 1);
    }
  std::vector<std::string> hits;
  std::function<void()> apply;
  auto look = [&](std::string_view section, auto& params) {
    if (!only.empty() && only != section) return;
    visit_params(params, [&](auto& value, const param_info& info) {
      if (key != info.key) return;
      hits.push_back(std::string(section) + "." + info.key);
      apply = [&value, info, &f] { f(value, info); };
    });
  };
  std::visit([&](auto& gp) { look("params", gp); }, p.spec.params);
  look("mesh", p.mesh);
  look("render", p.render);
  look("wood", p.spec.wood);
  if (hits.empty())
    return "unknown parameter \"" + std::string(key) + "\" for generator " + generator_name(p.spec) +
           " (see `sylva params`)";
  if (hits.size() > 1) {
    std::string names;
    for (const std::string& h : hits) names += (names.empty() ? "" : " or ") + h;
    return quote_text(key) + " is ambiguous: write " + names;
  }
  apply();
  return "";
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

namespace {
constexpr std::string_view define_prefix = "define.";
bool is_define_key(std::string_view key) {
  return key.size() > define_prefix.size() && key.substr(0, define_prefix.size()) == define_prefix;
}

// --set define.NAME=value: rewrites `#define NAME ...` in a text-mode L-system's source. The value
// must lie in the constant's [min,max] (its comment, or the editor's default range around it).
std::string set_preset_define(preset& p, std::string_view key, std::string_view text) {
  auto* lp = std::get_if<lsystem_params>(&p.spec.params);
  if (!lp || lp->mode != lsystem_mode::text)
    return std::string(key) + ": define.NAME reaches the #define constants of a text-mode L-system; this preset has none";
  const std::string name(key.substr(define_prefix.size()));
  const std::vector<lsystem_constant> ks = lsystem_constants(lp->source);
  const lsystem_constant* k = nullptr;
  std::string names;
  for (const lsystem_constant& c : ks) {
    if (c.name == name) k = &c;
    names += (names.empty() ? "" : ", ") + c.name;
  }
  if (!k) return std::string(key) + ": the L-system has no #define " + quote_text(name) +
                (names.empty() ? " (it defines no constants)" : " (it defines " + names + ")");
  float v;
  if (!parse_float_text(text, v) || !std::isfinite(v)) return std::string(key) + ": " + quote_text(text) + " is not a number";
  if (v < k->min || v > k->max) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " is outside [%g, %g]", double(k->min), double(k->max));
    return std::string(key) + ": " + quote_text(text) + buf;
  }
  if (!set_lsystem_constant(lp->source, name, v)) return std::string(key) + ": could not rewrite #define " + name;
  return "";
}
}  // namespace

// `--set key@step=value`: a keyframe of the generator's parameter `key` (issue 18).
static std::string set_preset_keyframe(preset& p, std::string_view key_at, std::string_view text) {
  const size_t at = key_at.find('@');
  std::string_view key = key_at.substr(0, at);
  if (key.substr(0, 7) == "params.") key.remove_prefix(7);
  float step_f = 0;
  if (!parse_float_text(key_at.substr(at + 1), step_f) || step_f != std::floor(step_f) || std::fabs(step_f) > 1e6f)
    return std::string(key_at) + ": the step after @ must be a whole number";
  keyframe k;
  k.step = int(step_f);
  k.key = std::string(key);
  std::string error;
  with_keyable(p.spec, k.key, [&](auto& value, const param_info& info) {
    error = text_to_value(text, value, info);
    k.value = to_key_value(value);
  });
  if (!error.empty()) return std::string(key_at) + ": " + error;
  return set_keyframe(p.spec, k);
}

std::string set_preset_param(preset& p, std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    return "--set expects key=value, got \"" + std::string(assignment) + "\"";
  const std::string_view key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (is_define_key(key)) return set_preset_define(p, key, text);
  if (key.find('@') != std::string_view::npos) return set_preset_keyframe(p, key, text);
  std::string error;
  std::string found = with_param(p, key, [&](auto& value, const param_info& info) {
    auto v = value;
    error = text_to_value(text, v, info);
    if (error.empty() && !clamp_param(v, info)) error = quote_text(text) + " is outside " + range_text(info);
    if (error.empty()) value = std::move(v);
  });
  if (!found.empty()) return found;
  if (!error.empty()) return std::string(key) + ": " + error;
  return "";
}

std::string expand_param_sweep(const preset& p, std::string_view assignment, std::vector<std::string>& out) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    return "--set expects key=value, got \"" + std::string(assignment) + "\"";
  const std::string_view key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (key.find('@') != std::string_view::npos) {
    // A keyframe: one value, checked when it is set, after the --set before it (which may raise
    // the step count it is checked against).
    out.emplace_back(assignment);
    return "";
  }
  const auto parts = split(text, ':');
  preset copy = p;
  bool numeric = is_define_key(key), integral = false;
  std::string found = numeric ? std::string() : with_param(copy, key, [&](auto& value, const param_info&) {
    using T = std::decay_t<decltype(value)>;
    numeric = std::is_same_v<T, float> || std::is_same_v<T, int>;
    integral = std::is_same_v<T, int>;
  });
  if (!found.empty()) return found;
  if (!numeric || parts.size() != 3) {  // a plain value (strings such as L-system text may hold ':')
    if (std::string e = set_preset_param(copy, assignment); !e.empty()) return e;
    out.emplace_back(assignment);
    return "";
  }
  float a, b, n;
  if (!parse_float_text(parts[0], a) || !parse_float_text(parts[1], b) || !parse_float_text(parts[2], n) ||
      n != std::floor(n) || n < 1 || n > 100000)
    return std::string(key) + ": a sweep is from:to:count with a whole count >= 1, got \"" + std::string(text) + "\"";
  const int count = int(n);
  std::vector<std::string> values;
  for (int i = 0; i < count; ++i) {
    const double t = count == 1 ? 0.0 : double(i) / double(count - 1);
    double v = double(a) + (double(b) - double(a)) * t;
    if (integral) v = std::round(v);
    char buf[32];
    if (integral) std::snprintf(buf, sizeof buf, "%lld", (long long)v);
    else {
      auto r = std::to_chars(buf, buf + sizeof buf - 1, float(v));
      *r.ptr = 0;
    }
    std::string value = std::string(key) + "=" + buf;
    // Checked now, so that a sweep whose last value is out of range is refused before the first grows.
    if (std::string e = set_preset_param(copy, value); !e.empty())
      return e + " (value " + std::to_string(i + 1) + " of the sweep " + quote_text(text) + ")";
    values.push_back(std::move(value));
  }
  out.insert(out.end(), std::make_move_iterator(values.begin()), std::make_move_iterator(values.end()));
  return "";
}

preset default_preset() {
  preset p;
  p.name = "Honda tree a";
  p.description = "Honda's binary tree a (Prusinkiewicz et al. 1996, Table 1): the built-in default.";
  p.tags = {"lsystem", "honda", "paper"};
  p.spec.params = lsystem_params{};
  return p;
}

namespace {
std::atomic<int> write_fault{-1};   // stage_file calls left before one fails (tests); -1: never
}  // namespace

void inject_write_failure_for_tests(int n) { write_fault.store(n); }

std::string stage_file(const std::string& path, std::string_view bytes, staged_write& out) {
  namespace fs = std::filesystem;
  out = {};
  if (path.empty()) return "cannot write: empty path";
  // Through symlinks (as editors do): renaming over the link itself would turn it into a copy.
  fs::path target(path);
  for (int hops = 0;; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(target, ec)) || ec) break;
    if (hops == 40) return "cannot write " + path + ": too many levels of symbolic links";
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) return "cannot write " + path + ": cannot read the symbolic link: " + ec.message();
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // An existing file keeps its permissions (a 0600 file must not come back 0644) and, where the
  // user may, its owner; a new file gets 0666 less the umask, as open() would give it.
  struct stat old_st {};
  const bool present = ::stat(target.c_str(), &old_st) == 0;
  if (present && S_ISDIR(old_st.st_mode)) return "cannot write " + path + ": it is a folder";
  const bool existed = present && S_ISREG(old_st.st_mode);
  static std::atomic<unsigned> counter{0};
  const fs::path temp = dir / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                               std::to_string(counter.fetch_add(1)));
  auto fail = [&](const char* what, int err) {
    return "cannot write " + path + ": " + what + ": " + std::strerror(err);
  };
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, existed ? 0600 : 0666);
  if (fd < 0) return fail("cannot create a file in its folder", errno);
  if (existed) {
    if (::fchown(fd, old_st.st_uid, old_st.st_gid) != 0) {}  // only root may give a file away; not an error
    if (::fchmod(fd, old_st.st_mode & 07777) != 0) {
      const int err = errno;
      ::close(fd);
      ::unlink(temp.c_str());
      return fail("cannot keep the file's permissions", err);
    }
  }
  size_t done = 0;
  const bool injected = write_fault.load() >= 0 && write_fault.fetch_sub(1) == 0;
  while (done < bytes.size() || injected) {
    const ssize_t n = injected ? (errno = ENOSPC, -1) : ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      ::unlink(temp.c_str());
      return fail("write failed", err);  // e.g. a full disk: the partial temp file is removed
    }
    done += size_t(n);
  }
  // fsync before rename: otherwise a crash can leave the new name pointing at an empty file.
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    ::unlink(temp.c_str());
    return fail("fsync failed", err);
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    return fail("close failed", err);
  }
  out.path = path;
  out.temp = temp.string();
  out.target = target.string();
  return "";
}

std::string commit_staged(const staged_write& s) {
  namespace fs = std::filesystem;
  if (::rename(s.temp.c_str(), s.target.c_str()) != 0) {
    const int err = errno;
    ::unlink(s.temp.c_str());
    return "cannot write " + s.path + ": rename failed: " + std::strerror(err);
  }
  const fs::path target(s.target);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
    ::fsync(dfd);  // makes the rename itself durable; failure here loses nothing already written
    ::close(dfd);
  }
  return "";
}

void discard_staged(const staged_write& s) {
  if (!s.temp.empty()) ::unlink(s.temp.c_str());
}

std::string write_file_atomic(const std::string& path, std::string_view bytes) {
  staged_write s;
  if (std::string err = stage_file(path, bytes, s); !err.empty()) return err;
  return commit_staged(s);
}

std::string read_file(const std::string& path, std::string& out, uint64_t max_bytes) {
  auto fail = [&](const std::string& why) { return "cannot read " + path + ": " + why; };
  // O_NONBLOCK: opening a FIFO with no writer must not hang before the type check below refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return fail(std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return fail(std::strerror(err));
  }
  // Only regular files: a device (/dev/zero), FIFO or socket may never end, and a folder has no bytes.
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return fail(S_ISDIR(st.st_mode) ? "it is a folder" : "not a regular file (a device, FIFO or socket)");
  }
  auto too_big = [&] {
    return fail("larger than the " + std::to_string(max_bytes >> 20) + " MB limit for this kind of file");
  };
  if (uint64_t(st.st_size) > max_bytes) {
    ::close(fd);
    return too_big();
  }
  std::string text;
  text.resize(size_t(st.st_size));
  size_t got = 0;
  for (;;) {  // also reads past st_size if the file grows meanwhile, up to the limit
    if (got == text.size()) {
      if (got > max_bytes) {
        ::close(fd);
        return too_big();
      }
      text.resize(std::min<uint64_t>(max_bytes + 1, std::max<uint64_t>(got * 2, 4096)));
    }
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      return fail(std::strerror(err));
    }
    if (n == 0) break;
    got += size_t(n);
  }
  ::close(fd);
  if (got > max_bytes) return too_big();
  text.resize(got);
  out = std::move(text);
  return "";
}

}  // namespace sylva
