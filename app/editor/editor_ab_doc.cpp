// A/B comparison, the display-free part: the two slots' documents.
#include "app/editor/editor_ab.h"

#include <cstdio>
#include <utility>

namespace sylva {

bool ab_duplicate_doc(ab_state& s) {
  if (s.has_b && s.selected != 0) return false;
  const slot_document& a = s.slots[0];
  slot_document b;
  b.doc = a.doc;
  b.doc.name = a.doc.name + " (B)";
  b.undo_base = b.doc;
  // B has never been saved: its baseline is an empty document, so it shows as modified.
  b.baseline = preset{};
  b.baseline.name.clear();
  static_cast<slot_document&>(s.slots[1]) = std::move(b);
  s.has_b = true;
  s.selected = 0;
  return true;
}

bool ab_select_doc(ab_state& s, int slot) {
  if (!s.has_b || slot == s.selected || slot < 0 || slot > 1) return false;
  s.selected = slot;
  return true;
}

std::string ab_save_slot(ab_state& s, int slot, const std::string& path) {
  slot_document& d = s.slots[s.has_b ? slot : 0];
  if (std::string err = save_preset_file(d.doc, path); !err.empty()) return err;
  d.path = path;
  d.baseline = d.doc;
  d.baseline_path = path;
  return "";
}

void ab_drop_doc(ab_state& s) {
  if (!s.has_b) return;
  static_cast<slot_document&>(s.slots[1]) = slot_document{};
  s.has_b = false;
  s.selected = 0;
}

std::vector<int> ab_unsaved_slots(const ab_state& s) {
  std::vector<int> out;
  const slot_document& cur = s.cur();
  if (!(cur.doc == cur.baseline)) out.push_back(s.selected);
  const slot_document& other = s.other();
  if (s.has_b && !(other.doc == other.baseline)) out.push_back(1 - s.selected);
  return out;
}

std::string ab_unsaved_line(const ab_state& s, int slot) {
  const slot_document& d = s.slots[s.has_b ? slot : s.selected];
  std::string line = std::string(s.has_b ? (slot == 0 ? "Slot A " : "Slot B ") : "") + "\"" + d.doc.name + "\"";
  line += d.path.empty() ? " (no file yet)" : " (" + d.path + ")";
  return line;
}

ab_result_use ab_take_other_result(slot_view& v, const grow_result& r) {
  v.seen_generation = r.generation;
  if (int32_t(r.generation - v.stale_before) < 0) return ab_result_use::ignore;   // cancelled before it arrived
  const bool newest = r.generation == v.posted_generation;
  // An over-budget answer or a failed growth keeps the slot's last tree; selecting the slot again
  // posts its document anew (its posted spec is reset), where the editor asks or reports.
  if (r.over_budget || r.report.error || !r.skeleton) {
    if (!newest) return ab_result_use::ignore;
    v.posted_once = false;
    char b[160];
    if (r.over_budget) {
      std::snprintf(b, sizeof b, "over the node budget (about %.0f nodes): select the slot to grow it anyway",
                    r.estimated_nodes);
      v.growth = slot_growth::asking;
      v.growth_text = b;
    } else {
      v.growth = slot_growth::failed;
      v.growth_text = r.report.message.empty() ? "the growth failed" : r.report.message;
    }
    return ab_result_use::keep;
  }
  if (newest) {
    v.growth = slot_growth::done;
    v.growth_text = r.report.stop_reason;
    if (!r.report.message.empty()) v.growth_text += " (" + r.report.message + ")";
  }
  return ab_result_use::show;
}

std::string ab_slot_problem(slot_growth growth, const std::string& growth_text) {
  switch (growth) {
    case slot_growth::asking: return "waiting: " + growth_text;
    case slot_growth::failed: return "growth stopped: " + growth_text;
    case slot_growth::cancelled: return "cancelled: " + growth_text;
    default: return "";
  }
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
  if (!c.present) return std::string(name) + (c.problem.empty() ? " growing" : " " + c.problem);
  char b[160];
  std::snprintf(b, sizeof b, "%s nodes %s leaves %s tris grow %.0f ms mesh %.0f ms", short_count(c.nodes).c_str(),
                short_count(c.leaves).c_str(), short_count(c.triangles).c_str(), c.grow_ms, c.mesh_ms);
  if (!c.problem.empty()) return std::string(name) + " " + c.problem + " (last tree: " + b + ")";
  return std::string(name) + " " + b;
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
