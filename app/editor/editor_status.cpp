// The status bar, the error toast and the growth overlays' legend.
#include "app/editor/editor_state.h"
#include "render/mesh/lod.h"   // exported_card_triangles

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <ctime>
#include <functional>
#include <string_view>

#include <imgui.h>

namespace sylva::ed {

// The status bar's message; errors also go to a dismissable toast, and every message to the log.
// A successful action's message replaces an earlier error, and its toast goes away.
void set_status(editor_state& e, const std::string& m, bool error) {
  e.message = m;
  e.message_is_error = error;
  e.message_edits = e.cur().undo.size() + e.cur().redo.size();
  e.message_at = std::chrono::steady_clock::now();
  if (error) std::fprintf(stderr, "sylva: %s\n", m.c_str());
  e.toast = error ? m : "";
  // A tree from a later request is a successful action that clears this error (the first request
  // is generation 1: an error while opening the start preset stays over its tree).
  if (error) e.cur().error_after = e.cur().posted_once ? e.cur().posted_generation : 1;
  if (m.empty()) return;
  char stamp[16] = "";
  const std::time_t t = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%H:%M:%S", std::localtime(&t));
  e.log.push_back({stamp, m, error});
  if (e.log.size() > 500) e.log.erase(e.log.begin());
}

// The next successful action clears an error left from before.
void clear_error(editor_state& e) {
  if (e.message_is_error) e.message.clear();
  e.message_is_error = false;
  e.toast.clear();
}

std::string count_text(double n) {
  char b[64];
  if (n >= 1e6) std::snprintf(b, sizeof b, "%.1f million", n / 1e6);
  else if (n >= 1e4) std::snprintf(b, sizeof b, "%.0f thousand", n / 1e3);
  else std::snprintf(b, sizeof b, "%.0f", n);
  return b;
}

std::string seconds_text(double s) {
  char b[64];
  if (s >= 120) std::snprintf(b, sizeof b, "%.0f min", s / 60);
  else if (s >= 1) std::snprintf(b, sizeof b, "%.0f s", s);
  else std::snprintf(b, sizeof b, "%.1f s", s);
  return b;
}

std::string elide_text(const std::string& text, float width, const std::function<float(std::string_view)>& measure) {
  if (measure(text) <= width) return text;
  static const std::string dots = "\u2026";
  // The longest prefix, cut between UTF-8 characters, that fits with the dots (the width only grows
  // with the prefix, so a binary search over the character boundaries finds it).
  std::vector<size_t> cuts{0};
  for (size_t i = 1; i <= text.size(); ++i)
    if (i == text.size() || (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) cuts.push_back(i);
  size_t lo = 0, hi = cuts.size() - 1;
  while (lo < hi) {
    const size_t mid = (lo + hi + 1) / 2;
    if (measure(text.substr(0, cuts[mid]) + dots) <= width) lo = mid;
    else hi = mid - 1;
  }
  std::string out = text.substr(0, cuts[lo]);
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out + dots;
}

// The overlays' legend in the viewport's bottom left corner: each visible layer, its colour and units.
void draw_overlay_legend(editor_state& e, float left, float bottom) {
  const overlay_gpu& g = e.cur().renderer.overlay;
  const overlay_view& v = e.overlays;
  const uint32_t shown = v.kinds & g.present;
  if (!e.show_overlays || !shown) return;
  ImGui::SetNextWindowPos(ImVec2(left + 10, bottom - 10), 0, ImVec2(0, 1));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##legend", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoInputs);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float h = ImGui::GetTextLineHeight();
  auto swatch = [&](const glm::vec3& c) {
    const ImVec2 p = ImGui::GetCursorScreenPos();
    dl->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + h - 4, p.y + h - 2), ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1)));
    ImGui::Dummy(ImVec2(h - 2, h));
    ImGui::SameLine();
  };
  auto ramp = [&](const char* lo, const char* hi) {
    ImGui::TextUnformatted(lo);
    ImGui::SameLine();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = 120 * ui_scale;
    for (int i = 0; i < 24; ++i) {
      const glm::vec3 c = overlay_ramp((float(i) + 0.5f) / 24);
      dl->AddRectFilled(ImVec2(p.x + w * float(i) / 24, p.y + 2), ImVec2(p.x + w * float(i + 1) / 24, p.y + h - 2),
                        ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1)));
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::SameLine();
    ImGui::TextUnformatted(hi);
  };
  char hi[64];
  for (int k = 0; k < overlay_kind_count; ++k) {
    if (!((shown >> k) & 1u)) continue;
    switch (k) {
      case overlay_shadow_grid:
        ImGui::Text("Shadow grid: shade s of each voxel%s", v.shadow_slice ? "" : " (whole grid)");
        if (v.shadow_slice) ImGui::Text("  slice at %.2f m of %.2f to %.2f m", v.slice_height, g.shadow_min_y, g.shadow_max_y);
        std::snprintf(hi, sizeof hi, "%.3g (densest)", g.max_shade);
        ramp("  0", hi);
        break;
      case overlay_flow:
        ImGui::TextUnformatted("Resource flow per internode (point area ∝ flow)");
        std::snprintf(hi, sizeof hi, "%.3g", g.max_flow);
        ramp("  0", hi);
        break;
      case overlay_fates:
        swatch(overlay_fate_colour[0]); ImGui::TextUnformatted("bud grew");
        swatch(overlay_fate_colour[1]); ImGui::TextUnformatted("bud dormant");
        swatch(overlay_fate_colour[2]); ImGui::TextUnformatted("branch shed");
        break;
      case overlay_markers: swatch(overlay_marker_colour); ImGui::TextUnformatted("attraction points / markers alive"); break;
      case overlay_killed: swatch(overlay_killed_colour); ImGui::TextUnformatted("points killed in this step"); break;
      case overlay_endpoints:
        swatch(overlay_source_colour); ImGui::TextUnformatted("sources of the step");
        swatch(overlay_endpoint_colour); ImGui::TextUnformatted("endpoints of the step");
        break;
      default: ImGui::TextUnformatted(overlay_kind_labels[k]); break;
    }
  }
  ImGui::End();
}

