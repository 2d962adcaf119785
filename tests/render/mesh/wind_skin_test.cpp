// Wind export: the glTF skin's trunk. Its joint count follows the trunk's internodes
// (at least 4, up to wind_trunk_segments_max) within the 64-joint cap, majors keep their joints,
// and the skinned trunk follows the viewport's bend (offset theta h^2 / 2H, wind_displace) more
// closely than the old 4 segments did. The skin is posed on the CPU as glTF does: each joint's
// world matrix is its parent's times translate(pivot - parent pivot) * rotation, and a vertex
// is the weighted sum of world * inverse bind (translate(-pivot)) applied to it.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "generators/tree_spec.h"
#include "render/io/preset.h"
#include "render/mesh/wind.h"
#include "tests/fixtures.h"

using namespace sylva;

namespace {

tree_skeleton grown(const char* name) { return grow(sylva_test::shipped_preset(name).spec, grow_options{}); }

// Every node's skinned position at time t.
std::vector<glm::vec3> skinned(const tree_skeleton& t, const wind_skin& s, const wind_motion& m, float time) {
  std::vector<glm::mat4> world(s.joints.size()), skin(s.joints.size());
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const wind_joint& jt = s.joints[j];
    const glm::vec3 parent_pivot = jt.parent >= 0 ? s.joints[size_t(jt.parent)].pivot : glm::vec3(0);
    const glm::mat4 local = glm::translate(glm::mat4(1), jt.pivot - parent_pivot) * glm::mat4_cast(wind_joint_rotation(s, m, j, time));
    world[j] = jt.parent >= 0 ? world[size_t(jt.parent)] * local : local;
    skin[j] = world[j] * glm::translate(glm::mat4(1), -jt.pivot);
  }
  std::vector<glm::vec3> out(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    glm::vec4 p(0);
    for (int c = 0; c < 4; ++c) p += s.node_weights[i][c] * (skin[s.node_joints[i][c]] * glm::vec4(t.position[i], 1));
    out[i] = glm::vec3(p);
  }
  return out;
}

int trunk_joints(const wind_skin& s) {
  int n = 0;
  for (const wind_joint& j : s.joints) n += j.kind == 1;
  return n;
}

// Over the trunk's nodes and a loop's moments: the largest horizontal distance between the skinned
// trunk and the viewport's bend (the bend is horizontal: theta h^2 / 2H along the wind), the largest
// bend offset itself, and the largest vertical distance (a rigid joint lifts or lowers a point
// beside its pivot, as a leaning trunk does; the viewport's shear does not).
struct trunk_fit { float err = 0, bend = 0, vertical = 0; };
trunk_fit trunk_error(const tree_skeleton& t, const wind_rig& rig, const wind_skin& s, const wind_motion& m) {
  trunk_fit f;
  for (float time = 0; time < 4.0f; time += 0.25f) {
    const std::vector<glm::vec3> posed = skinned(t, s, m, time);
    for (size_t i = 0; i < t.size(); ++i) {
      if (rig.major[i] >= 0) continue;   // trunk nodes only
      const glm::vec3 want = wind_displace(rig, m, uint32_t(i), t.position[i], time);
      const glm::vec3 d = posed[i] - want;
      f.err = std::max(f.err, glm::length(glm::vec2(d.x, d.z)));
      f.vertical = std::max(f.vertical, std::abs(d.y));
      f.bend = std::max(f.bend, glm::length(want - t.position[i]));
    }
  }
  return f;
}

}  // namespace

TEST(WindSkin, TrunkSegmentsFollowTheTrunkAndShrinkTheBendError) {
  wind_params w;
  w.enabled = true;
  w.strength = 1.0f;
  const wind_motion m = make_wind_motion(w, 4.0f);
  // Straight trunks (pine, spruce: more majors than joints, ash) and a winding one (oak), whose
  // remaining horizontal error is the rigid joints' second-order swing of points beside the pivots.
  for (const char* name : {"species_pine", "species_spruce", "species_ash", "species_oak"}) {
    const bool winding = std::string(name) == "species_oak";
    const tree_skeleton t = grown(name);
    const wind_rig rig = build_wind_rig(t);
    int trunk_nodes = 0, majors = 0;
    for (size_t i = 0; i < t.size(); ++i) trunk_nodes += rig.major[i] < 0, majors += rig.major[i] == int32_t(i);
    const wind_skin old = build_wind_skin(t, rig, wind_max_joints, 4), now = build_wind_skin(t, rig);
    ASSERT_LE(now.joints.size(), size_t(wind_max_joints));
    EXPECT_LE(trunk_joints(old), 4) << name;
    EXPECT_GT(trunk_joints(now), trunk_joints(old)) << name << ": " << trunk_nodes << " trunk nodes, " << majors << " majors";
    EXPECT_LE(trunk_joints(now), wind_trunk_segments_max);
    EXPECT_LE(trunk_joints(now), trunk_nodes - 1);
    // The majors keep their joints: every one of them, or all the joints the trunk leaves.
    int old_majors = 0, now_majors = 0;
    for (const wind_joint& j : old.joints) old_majors += j.kind == 2 && rig.major[size_t(j.branch)] == j.branch;
    for (const wind_joint& j : now.joints) now_majors += j.kind == 2 && rig.major[size_t(j.branch)] == j.branch;
    EXPECT_EQ(now_majors, std::min(majors, wind_max_joints - 1 - trunk_joints(now))) << name;
    // The trunk takes at most 8 joints from the majors (spruce: 4 more merge than with 4 segments).
    EXPECT_GE(now_majors, std::min(old_majors, majors) - (wind_trunk_segments_max - 4)) << name;
    const trunk_fit a = trunk_error(t, rig, old, m), b = trunk_error(t, rig, now, m);
    std::printf("%s: %d trunk nodes, %d majors; trunk joints %d -> %d; bend up to %.4f m; horizontal error %.5f -> %.5f m, "
                "vertical %.5f -> %.5f m\n", name, trunk_nodes, majors, trunk_joints(old), trunk_joints(now), double(a.bend),
                double(a.err), double(b.err), double(a.vertical), double(b.vertical));
    EXPECT_GT(a.bend, 0.01f) << name << ": the trunk bends";
    // The oak's trunk forks sympodially: past the fork the rig's trunk follows a crooked
    // limb, where more straight segments no longer shrink the (millimetre) error; they must not grow it.
    EXPECT_LT(b.err, (winding ? 1.05f : 0.5f) * a.err) << name;
    EXPECT_LT(b.err, (winding ? 0.03f : 0.01f) * a.bend) << name;
  }
}
