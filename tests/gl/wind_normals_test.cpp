// Wind: the lighting follows the sway. The viewport's vertex shaders turn the bark
// normal and the leaf card's frame with the branch rotations and the trunk's bend. Checked in
// pixels against the same tree posed on the CPU: positions through wind_displace (the shader's
// CPU reference) and normals through the deformation's Jacobian J, taken by central differences of
// wind_displace (normals map by J^-T, tangents by J), so the reference knows nothing of the shader's
// rotations. A render of the posed tree with its rest normals (what the shader drew before) must
// differ clearly more.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "generators/lsystem.h"
#include "tests/gl/gl_test_context.h"
#include "render/mesh/wind.h"
#include "render/gl/wind_gl.h"

using namespace sylva;

namespace {

// The Jacobian of the sway at p (columns d displace / d x, y, z); central differences are exact for
// the rotations (affine in p) and for the bend (quadratic in the height).
glm::mat3 sway_jacobian(const wind_rig& rig, const wind_motion& m, uint32_t node, glm::vec3 p, float t) {
  const float e = 0.01f;
  glm::mat3 j(1.0f);
  for (int k = 0; k < 3; ++k) {
    glm::vec3 d(0);
    d[k] = e;
    j[k] = (wind_displace(rig, m, node, p + d, t) - wind_displace(rig, m, node, p - d, t)) / (2.0f * e);
  }
  return j;
}

// The tree as the wind poses it at time t; `turn_frames` false keeps the rest normals and leaf
// orientations (the shader before normals swayed).
tree_mesh posed(const tree_mesh& rest, const wind_rig& rig, const wind_motion& m, float t, bool turn_frames) {
  tree_mesh out = rest;
  for (size_t v = 0; v < rest.position.size(); ++v) {
    const glm::vec3 p = rest.position[v];
    out.position[v] = wind_displace(rig, m, rest.node[v], p, t);
    if (turn_frames) out.normal[v] = glm::normalize(glm::inverseTranspose(sway_jacobian(rig, m, rest.node[v], p, t)) * rest.normal[v]);
  }
  for (size_t i = 0; i < rest.leaves.size(); ++i) {
    const leaf_instance& l = rest.leaves[i];
    out.leaves[i].position = wind_displace(rig, m, l.node, l.position, t);
    if (!turn_frames) continue;
    const glm::quat q(l.orientation.w, l.orientation.x, l.orientation.y, l.orientation.z);
    const glm::mat3 j = sway_jacobian(rig, m, l.node, l.position, t);
    const glm::vec3 tan = glm::normalize(j * (q * glm::vec3(1, 0, 0)));
    const glm::vec3 n = glm::normalize(glm::inverseTranspose(j) * (q * glm::vec3(0, 0, 1)));
    const glm::quat r = glm::quat_cast(glm::mat3(tan, glm::cross(n, tan), n));
    out.leaves[i].orientation = glm::vec4(r.x, r.y, r.z, r.w);
  }
  return out;
}

}  // namespace

class WindNormals : public sylva_test::renderer_test {};

// A thick trunk with a thin major branch toward the wind and thinner minor branches off it: thin
// branches sway most (stiffness from the radius against the trunk's), so at storm strength they
// turn by about half a radian.
tree_skeleton swaying_tree() {
  tree_skeleton t;
  int32_t prev = t.add_node(glm::vec3(0), -1, 2.0f, 0, 0);
  int32_t fork = -1;
  for (int i = 1; i <= 8; ++i) {
    prev = t.add_node(glm::vec3(0, float(i), 0), prev, 0.8f - 0.06f * float(i), 0, 0);
    if (i == 4) fork = prev;
  }
  prev = fork;
  for (int i = 1; i <= 6; ++i) {
    prev = t.add_node(glm::vec3(0.1f * float(i), 4.0f + 0.15f * float(i), 0.8f * float(i)), prev, 0.3f - 0.02f * float(i), 0, 1);
    if (i % 2 == 0) {   // a minor branch, up and to the side
      int32_t q = prev;
      for (int k = 1; k <= 4; ++k) q = t.add_node(t.position[size_t(prev)] + glm::vec3(0.5f, 0.6f, 0.1f) * float(k), q, 0.18f - 0.02f * float(k), 0, 2);
    }
  }
  t.steps = 1;
  return t;
}

