// Export window: the exporter runs on a helper thread (it takes progress/cancel); PNG renders on the main thread.
#include "app/editor/export_dialog.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/common/gl_window.h"
#include "render/gl/impostor.h"
#include "render/gl/renderer.h"
#include "render/mesh/lod.h"

namespace sylva {

namespace fs = std::filesystem;

namespace {

// The row of export_format_table the path's extension names (any case), or -1.
int format_of(const std::string& path) {
  const export_format* f = find_export_format(fs::path(path).extension().string());
  return f ? int(f - export_format_table) : -1;
}

std::string human_bytes(size_t b) {
  char buf[64];
  if (b >= size_t(1) << 20) std::snprintf(buf, sizeof buf, "%.1f MiB", double(b) / double(1 << 20));
  else std::snprintf(buf, sizeof buf, "%.1f KiB", double(b) / 1024.0);
  return buf;
}

bool gltf_format(int f) { return f >= 0 && export_format_table[f].gltf; }

// The LOD chain applies: asked for, and the format carries levels.
bool lods_apply(const export_dialog_state& d, int f) { return d.lods && f >= 0 && export_format_table[f].lods; }

export_options options_for(const export_dialog_state& d, const export_context& c) {
  export_options o;
  const int steps = c.tree->skeleton->steps;
  const int f = format_of(d.path);
  const bool lods = lods_apply(d, f);   // the final tree, no growth animation (as the CLI's --lods)
  o.step = d.final_tree || lods || c.step >= steps ? -1 : c.step;
  o.growth_animation = d.animation && !lods && f >= 0 && export_format_table[f].gltf;
  o.compact = d.compact && f >= 0 && export_format_table[f].gltf;
  o.seconds_per_step = d.seconds_per_step;
  apply_export_profile(o, export_profile(std::clamp(d.profile, 0, 2)), f >= 0 && export_format_table[f].gltf);
  o.mesh = c.tree->mesh_settings;
  apply_render_params(o, c.doc.render);  // the same materials and user textures as `sylva export`
  return o;
}

void join(export_dialog_state& d) {
  if (d.thread.joinable()) d.thread.join();
}

// The impostor of a glTF LOD export, rendered here on the UI thread (the editor's GL context is
// this thread's): a view at a time into the build's own copy of LOD0, so the level the view shows
// stays uploaded, then read back as PNGs. Null, with `why`, when it cannot be made.
std::shared_ptr<const export_impostor> render_export_impostor(const export_context& c, std::string& why) {
  const render_params& rp = c.doc.render;
  impostor_build b;
  why = impostor_begin(b, c.renderer, rp, rp.lod.impostor_views, rp.lod.impostor_size, &c.tree->mesh);
  if (why.empty())
    while (!impostor_step(b, c.renderer)) {
    }
  if (why.empty() && b.st != impostor_build::state::complete) why = b.atlas.error.empty() ? "the atlas failed" : b.atlas.error;
  auto im = std::make_shared<export_impostor>();
  if (why.empty()) why = impostor_pngs(b.atlas, im->color_png, im->normal_png);
  impostor_cancel(b);
  if (!why.empty()) return nullptr;
  im->views = b.atlas.views;
  im->columns = b.atlas.columns;
  im->rows = b.atlas.rows;
  im->width = im->height = b.atlas.cell_metres;
  im->centre = b.atlas.centre;
  return im;
}

void start_job(export_dialog_state& d, const export_context& c, bool dry,
               std::shared_ptr<const export_impostor> impostor = nullptr) {
  join(d);
  {
    std::lock_guard lock(d.mutex);
    d.finished.reset();   // a cancelled estimate's result must not pass for this job's
  }
  d.cancel = 0;
  d.progress = 0;
  d.running = true;
  d.job_dry = dry;
  export_options o = options_for(d, c);
  o.dry_run = dry;
  o.cancel = &d.cancel;
  o.progress = [&d](float p) { d.progress = p; };
  const export_info info{generator_name(c.tree->spec), c.tree->spec.seed};
  const bool lods = lods_apply(d, format_of(d.path));
  d.thread = std::thread([&d, tree = c.tree, info, o, path = d.path, lods, lp = c.doc.render.lod, impostor]() mutable {
    // The chain is built here, off the UI thread, from the final tree (as `sylva export --lods`);
    // its clamped budgets and any level off its budget (with the floor that kept it) are warnings.
    lod_chain chain;
    std::string counts;
    export_impostor im;
    if (lods) {
      chain = build_lods(*tree->skeleton, tree->mesh, tree->mesh_settings, lp);
      o.lod0_coverage = chain.coverage[0];
      for (int k = 1; k < lod_levels; ++k)
        o.lods.push_back({&chain.level[size_t(k) - 1], chain.coverage[size_t(k)], chain.target[size_t(k)]});
      counts = lod_summary(chain);
      if (impostor) {
        im = *impostor;
        im.coverage = chain.impostor_coverage;
        o.impostor = &im;
      }
    }
    export_result r = export_tree(*tree->skeleton, tree->mesh, info, path, o);
    if (lods && !chain.message.empty()) r.warning = chain.message + (r.warning.empty() ? "" : "\n" + r.warning);
    std::lock_guard lock(d.mutex);
    d.finished = std::move(r);
    d.finished_lods = counts;
    d.running = false;
  });
}

}  // namespace

void shutdown_export_dialog(export_dialog_state& d) {
  d.cancel = 1;
  join(d);
}

void draw_export_dialog(export_dialog_state& d, const export_context& c, std::string& status, bool& error) {
  // A finished job reports even when the window was closed meanwhile.
  std::optional<export_result> done;
  std::string done_lods;
  {
    std::lock_guard lock(d.mutex);
    done.swap(d.finished);
    done_lods.swap(d.finished_lods);
  }
  if (done) {
    join(d);
    if (done->error.empty()) d.lod_counts = done_lods;
    if (d.job_dry) {
      d.warning = done->warning;  // a user texture that cannot be used shows before the export
      d.estimate = !done->error.empty() ? "cannot estimate: " + done->error
                                        : "about " + human_bytes(done->bytes) + ", " + std::to_string(done->triangles) +
                                              " triangles in the file" +
                                              (done->animation_steps ? ", " + std::to_string(done->animation_steps) + " steps" : "");
    } else {
      error = !done->error.empty();
      d.failure = error ? done->error : "";
      status = error ? "Export failed: " + done->error
                     : "Exported " + d.path + " (" + human_bytes(done->bytes) + ", " + std::to_string(done->files.size()) + " file(s))" +
                           (done_lods.empty() ? "" : "; " + done_lods);
      d.warning = error ? "" : done->warning;
      if (!d.warning.empty()) status += "; warning: " + d.warning.substr(0, d.warning.find('\n'));
      if (!d.warning.empty()) std::fprintf(stderr, "sylva: export warning: %s\n", d.warning.c_str());
    }
  }
  if (!d.open) return;
  ImGui::SetNextWindowSize(ImVec2(560, 0), ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(c.view_left + 24, c.view_top + 24), ImGuiCond_Appearing);
  if (!ImGui::Begin("Export", &d.open, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  const bool have_tree = c.tree && c.tree->skeleton;
  const bool busy = d.running;
  int f = format_of(d.path);
  ImGui::TextUnformatted("Format");
  for (int i = 0; i < export_format_count; ++i) {
    ImGui::SameLine();
    const export_format& row = export_format_table[i];
    if (ImGui::RadioButton(row.ext, f == i) && f != i) {
      d.path = fs::path(d.path).replace_extension(row.ext).string();
      f = i;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.label);
  }
  ImGui::SetNextItemWidth(440);
  ImGui::InputText("Path", &d.path);
  d.path_at[0] = 0.5f * (ImGui::GetItemRectMin().x + ImGui::GetItemRectMax().x);
  d.path_at[1] = 0.5f * (ImGui::GetItemRectMin().y + ImGui::GetItemRectMax().y);
  if (d.path != d.shown_path) {   // a new path: the old failure and replace question were about another file
    if (!d.shown_path.empty()) d.failure.clear();
    if (d.confirm_replace != d.path) d.confirm_replace.clear();
    d.shown_path = d.path;
  }
  if (f < 0) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "The extension picks the format: %s", export_format_list(nullptr, " ").c_str());
  // The LOD chain (as the command line's --lods): the final tree only, no growth animation.
  const bool can_lods = f >= 0 && export_format_table[f].lods;
  ImGui::BeginDisabled(!can_lods);
  ImGui::Checkbox("LOD chain (LOD0-LOD3)", &d.lods);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("%s", can_lods ? "LOD1-3 at the preset's budgets (Render > Level of detail), built from the final tree: "
                                       "glTF MSFT_lod, an FBX LOD group (Unreal, Unity), one OBJ per level"
                                     : "This format carries no levels");
  const bool lods = d.lods && can_lods;
  if (lods) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 520);
    ImGui::TextDisabled("%s %s %s",
                        gltf_format(f) ? "The final tree's levels and the impostor (its atlas renders when you export: "
                                         "the window pauses for it)."
                                       : "The final tree's levels (the impostor goes into glTF only).",
                        d.lod_counts.c_str(), d.impostor_note.c_str());
    ImGui::PopTextWrapPos();
  }
  int scope = d.final_tree || lods ? 1 : 0;
  ImGui::BeginDisabled(lods);
  ImGui::RadioButton("Current step", &scope, 0);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::RadioButton("Final tree", &scope, 1);
  if (!lods) d.final_tree = scope == 1;
  if (have_tree) {
    ImGui::SameLine();
    ImGui::TextDisabled("(step %d of %d)", d.final_tree || lods ? c.tree->skeleton->steps : c.step, c.tree->skeleton->steps);
  }
  const bool gltf = f >= 0 && export_format_table[f].gltf;
  ImGui::BeginDisabled(!gltf || lods);
  ImGui::Checkbox("Growth animation", &d.animation);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(140);
  ImGui::SliderFloat("s per step", &d.seconds_per_step, 0.05f, 5, "%.2f s", ImGuiSliderFlags_Logarithmic);
  ImGui::EndDisabled();
  if (d.animation && gltf && !lods) ImGui::TextDisabled("Steps 0..N as one mesh each, shown in turn (STEP scale keys).");
  ImGui::BeginDisabled(!gltf);
  ImGui::Checkbox("Compact (meshopt)", &d.compact);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("glTF: quantized vertices (KHR_mesh_quantization), EXT_meshopt_compression, opaque textures as JPEG");
  // The leaves' profile (render/io/export.h); the LOD chain (game) is the command line's --lods.
  ImGui::SetNextItemWidth(160);
  if (ImGui::BeginCombo("Leaves", export_profile_names[std::clamp(d.profile, 0, 2)])) {
    for (int k = 0; k < 3; ++k) {
      if (ImGui::Selectable(export_profile_names[k], d.profile == k)) d.profile = k;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", export_profile_help[k]);
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s", export_profile_help[std::clamp(d.profile, 0, 2)]);

  // The size estimate: a dry run of the same export, redone whenever an input changes.
  const bool png = f >= 0 && export_format_table[f].render;
  if (have_tree && f >= 0 && !png) {
    char head[240];
    const lod_params& lp = c.doc.render.lod;
    std::snprintf(head, sizeof head, "%u|%d|%d|%d|%d|%g|%d|%d|%d|%d|%g|%g|%g", c.tree->generation, f, d.final_tree ? -1 : c.step,
                  int(d.animation && gltf), int(d.final_tree), double(d.seconds_per_step), int(c.doc.render.bark),
                  int(d.compact && gltf), d.profile, int(lods), double(lp.lod1_budget), double(lp.lod2_budget),
                  double(lp.lod3_budget));
    const render_params& rp = c.doc.render;
    const std::string key = std::string(head) + "|" + rp.bark_texture + "|" + rp.leaf_texture + "|" + rp.leaf_opacity;
    if (key != d.estimate_key && !busy) {
      d.estimate_key = key;
      d.estimate = "estimating...";
      start_job(d, c, true);
    }
    ImGui::Text("Estimated size: %s", d.estimate.c_str());
  } else if (png) {
    ImGui::TextDisabled("A 1280x720 render of the current view.");
  }

  if (!d.warning.empty()) ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "Warning: %s", d.warning.c_str());
  if (!d.failure.empty()) {   // the dialog's own failure, whole, not only the status bar's one line
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 520);
    ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "Export failed: %s", d.failure.c_str());
    ImGui::PopTextWrapPos();
  }

  if (busy && !d.job_dry) {
    ImGui::ProgressBar(d.progress.load(), ImVec2(400, 0));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) d.cancel = 1;
  } else {
    ImGui::BeginDisabled(!have_tree || f < 0 || d.path.empty());
    std::error_code ec;
    const bool exists = !d.path.empty() && fs::exists(d.path, ec);
    const bool asking = exists && d.confirm_replace == d.path;
    if (asking) ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "%s exists. Replace it?", fs::path(d.path).filename().c_str());
    bool go = ImGui::Button(asking ? "Replace" : "Export");
    d.export_at[0] = 0.5f * (ImGui::GetItemRectMin().x + ImGui::GetItemRectMax().x);
    d.export_at[1] = 0.5f * (ImGui::GetItemRectMin().y + ImGui::GetItemRectMax().y);
    if (d.export_now && have_tree && f >= 0) go = true, d.confirm_replace = d.path;   // Export as... asked already
    d.export_now = false;
    if (go && exists && d.confirm_replace != d.path) {   // an existing file: ask before writing over it
      d.confirm_replace = d.path;
      go = false;
    }
    if (go) {
      d.confirm_replace.clear();
      if (png) {   // GL: main thread only
        std::string err = save_view_png(c.renderer, c.doc.render, c.camera, 1280, 720, d.path);
        error = !err.empty();
        d.failure = err;
        status = error ? "Export failed: " + err : "Rendered " + d.path;
      } else {
        if (busy) d.cancel = 1;   // a running estimate gives way to the export
        d.failure.clear();
        // glTF with the LOD chain: the impostor as `sylva export --lods` writes it, rendered now on
        // this thread (a pause of about a second on software GL); without it the levels still go.
        std::shared_ptr<const export_impostor> impostor;
        d.impostor_note.clear();
        if (lods && gltf) {
          std::string why;
          impostor = render_export_impostor(c, why);
          if (!impostor) d.impostor_note = "impostor left out: " + why;
        }
        start_job(d, c, false, impostor);
        d.estimate_key.clear();
      }
    }
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Close")) d.open = false;
  }
  ImGui::End();
}

}  // namespace sylva
