// A/B comparison: moving the selected slot's document and view in and out of editor_state (app/editor_ab.h).
#include "app/editor_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <utility>

namespace sylva::ed {

// ---------------------------------------------------------------- A/B comparison (app/editor_ab.h)

namespace {

ab_doc take_doc(editor_state& e) {
  ab_doc d;
  d.doc = std::move(e.doc);
  d.undo_base = std::move(e.undo_base);
  d.undo = std::move(e.undo);
  d.redo = std::move(e.redo);
  d.path = std::move(e.path);
  d.baseline = e.browser.baseline;
  d.baseline_path = e.browser.baseline_path;
  return d;
}

void put_doc(editor_state& e, ab_doc&& d) {
  e.doc = std::move(d.doc);
  e.undo_base = std::move(d.undo_base);
  e.undo = std::move(d.undo);
  e.redo = std::move(d.redo);
  e.path = std::move(d.path);
  e.browser.baseline = std::move(d.baseline);
  e.browser.baseline_path = std::move(d.baseline_path);
}

// Swaps the selected slot's growth and drawing state with the stored slot's.
void swap_views(editor_state& e, ab_view& v) {
  // A slot waiting on the over-budget question asks again when it is selected again.
  if (e.growth_state == editor_state::growth::asking) e.posted_once = false;
  e.budget_answer.reset();
  e.open_budget_prompt = false;
  e.before_open.reset();
  std::swap(e.worker, v.worker);
  std::swap(e.renderer, v.renderer);
  std::swap(e.lod, v.lod);
  std::swap(e.shown, v.shown);
  std::swap(e.posted_spec, v.posted_spec);
  std::swap(e.posted_mesh, v.posted_mesh);
  std::swap(e.posted_once, v.posted_once);
  std::swap(e.seen_generation, v.seen_generation);
  std::swap(e.posted_generation, v.posted_generation);
  std::swap(e.stale_before, v.stale_before);
  std::swap(e.error_after, v.error_after);
  std::swap(e.frame_generation, v.frame_generation);
  std::swap(e.growth_text, v.growth_text);
  std::swap(e.posted_at, v.posted_at);
  std::swap(e.overlay_generator, v.overlay_generator);
  const int g = int(e.growth_state);
  e.growth_state = editor_state::growth(v.growth);
  v.growth = g;
  e.counted_tree = nullptr;
  e.prune.selected = -1;   // a pick or a marker drag belongs to the other slot's tree
  e.prune.picked_in = nullptr;
  e.keys.drag_from = e.keys.drag_to = e.keys.popup_step = -1;
}

}  // namespace

void select_slot(editor_state& e, int slot) {
  ab_doc cur = take_doc(e);
  const bool changed = ab_select_doc(e.ab, slot, cur);
  put_doc(e, std::move(cur));
  if (!changed) return;
  swap_views(e, e.ab.other);
  set_status(e, std::string("Editing slot ") + (slot == 0 ? "A" : "B") + ": the panel, undo, Save and Export act on it");
}

void handle_ab(editor_state& e, ab_action a) {
  switch (a) {
    case ab_action::none: return;
    case ab_action::duplicate: {
      if (!e.shown || !e.shown->skeleton) return set_status(e, "Duplicate to B: wait for the tree to grow first", true);
      if (e.ab.has_b && e.ab.selected != 0) return set_status(e, "Duplicate to B: select slot A first", true);
      ab_doc cur = take_doc(e);
      ab_duplicate_doc(e.ab, cur);
      put_doc(e, std::move(cur));
      if (std::string err = ab_start_view(e.ab.other, e.shown, e.step); !err.empty()) {
        ab_doc back = take_doc(e);
        ab_drop_doc(e.ab, back);
        put_doc(e, std::move(back));
        ab_stop_view(e.ab.other);
        return set_status(e, "Duplicate to B failed: " + err, true);
      }
      e.ab.other.worker->node_budget = e.worker->node_budget.load();
      e.ab.other.growth = int(editor_state::growth::done);
      e.ab.other.growth_text = e.growth_text;
      if (e.ab.mode == ab_mode::off) e.ab.mode = ab_mode::side_by_side;
      select_slot(e, 1);
      return set_status(e, "Duplicated to slot B and selected it: the panel, Save and Export act on B");
    }
    case ab_action::select_a: return select_slot(e, 0);
    case ab_action::select_b: return select_slot(e, 1);
    case ab_action::drop: {
      // Edits made in B are lost with it: ask first (B's own undo history holds them).
      const bool b_edited = e.ab.selected == 1 ? !e.undo.empty() : !e.ab.other_doc.undo.empty();
      if (b_edited && !e.ab.drop_confirmed) {
        e.ab.ask_drop = true;
        return;
      }
      e.ab.drop_confirmed = false;
      select_slot(e, 0);
      ab_doc cur = take_doc(e);
      ab_drop_doc(e.ab, cur);
      put_doc(e, std::move(cur));
      ab_stop_view(e.ab.other);
      return set_status(e, "Slot B dropped");
    }
  }
}

// A recovered slot B comes back as B once slot A's tree is shown (B starts as A's duplicate).
void restore_slot_b(editor_state& e) {
  if (!e.restore_b_pending || !e.shown || !e.shown->skeleton || e.growth_state == editor_state::growth::growing) return;
  e.restore_b_pending = false;
  if (e.ab.has_b && e.ab.selected != 0) select_slot(e, 0);
  handle_ab(e, ab_action::duplicate);   // selects B
  if (!e.ab.has_b || e.ab.selected != 1) return;
  e.doc = e.recovered_b_doc;
  e.undo_base = e.doc;
  e.path = e.recovered_b_path;
  // B stays selected so its restored document is grown (post_if_changed); Edit A switches back.
  set_status(e, "Restored unsaved work in slot B (and A); save them to keep them");
}

std::string slot_label(const preset& p) {
  const size_t g = p.spec.params.index();
  return p.name + " - " + (g < size_t(generator_count) ? generator_labels[g] : "?");
}

}  // namespace sylva::ed