TEST_F(WindNormals, LightingFollowsTheSway) {
  const tree_skeleton t = swaying_tree();
  mesh_params mp;
  mp.radial_segments = 16;
  mp.leaves.mode = leaf_mode::tips;
  mp.leaves.min_order = 1;
  mp.leaves.size = 0.7f;   // big cards: their turned frames show
  mp.leaves.density = 6;
  const tree_mesh rest = mesh_tree(t, mp);
  ASSERT_FALSE(rest.leaves.empty());
  const wind_rig rig = build_wind_rig(t);

  wind_params w;
  w.enabled = true;
  w.strength = wind_strength_max;   // a storm: branches turn up to the 0.8 rad cap
  w.gustiness = 0;
  w.leaf_flutter = 0;               // the flutter is the shader's alone; the CPU poses the sway
  const wind_motion m = make_wind_motion(w);
  const float when = 0.7f;
  // The sway is strong: some branch turns by more than 0.3 rad at that moment.
  float most = 0;
  for (const wind_node& n : rig.nodes)
    most = std::max(most, glm::length(wind_branch_rotation(m, n.major_amp, n.major_phase, n.major_freq, when)) +
                              glm::length(wind_branch_rotation(m, n.minor_amp, n.minor_phase, n.minor_freq, when)));
  std::printf("largest branch turn %.2f rad\n", double(most));
  ASSERT_GT(most, 0.3f);

  const int size = 240;
  sylva_test::color_target<unsigned char> target(size, size);
  orbit_camera cam;
  frame_camera(cam, glm::vec3(-1, 3, 0), glm::vec3(5, 8, 6), 1.0f);   // the branches; one camera for every render
  render_params rp;
  rp.msaa = 0;
  rp.shafts = light_shafts::off;
  rp.shadows = false;              // the shadow map's fit follows the bounds; lighting alone here
  rp.sun_azimuth = 60;             // the sun over the viewer's shoulder: the branches' lit sides show
  rp.sun_elevation = 35;
  rp.auto_exposure = false;
  rp.leaf_color_variation = 0;     // the tint hashes the leaf's position, which the CPU pose moves
  auto draw = [&](const tree_mesh& mesh, bool wind) {
    upload_tree(r, mesh);
    if (wind) upload_wind(r, t);
    set_tree_step(r, t, mp.min_radius, t.steps);
    render_params q = rp;
    q.wind = wind ? w : wind_params{};
    r.wind_time = when;
    draw_frame(r, q, cam, size, size, target.fbo);
    return target.read();
  };
  const auto shader = draw(rest, true);
  const auto cpu = draw(posed(rest, rig, m, when, true), false);
  const auto unturned = draw(posed(rest, rig, m, when, false), false);
  const auto calm = draw(rest, false);
  // Pixels whose colour differs by more than 10 of 255 in a channel.
  auto differing = [](const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.size(); i += 4)
      n += std::max({std::abs(int(a[i]) - int(b[i])), std::abs(int(a[i + 1]) - int(b[i + 1])), std::abs(int(a[i + 2]) - int(b[i + 2]))}) > 10;
    return n;
  };
  const size_t moved = differing(shader, calm), vs_cpu = differing(shader, cpu), vs_unturned = differing(shader, unturned);
  std::printf("pixels differing: shader vs calm %zu, vs CPU pose with turned normals %zu, vs CPU pose with rest normals %zu\n",
              moved, vs_cpu, vs_unturned);
  EXPECT_GT(moved, size_t(size * size / 100)) << "the tree sways";
  EXPECT_LT(vs_cpu * 5, vs_unturned) << "the shading matches the turned normals, not the rest ones";
  EXPECT_LT(vs_cpu, size_t(size * size / 200)) << "shader and CPU pose agree but at leaf card edges (the CPU poses each card rigidly)";
}

