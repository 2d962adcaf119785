// A/B comparison, the display-free part: the two slots' documents (issue 18).
#include "app/editor_ab.h"

#include <cstdio>
#include <utility>

namespace sylva {

bool ab_duplicate_doc(ab_state& s, const ab_doc& current) {
  if (s.has_b && s.selected != 0) return false;
  ab_doc b;
  b.doc = current.doc;
  b.doc.name = current.doc.name + " (B)";
  b.undo_base = b.doc;
  // B has never been saved: its baseline is an empty document, so it shows as modified.
  b.baseline = preset{};
  b.baseline.name.clear();
  s.other_doc = std::move(b);
  s.has_b = true;
  s.selected = 0;
  return true;
}

bool ab_select_doc(ab_state& s, int slot, ab_doc& current) {
  if (!s.has_b || slot == s.selected || slot < 0 || slot > 1) return false;
  std::swap(current, s.other_doc);
  s.selected = slot;
  return true;
}

const ab_doc& ab_slot_doc(const ab_state& s, int slot, const ab_doc& current) {
  return slot == s.selected || !s.has_b ? current : s.other_doc;
}

std::string ab_save_slot(ab_state& s, int slot, ab_doc& current, const std::string& path) {
  ab_doc& d = slot == s.selected || !s.has_b ? current : s.other_doc;
  if (std::string err = save_preset_file(d.doc, path); !err.empty()) return err;
  d.path = path;
  d.baseline = d.doc;
  d.baseline_path = path;
  return "";
}

void ab_drop_doc(ab_state& s, ab_doc& current) {
  if (!s.has_b) return;
  if (s.selected == 1) std::swap(current, s.other_doc);
  s.other_doc = ab_doc{};
  s.has_b = false;
  s.selected = 0;
}

ab_counts ab_counts_of(const grow_result* r) {
  ab_counts c;
  if (!r || !r->skeleton) return c;
  c.present = true;
  c.nodes = r->skeleton->size();
  c.leaves = r->mesh.leaves.size();
  c.triangles = r->mesh.triangles();
  c.grow_ms = r->grow_ms;
  c.mesh_ms = r->mesh_ms;
  return c;
}

namespace {
std::string short_count(size_t n) {
  char b[32];
  if (n >= 1000000) std::snprintf(b, sizeof b, "%.2fM", double(n) / 1e6);
  else if (n >= 10000) std::snprintf(b, sizeof b, "%.1fk", double(n) / 1e3);
  else std::snprintf(b, sizeof b, "%zu", n);
  return b;
}
std::string slot_text(const char* name, const ab_counts& c) {
  if (!c.present) return std::string(name) + " growing";
  char b[160];
  std::snprintf(b, sizeof b, "%s %s nodes %s leaves %s tris grow %.0f ms mesh %.0f ms", name, short_count(c.nodes).c_str(),
                short_count(c.leaves).c_str(), short_count(c.triangles).c_str(), c.grow_ms, c.mesh_ms);
  return b;
}
}  // namespace

std::string ab_compare_text(const ab_counts& a, const ab_counts& b) { return slot_text("A", a) + " | " + slot_text("B", b); }

const char* ab_mode_label(ab_mode m) {
  switch (m) {
    case ab_mode::off: return "off";
    case ab_mode::side_by_side: return "side by side";
    case ab_mode::split: return "split";
  }
  return "?";
}

bool ab_showing(const ab_state& s) { return s.has_b && s.mode != ab_mode::off; }

}  // namespace sylva
