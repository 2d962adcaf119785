// A/B comparison in the editor: selecting, duplicating, dropping and restoring slots (app/editor/editor_ab.h).
#include "app/editor/editor_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <utility>

namespace sylva::ed {

void select_slot(editor_state& e, int slot) {
  editor_slot& was = e.cur();
  if (!ab_select_doc(e.ab, slot)) return;
  // A slot waiting on the over-budget question asks again when it is selected again.
  if (was.growth == slot_growth::asking) was.posted_once = false;
  e.budget_answer.reset();
  e.ask(dialog::large_tree, false);
  e.before_open.reset();
  e.counted_tree = nullptr;
  e.prune.selected = -1;   // a pick or a marker drag belongs to the other slot's tree
  e.prune.picked_in = nullptr;
  e.keys.drag_from = e.keys.drag_to = e.keys.popup_step = -1;
  set_status(e, std::string("Editing slot ") + (slot == 0 ? "A" : "B") + ": the panel, undo, Save and Export act on it");
}

void handle_ab(editor_state& e, ab_action a) {
  editor_slot& b = e.ab.slots[1];
  switch (a) {
    case ab_action::none: return;
    case ab_action::duplicate: {
      const editor_slot& from = e.cur();
      if (!from.shown || !from.shown->skeleton) return set_status(e, "Duplicate to B: wait for the tree to grow first", true);
      if (e.ab.has_b && e.ab.selected != 0) return set_status(e, "Duplicate to B: select slot A first", true);
      ab_duplicate_doc(e.ab);
      if (std::string err = ab_start_view(b, from.shown, e.step, from.renderer.shared, from.renderer.overlay.geometry);
          !err.empty()) {
        ab_drop_doc(e.ab);
        ab_stop_view(b);
        return set_status(e, "Duplicate to B failed: " + err, true);
      }
      b.worker->node_budget = from.worker->node_budget.load();
      b.growth = slot_growth::done;
      b.growth_text = from.growth_text;
      if (e.ab.mode == ab_mode::off) e.ab.mode = ab_mode::side_by_side;
      select_slot(e, 1);
      return set_status(e, "Duplicated to slot B and selected it: the panel, Save and Export act on B");
    }
    case ab_action::select_a: return select_slot(e, 0);
    case ab_action::select_b: return select_slot(e, 1);
    case ab_action::drop: {
      // Edits made in B are lost with it: ask first (B's own undo history holds them).
      if (!b.undo.empty() && !e.ab.drop_confirmed) {
        e.ask(dialog::drop_b);
        return;
      }
      e.ab.drop_confirmed = false;
      select_slot(e, 0);
      ab_drop_doc(e.ab);
      ab_stop_view(b);
      return set_status(e, "Slot B dropped");
    }
  }
}

// A recovered slot B comes back as B once slot A's tree is shown (B starts as A's duplicate).
void restore_slot_b(editor_state& e) {
  if (!e.restore_b_pending || !e.cur().shown || !e.cur().shown->skeleton || e.cur().growth == slot_growth::growing) return;
  e.restore_b_pending = false;
  if (e.ab.has_b && e.ab.selected != 0) select_slot(e, 0);
  handle_ab(e, ab_action::duplicate);   // selects B
  if (!e.ab.has_b || e.ab.selected != 1) return;
  editor_slot& b = e.cur();
  b.doc = e.recovered_b_doc;
  b.undo_base = b.doc;
  b.path = e.recovered_b_path;
  // B stays selected so its restored document is grown (post_if_changed); Edit A switches back.
  set_status(e, "Restored unsaved work in slot B (and A); save them to keep them");
}

std::string slot_label(const preset& p) {
  const size_t g = p.spec.params.index();
  return p.name + " - " + (g < size_t(generator_count) ? generator_labels[g] : "?");
}

}  // namespace sylva::ed