// Leaf flutter: the blade flaps along its normal, more toward the tip, and wind_flutter_frame turns
// its frame by the flap's slope. The GLSL itself is run (transform feedback) at points along a
// blade; the blade's direction, taken by central differences of the returned positions, must be
// the returned bitangent's, and the returned normal perpendicular to it.
TEST_F(WindNormals, LeafFlutterTurnsTheBladeFrame) {
  const std::string vs = std::string("#version 330 core\n") + wind_glsl() + R"(
uniform float u_size; uniform float u_phase; uniform int u_steps;
out vec3 o_p; out vec3 o_n; out vec3 o_b;
void main() {
  float tip = float(gl_VertexID) / float(u_steps);
  vec3 n = vec3(0.0, 0.0, 1.0), b = vec3(0.0, 1.0, 0.0);
  o_p = wind_flutter_frame(vec3(0.0, tip * u_size, 0.0), n, b, tip, u_size, u_phase);
  o_n = n; o_b = b;
}
)";
  auto compile = [](GLenum type, const std::string& src) {
    const GLuint s = glCreateShader(type);
    const char* c = src.c_str();
    glShaderSource(s, 1, &c, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    EXPECT_TRUE(ok);
    return s;
  };
  const GLuint v = compile(GL_VERTEX_SHADER, vs);
  const GLuint f = compile(GL_FRAGMENT_SHADER, "#version 330 core\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n");
  gl_program prog;
  prog.id = glCreateProgram();
  glAttachShader(prog.id, v);
  glAttachShader(prog.id, f);
  const char* varyings[] = {"o_p", "o_n", "o_b"};
  glTransformFeedbackVaryings(prog.id, 3, varyings, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(prog.id);
  GLint linked = 0;
  glGetProgramiv(prog.id, GL_LINK_STATUS, &linked);
  ASSERT_TRUE(linked);
  glDeleteShader(v);
  glDeleteShader(f);

  const int steps = 200;
  const float size = 0.5f;
  gl_buffer out;
  glGenBuffers(1, &out.id);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, out.id);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, (steps + 1) * 9 * sizeof(float), nullptr, GL_STATIC_READ);
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glUseProgram(prog.id);
  wind_params w;
  w.enabled = true;
  w.strength = 1;
  w.leaf_flutter = 1;
  const wind_motion m = make_wind_motion(w);
  set_uniform(prog, "u_wind_on", 1);
  set_uniform(prog, "u_wind_strength", m.strength);
  set_uniform(prog, "u_wind_flutter", m.flutter);
  set_uniform(prog, "u_wind_leaf_hz", m.leaf_hz);
  set_uniform(prog, "u_size", size);
  set_uniform(prog, "u_steps", steps);
  float largest_turn = 0, worst = 0;
  for (float time : {0.0f, 0.13f, 0.31f, 0.55f}) {
    set_uniform(prog, "u_wind_time", time);
    set_uniform(prog, "u_phase", 1.0f + time);
    glEnable(GL_RASTERIZER_DISCARD);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, out.id);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, steps + 1);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    std::vector<glm::vec3> got(size_t(steps + 1) * 3);
    glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, GLsizeiptr(got.size() * sizeof(glm::vec3)), got.data());
    for (int i = 1; i < steps; ++i) {
      const glm::vec3 along = glm::normalize(got[size_t(i + 1) * 3] - got[size_t(i - 1) * 3]);
      const glm::vec3 n = glm::normalize(got[size_t(i) * 3 + 1]), b = glm::normalize(got[size_t(i) * 3 + 2]);
      EXPECT_NEAR(glm::dot(along, b), 1.0f, 2e-4f) << "t " << time << " tip " << i;
      EXPECT_NEAR(glm::dot(along, n), 0.0f, 1e-3f) << "t " << time << " tip " << i;
      worst = std::max(worst, std::abs(glm::dot(along, n)));
      largest_turn = std::max(largest_turn, std::acos(std::min(1.0f, n.z)));
    }
  }
  std::printf("flutter: the blade turns up to %.2f rad; normal . blade direction at most %.1e\n", double(largest_turn), double(worst));
  EXPECT_GT(largest_turn, 0.2f) << "the flap turns the blade";
  glDeleteVertexArrays(1, &vao);
  glUseProgram(0);
  delete_gl(out);
  delete_gl(prog);
}