// The last error, whole, in the viewport's top right corner until dismissed or a success.
void draw_toast(editor_state& e, float left, float top, float right) {
  if (e.toast.empty()) return;
  const float w = std::min(520.0f * ui_scale, right - left - 20);
  ImGui::SetNextWindowPos(ImVec2(right - w - 10, top + 10));
  ImGui::SetNextWindowSize(ImVec2(w, 0));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.35f, 0.08f, 0.08f, 1));
  ImGui::Begin("##toast", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::PushTextWrapPos(w - 70 * ui_scale);
  ImGui::TextUnformatted(e.toast.c_str());
  ImGui::PopTextWrapPos();
  ImGui::SameLine(w - 60 * ui_scale);
  if (ImGui::SmallButton("Dismiss")) e.toast.clear();
  if (ImGui::SmallButton("Messages...")) e.show_log = true;
  ImGui::End();
  ImGui::PopStyleColor();
}

std::string drawing_reason(const editor_state& e) {
  const editor_slot& c = e.cur();
  if (e.playing) return "playback";
  if (c.doc.render.wind.enabled || (ab_showing(e.ab) && e.ab.other().doc.render.wind.enabled)) return "wind";
  for (int i = 0; i < (e.ab.has_b ? 2 : 1); ++i)
    if (e.ab.slots[i].growth == slot_growth::growing) return "growing";   // its progress bar
  if (e.browser.open && !thumbnails_ready(e.browser)) return "thumbnails";   // rendered on this thread
  if (e.exporter.running) return "export";
  if (const auto& f = e.generator_panels.lsystem.pending; f.valid() && f.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return "derivation";
  // A new tree's chain is asked for once the tree has settled on screen (editor_lod.cpp).
  if (c.renderer.ok && c.shown && c.shown->skeleton && (c.lod.building || !c.lod.chain)) return "levels of detail";
  if (e.close_requested || e.rescale_to > 0 || e.frame_now || e.screenshot_requested || !e.screenshot_to.empty())
    return "a command";
  return "";
}

void draw_status(editor_state& e, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(0, y));
  ImGui::SetNextWindowSize(ImVec2(w, status_height()));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  ImGui::Begin("Status", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar);
  e.status_right = 0;
  e.status_cut.clear();
  auto width_of = [](std::string_view t) { return ImGui::CalcTextSize(t.data(), t.data() + t.size()).x; };
  // A piece of the line (after the first, on the same line), cut with "…" where it would run past
  // the bar's right edge (or `most` pixels, or `leave` pixels before it); one cut short or left out puts the whole line in the
  // bar's tooltip.
  std::string whole;
  bool cut = false;
  auto piece = [&](const std::string& text, const ImVec4& colour, float most = 1e9f, float leave = 0) {
    whole += text;
    if (e.status_right > 0) ImGui::SameLine();
    const float room = std::min(most, ImGui::GetContentRegionAvail().x - leave);
    const std::string shown = elide_text(text, room, width_of);
    if (width_of(shown) > room) {   // not even "…" fits
      cut = true;
      return;
    }
    ImGui::TextColored(colour, "%s", shown.c_str());
    e.status_right = std::max(e.status_right, ImGui::GetItemRectMax().x);
    cut |= shown != text;
  };
  const ImVec4 plain = ImGui::GetStyleColorVec4(ImGuiCol_Text), warn(1, 0.8f, 0.4f, 1), bad(1, 0.45f, 0.4f, 1);
  const grow_result* r = e.cur().shown.get();
  // One state: growing (with progress and Cancel once it takes a while), done, cancelled or failed.
  using g = slot_growth;
  switch (e.cur().growth) {
    case g::growing: {
      // A re-mesh (or a preset whose tree needs no growth) has no growth to show progress for.
      const bool meshing = e.cur().worker->meshing.load();
      if (long_growth(e)) {
        ImGui::TextUnformatted(meshing ? "meshing (the growth is kept)" : "growing");
        if (!meshing) {
          ImGui::SameLine();
          ImGui::ProgressBar(e.cur().worker->progress.load(), ImVec2(160, 0));
        }
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel (Esc)")) cancel_request(e);
      } else {
        ImGui::TextUnformatted(meshing ? "meshing..." : "growing...");
      }
      break;
    }
    case g::asking: piece(e.cur().growth_text, warn, 0.45f * w); break;
    case g::done: piece("done: " + e.cur().growth_text, ImVec4(0.6f, 0.9f, 0.6f, 1), 0.45f * w); break;
    case g::cancelled: piece("cancelled: " + e.cur().growth_text, warn, 0.45f * w); break;
    case g::failed: piece("failed: " + e.cur().growth_text, bad, 0.45f * w); break;
    case g::idle: ImGui::TextDisabled("no tree yet"); break;
  }
  e.status_right = std::max(e.status_right, ImGui::GetItemRectMax().x);
  if (!e.message.empty() && !e.message_is_error &&
      (e.cur().undo.size() + e.cur().redo.size() != e.message_edits || seconds_since(e.message_at) > 30))
    e.message.clear();   // stale: the document changed since, or it is old news
  // The counts leave the message room (up to 40 % of the bar) rather than push it out of sight.
  const float keep = e.message.empty() ? 0 : std::min(width_of("   " + e.message), 0.4f * w);
  char text[512];
  if (ab_showing(e.ab)) {   // A/B: both slots' counts and timings in place of the one tree's
    ab_counts c[2];
    for (int i = 0; i < 2; ++i) {
      const editor_slot& s = e.ab.slots[i];
      c[i] = ab_counts_of(s.shown.get());
      // A slot whose last growth failed or waits shows it, with the counts of the tree it still shows.
      c[i].problem = ab_slot_problem(s.growth, s.growth_text);
    }
    std::snprintf(text, sizeof text, "   %s   frame %.1f ms", ab_compare_text(c[0], c[1]).c_str(), e.frame_ms);
    piece(text, plain, 1e9f, keep);
  } else {
    // Triangles as the LOD panel and a flat-card export count them (bark, and exported_card_triangles
    // per leaf card: a face per side), so LOD0's figure there and the export dialog's "in the file"
    // are this one at the last step (issue 54); blades (--profile hero) make a file hold more.
    const renderer_gpu& g = e.cur().renderer;
    std::snprintf(text, sizeof text, "   nodes %zu   leaves %zu   triangles %zu (bark %zu)   %s   frame %.1f ms", nodes_at_step(e),
                  g.leaves_drawn, g.triangles_drawn + exported_card_triangles * g.leaves_drawn, g.triangles_drawn,
                  edit_timing_text(e.last_edit, r, e.upload_ms).c_str(), e.frame_ms);
    piece(text, plain, 1e9f, keep);
    // The hidden slot's failure still shows (A/B view off).
    if (const std::string p = e.ab.has_b ? ab_slot_problem(e.ab.other().growth, e.ab.other().growth_text) : ""; !p.empty())
      piece(std::string("   ") + (e.ab.selected == 0 ? "B" : "A") + ": " + p, bad);
  }
  if (!e.message.empty()) piece("   " + e.message, e.message_is_error ? bad : ImVec4(0.75f, 0.85f, 0.75f, 1));
  // What keeps the view drawing every frame, where the user can stop it (otherwise it waits for input).
  if (const std::string why = drawing_reason(e); why == "wind" || why == "playback")
    piece(why == "wind" ? "   drawing every frame: the wind blows" : "   drawing every frame: playback", plain);
  if (const std::string lod = editor_lod_status(e.cur().lod); !lod.empty()) piece("   " + lod, plain);
  if (r && !r->mesh.message.empty()) piece("   " + r->mesh.message, warn);   // the leaf cap: growth went on, the foliage stopped
  if (cut) {
    e.status_cut = whole;
    if (ImGui::IsWindowHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(std::min(w * 0.6f, 700 * ui_scale));
      ImGui::TextUnformatted(whole.c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

}  // namespace sylva::ed
