// General L-system engine: language, derivation counts, context, stochastic rules, turtle, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "generators/lsystem_engine.h"
#include "generators/tree_spec.h"
#include "render/io/preset.h"
#include "tests/generators/generator_specs.h"

using namespace sylva;

namespace {

lsystem_string derive_text(const std::string& src, int n, uint64_t seed = 1, lsystem_derive_report* out = nullptr,
                           int64_t cap = 4000000) {
  lsystem_program prog;
  const lsystem_error err = compile_lsystem(src, prog);
  EXPECT_TRUE(err.ok()) << err.line << ":" << err.column << " " << err.message;
  lsystem_derive_report rep;
  lsystem_string s = derive_lsystem(prog, n, seed, cap, {}, rep);
  if (out) *out = rep;
  return s;
}

std::string derive_str(const std::string& src, int n, uint64_t seed = 1) {
  return format_lsystem_string(derive_text(src, n, seed));
}

using sylva_test::text_params;

size_t count_symbol(const lsystem_string& s, char c) {
  return size_t(std::count_if(s.modules.begin(), s.modules.end(), [&](const lsystem_module& m) { return m.symbol == c; }));
}

const std::string honda_text =
    "#define r1 0.75\n#define r2 0.77\n#define a1 35\n#define a2 -35\n#define p1 0\n#define p2 137\n"
    "#define q 0.5\n#define e 0.4\n#define min 0\n#axiom A(100,30)\n"
    "A(s,w) : s >= min -> !(w)F(s)[+(a1)/(p1)A(s*r1,w*q^e)][+(a2)/(p2)A(s*r2,w*(1-q)^e)]\n";

}  // namespace

TEST(LSystem, Seed004BinaryTreeStrings) {
  // Seed 004 lists the first three derivations of a -> b[a]a, b -> bb verbatim.
  const std::string src = "#axiom a\na -> b[a]a\nb -> bb\n";
  EXPECT_EQ(derive_str(src, 1), "b[a]a");
  EXPECT_EQ(derive_str(src, 2), "bb[b[a]a]b[a]a");
  EXPECT_EQ(derive_str(src, 3), "bbbb[bb[b[a]a]b[a]a]bb[b[a]a]b[a]a");
  // a(n) = 2^n; b(n+1) = 2b(n) + a(n) = 0,1,4,12,32,80,192; bracket pairs 2^n - 1.
  const lsystem_string s6 = derive_text(src, 6);
  EXPECT_EQ(count_symbol(s6, 'a'), 64u);
  EXPECT_EQ(count_symbol(s6, 'b'), 192u);
  EXPECT_EQ(count_symbol(s6, '['), 63u);
  EXPECT_EQ(s6.modules.size(), 64u + 192u + 126u);
}

TEST(LSystem, Abop124aCounts) {
  // F -> F[+F]F[-F]F: F(n) = 5^n; each F adds 10 non-F modules, so L(n+1) = L(n) + 10·5^n.
  const std::string src = "#angle 25.7\n#axiom F\nF -> F[+F]F[-F]F\n";
  lsystem_inspection in = inspect_lsystem(src, 3, 5);
  ASSERT_TRUE(in.error.ok());
  EXPECT_EQ(in.module_counts, (std::vector<size_t>{1, 11, 61, 311}));
  EXPECT_EQ(in.first_modules, "F[+F]");
  grow_report rep;
  tree_skeleton t = grow_lsystem(text_params(src, 3), {}, &rep);
  EXPECT_EQ(t.size(), 1u + 125u);  // the root plus one node per F
  EXPECT_EQ(validate_skeleton(t), "");
  EXPECT_FALSE(rep.error) << rep.message;
}

TEST(LSystem, KochIslandCountsAndCloses) {
  // ABOP Fig. 1.7a: 8 F and 6 turns per F; F(n) = 4·8^n, L(n+1) = L(n) + 13·F(n).
  const std::string src = "#angle 90\n#axiom F-F-F-F\nF -> F-F+F+FF-F-F+F\n";
  lsystem_inspection in = inspect_lsystem(src, 2);
  EXPECT_EQ(in.module_counts, (std::vector<size_t>{7, 7 + 13 * 4, 7 + 13 * 4 + 13 * 32}));
  tree_skeleton t = grow_lsystem(text_params(src, 2), {});
  ASSERT_EQ(t.size(), 1u + 256u);
  EXPECT_NEAR(glm::length(t.position.back() - t.position.front()), 0.0f, 1e-3f);  // the island closes
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(LSystem, SquareCloses) {
  // H starts at +Y; + turns left about U = +Z, so the square runs up, then towards -X.
  tree_skeleton t = grow_lsystem(text_params("#angle 90\n#axiom F+F+F+F\n", 0), {});
  ASSERT_EQ(t.size(), 5u);
  EXPECT_NEAR(glm::length(t.position[1] - glm::vec3(0, 1, 0)), 0, 1e-6f);
  EXPECT_NEAR(glm::length(t.position[2] - glm::vec3(-1, 1, 0)), 0, 1e-6f);
  EXPECT_NEAR(glm::length(t.position[3] - glm::vec3(-1, 0, 0)), 0, 1e-6f);
  EXPECT_NEAR(glm::length(t.position[4]), 0, 1e-6f);
  for (size_t i = 1; i < 5; ++i) EXPECT_EQ(t.parent[i], int32_t(i - 1));
}

TEST(LSystem, ContextSensitiveSignal) {
  // ABOP §1.8 signal propagation: b moves one module to the right per derivation.
  const std::string src = "#axiom baaaa\nb < a -> b\nb -> a\n";
  EXPECT_EQ(derive_str(src, 1), "abaaa");
  EXPECT_EQ(derive_str(src, 3), "aaaba");
  // Ignored symbols are passed over when looking for context.
  EXPECT_EQ(derive_str("#ignore +\n#axiom b+a+a\nb < a -> b\nb -> a\n", 1), "a+b+a");
  EXPECT_EQ(derive_str("#axiom b+a+a\nb < a -> b\nb -> a\n", 1), "a+a+a");
  // Left context reaches the parent axis from inside a branch and skips a finished branch.
  EXPECT_EQ(derive_str("#axiom b[a]a\nb < a -> b\nb -> a\n", 1), "a[b]b");
  // Right context skips lateral branches along the axis.
  EXPECT_EQ(derive_str("#axiom a[x]b\na > b -> c\n", 1), "c[x]b");
  EXPECT_EQ(derive_str("#axiom a[b]\na > b -> c\n", 1), "a[b]");
  // Context parameters bind like the predecessor's.
  EXPECT_EQ(derive_str("#axiom A(1)B(2)C(4)\nA(x) < B(y) > C(z) -> B(x+y*z)\n", 1), "A(1)B(9)C(4)");
}

TEST(LSystem, StochasticWithFixedSeed) {
  const std::string src = "#axiom " + std::string(1000, 'A') + "\nA -> (1) B\nA -> (3) C\n";
  const lsystem_string s = derive_text(src, 1, 7);
  const size_t b = count_symbol(s, 'B'), c = count_symbol(s, 'C');
  EXPECT_EQ(b + c, 1000u);
  // P(B) = 1/4: mean 250, σ ≈ 13.7, so ±70 is five σ.
  EXPECT_GT(b, 180u);
  EXPECT_LT(b, 320u);
  EXPECT_EQ(format_lsystem_string(s), derive_str(src, 1, 7));   // same seed, same string
  EXPECT_NE(format_lsystem_string(s), derive_str(src, 1, 8));   // another seed, another string
  // A zero-weight alternative is never chosen.
  EXPECT_EQ(derive_str("#axiom AAAAAAAA\nA -> (0) B\nA -> (2) C\n", 1), "CCCCCCCC");
}

TEST(LSystem, ConditionStopsGrowth) {
  // s = 1, 0.5, 0.25 satisfy s >= 0.2; 0.125 does not, so the apex stays forever.
  const std::string src = "#define min 0.2\n#axiom A(1)\nA(s) : s >= min -> F(s)A(s*0.5)\n";
  lsystem_derive_report rep;
  EXPECT_EQ(format_lsystem_string(derive_text(src, 10, 1, &rep)), "F(1)F(0.5)F(0.25)A(0.125)");
  EXPECT_EQ(rep.module_counts, (std::vector<size_t>{1, 2, 3, 4, 4, 4, 4, 4, 4, 4, 4}));
  EXPECT_EQ(rep.derivations, 10);
}

TEST(LSystem, ExpressionPrecedence) {
  const std::string src =
      "#axiom A(2+3*4^2, -2^2, 2^3^2, 10-4-3, 8/4/2, 1+2>2&&0||1, 1+2>2&&0, !0, min(3,max(1,2)), floor(2.7), "
      "(2+3)*4, 7>=7, 3!=3, 2*-3, sqrt(16)+abs(-1), sin(90), 2^-1)\n";
  const lsystem_string s = derive_text(src, 0);
  const std::vector<float> expected{50, -4, 512, 3, 1, 1, 0, 1, 2, 2, 20, 1, 0, -6, 5, 1, 0.5f};
  ASSERT_EQ(s.params.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(s.params[i], expected[i], 1e-6f) << "argument " << i;
}

TEST(LSystem, ParseErrorPositions) {
  lsystem_error e = lsystem_check("#axiom F\nF -> F(1+*2)\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 10);  // the '*'
  e = lsystem_check("#axiom F\nF -> F(x)\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 8);
  EXPECT_NE(e.message.find("'x'"), std::string::npos);
  e = lsystem_check("#axiom F\nF F\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_EQ(e.column, 1);
  e = lsystem_check("// comment\n#axiom F\n  #foo 1\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.column, 3);
  e = lsystem_check("#define a 1\nF -> F\n");
  EXPECT_NE(e.message.find("axiom"), std::string::npos);
  EXPECT_TRUE(lsystem_check(honda_text).ok());
  // The tree grown from a broken text is a single node with the message, never a crash.
  grow_report rep;
  tree_skeleton t = grow_lsystem(text_params("#axiom F(\n", 3), {}, &rep);
  EXPECT_TRUE(rep.error);
  EXPECT_NE(rep.message.find("line 1"), std::string::npos);
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(LSystem, ModuleCapStopsWithMessage) {
  // F -> FF doubles: 512 modules after 9 derivations, 1024 > 1000 after 10.
  lsystem_params p = text_params("#axiom F\nF -> FF\n", 20);
  p.module_cap = 1000;
  grow_report rep;
  tree_skeleton t = grow_lsystem(p, {}, &rep);
  EXPECT_NE(rep.message.find("module cap"), std::string::npos);
  EXPECT_EQ(t.steps, 9);
  EXPECT_EQ(t.size(), 1u + 512u);
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(LSystem, HostileInputIsAnErrorNotACrash) {
  EXPECT_FALSE(lsystem_check("#axiom F(" + std::string(100000, '(') + "1" + std::string(100000, ')') + ")\n").ok());
  EXPECT_FALSE(lsystem_check("#axiom F(" + std::string(100000, '-') + "1)\n").ok());
  EXPECT_FALSE(lsystem_check("#axiom F(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+(1+1)))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))\n").ok());
  // Unbalanced brackets in the string: the turtle ignores a stray ']' and an unclosed '['.
  tree_skeleton t = grow_lsystem(text_params("#axiom F]]F[[F\n", 0), {});
  EXPECT_EQ(t.size(), 4u);
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(LSystem, CancelReturnsTheAxiomsTree) {   // the node cap: generator_suite_test.cpp
  std::atomic<uint32_t> cancel{1};
  grow_options o;
  o.cancel = &cancel;  // already moved on: returns the axiom's tree
  grow_report rep2;
  tree_skeleton c = grow_lsystem(text_params("#axiom F\nF -> FF\n", 20), o, &rep2);
  EXPECT_TRUE(rep2.cancelled);
  EXPECT_EQ(c.steps, 0);
  EXPECT_EQ(validate_skeleton(c), "");
}

TEST(LSystem, DivisionByZeroNamesProduction) {
  grow_report rep;
  grow_lsystem(text_params("#axiom A(0)\nA(x) -> A(1/x)\n", 2), {}, &rep);
  EXPECT_TRUE(rep.error);
  EXPECT_NE(rep.message.find("division by zero"), std::string::npos);
  EXPECT_NE(rep.message.find("line 2"), std::string::npos);
  EXPECT_NE(rep.message.find("A(x) -> A(1/x)"), std::string::npos);
  grow_report rep2;
  grow_lsystem(text_params("#axiom A(0)\n\nA(x) -> A(sqrt(x-1))\n", 2), {}, &rep2);
  EXPECT_TRUE(rep2.error);
  EXPECT_NE(rep2.message.find("non-finite"), std::string::npos);
  EXPECT_NE(rep2.message.find("line 3"), std::string::npos);
}

TEST(LSystem, HondaTextMatchesHondaMode) {
  lsystem_params text = text_params(honda_text, 8);
  text.scale = 0.02f;
  lsystem_params honda;
  honda.derivations = 8;
  honda.phi2 = 137;
  tree_skeleton a = grow_lsystem(text, {}), b = grow_honda(honda, {});
  ASSERT_EQ(a.size(), size_t(1) << 8);  // as in Honda's own test: 2^n - 1 internodes + the root
  ASSERT_EQ(a.size(), b.size());
  auto sorted = [](const tree_skeleton& t) {
    std::vector<std::array<float, 4>> v;
    for (size_t i = 0; i < t.size(); ++i) v.push_back({t.position[i].x, t.position[i].y, t.position[i].z, t.radius[i]});
    std::sort(v.begin(), v.end());
    return v;
  };
  const auto va = sorted(a), vb = sorted(b);
  for (size_t i = 0; i < va.size(); ++i)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(va[i][size_t(k)], vb[i][size_t(k)], 1e-5f);
}

TEST(LSystem, StepViewIsTreeAfterThatManyDerivations) {
  // Interpreting only the final string with birth steps gives the whole history.
  lsystem_params p = text_params(honda_text, 7);
  tree_skeleton full = grow_lsystem(p, {});
  EXPECT_EQ(validate_skeleton(full), "");
  for (int s = 0; s <= 7; ++s) {
    grow_options o;
    o.steps = s;
    tree_skeleton part = grow_lsystem(p, o);
    std::vector<size_t> alive;
    for (size_t i = 0; i < full.size(); ++i)
      if (full.alive(i, s)) alive.push_back(i);
    ASSERT_EQ(part.size(), alive.size()) << "step " << s;
    for (size_t i = 0; i < part.size(); ++i) {
      EXPECT_EQ(part.position[i], full.position[alive[i]]);
      const int32_t fp = full.parent[alive[i]];
      EXPECT_EQ(part.parent[i], fp < 0 ? -1 : int32_t(std::find(alive.begin(), alive.end(), size_t(fp)) - alive.begin()));
    }
  }
}

TEST(LSystem, RewritingIntoItselfKeepsBirthStep) {
  // F(l) -> F(l*2) is the same internode growing, so it keeps the step it first appeared in.
  const lsystem_string s = derive_text("#axiom A\nA -> F(1)A\nF(l) -> F(l*2)\n", 3);
  EXPECT_EQ(format_lsystem_string(s), "F(4)F(2)F(1)A");
  ASSERT_EQ(s.modules.size(), 4u);
  EXPECT_EQ(s.modules[0].born, 1);
  EXPECT_EQ(s.modules[1].born, 2);
  EXPECT_EQ(s.modules[2].born, 3);
}

TEST(LSystem, TropismBendsTowardT) {
  // After the first F, H = +Y and T = +X: H×T = -Z, α = e·|H×T| = 0.5 rad, turning H to
  // (sin 0.5, cos 0.5, 0) for the second F (ABOP §2.4).
  tree_skeleton t = grow_lsystem(text_params("#tropism 1, 0, 0, 0.5\n#axiom FF\n", 0), {});
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t.position[2].x, std::sin(0.5f), 1e-5f);
  EXPECT_NEAR(t.position[2].y, 1 + std::cos(0.5f), 1e-5f);
  EXPECT_NEAR(t.position[2].z, 0, 1e-5f);
}

TEST(LSystem, TurtleWidthsLeavesAndPieces) {
  lsystem_params p = text_params("#axiom !(4)F[&(90)L]f!(2)F(2)L(3)\n", 0);
  p.scale = 0.5f;
  tree_skeleton t = grow_lsystem(p, {});
  // root, F, then f starts a second piece: a new root and its F.
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t.tree_count, 2);
  EXPECT_EQ(t.parent[3], 2);
  EXPECT_EQ(t.parent[2], -1);
  EXPECT_FLOAT_EQ(t.radius[1], 4 * 0.5f * 0.5f);  // width is a diameter in model units
  EXPECT_FLOAT_EQ(t.radius[3], 2 * 0.5f * 0.5f);
  EXPECT_NEAR(glm::length(t.position[3] - glm::vec3(0, 2.0f, 0)), 0, 1e-6f);  // (1 + 1 + 2)·0.5 up
  ASSERT_EQ(t.leaves.size(), 2u);
  EXPECT_EQ(t.leaves[0].node, 1);
  EXPECT_FLOAT_EQ(t.leaves[0].size, p.leaf_size);
  EXPECT_FLOAT_EQ(t.leaves[1].size, 1.5f);
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(LSystem, ConstantsForTheEditor) {
  std::string src = "#define angle 25 // [0,90] branching angle\n#define n 3\n#angle angle\n#axiom F\nF -> F+F\n";
  std::vector<lsystem_constant> k = lsystem_constants(src);
  ASSERT_EQ(k.size(), 2u);
  EXPECT_EQ(k[0].name, "angle");
  EXPECT_EQ(k[0].value, 25);
  EXPECT_EQ(k[0].min, 0);
  EXPECT_EQ(k[0].max, 90);
  EXPECT_EQ(k[0].help, "branching angle");
  EXPECT_EQ(k[1].min, 0);  // no range given: [0, 2·value]
  EXPECT_EQ(k[1].max, 6);
  EXPECT_TRUE(set_lsystem_constant(src, "angle", 30.5f));
  EXPECT_NE(src.find("#define angle 30.5 // [0,90] branching angle\n"), std::string::npos);
  EXPECT_EQ(lsystem_constants(src)[0].value, 30.5f);
  EXPECT_TRUE(set_lsystem_constant(src, "n", 0.1f));
  EXPECT_NE(src.find("#define n 0.1\n"), std::string::npos);
  EXPECT_FALSE(set_lsystem_constant(src, "nope", 1));
  // Constants may be used above their #define.
  EXPECT_TRUE(lsystem_check("#axiom F(len)\n#define len 2\n").ok());
}

TEST(LSystem, TextPresetsGrowValidTrees) {
  namespace fs = std::filesystem;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SYLVA_SOURCE_DIR) / "presets")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("lsystem_", 0) != 0) continue;
    preset pr;
    const load_result lr = load_preset_file(entry.path().string(), pr);
    ASSERT_TRUE(lr.ok) << name << ": " << lr.error;
    EXPECT_TRUE(lr.warnings.empty()) << name << ": " << lr.warnings.front();
    lsystem_params p = std::get<lsystem_params>(pr.spec.params);
    if (p.mode != lsystem_mode::text) continue;
    EXPECT_TRUE(lsystem_check(p.source).ok()) << name;
    p.derivations = std::min(p.derivations, 5);  // keep the test quick
    grow_report rep;
    tree_skeleton t = grow_lsystem(p, {}, &rep);
    EXPECT_FALSE(rep.error) << name << ": " << rep.message;
    EXPECT_EQ(validate_skeleton(t), "") << name;
    EXPECT_GT(t.size(), 1u) << name;
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

TEST(LSystem, HondaTextPresetsGrowTheHondaPresetTrees) {
  for (char k = 'a'; k <= 'i'; ++k) {
    const std::string dir = std::string(SYLVA_SOURCE_DIR) + "/presets/";
    preset text, honda;
    ASSERT_TRUE(load_preset_file(dir + "lsystem_text_honda_" + k + ".json", text).ok);
    ASSERT_TRUE(load_preset_file(dir + "lsystem_honda_" + k + ".json", honda).ok);
    const tree_skeleton a = grow(text.spec, {}), b = grow(honda.spec, {});
    ASSERT_EQ(a.size(), b.size()) << "tree " << k;
    float ha = 0, hb = 0;
    for (size_t i = 0; i < a.size(); ++i) ha = std::max(ha, a.position[i].y), hb = std::max(hb, b.position[i].y);
    EXPECT_NEAR(ha, hb, 1e-4f * std::max(1.0f, hb)) << "tree " << k;
  }
}

// The turtle's handedness (lsystem_turtle.cpp): ABOP §1.5's matrices as printed, start frame
// H = +Y, L = +X, U = −Z. A known sequence gives a known path and final frame.
TEST(LSystem, TurtleHandednessIsPinned) {
  const tree_skeleton t = grow_lsystem(text_params("#axiom F&(90)F/(90)+(90)FL\n", 0), {});
  ASSERT_EQ(t.size(), 4u);
  auto near = [](const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) < 1e-5f; };
  EXPECT_TRUE(near(t.position[1], {0, 1, 0}));
  EXPECT_TRUE(near(t.position[2], {0, 1, -1}));  // & = R_L(90°) pitches H onto U = −Z
  EXPECT_TRUE(near(t.position[3], {0, 0, -1}));  // / = R_H(−90°) rolls L onto +Y; + = R_U(90°) turns H to −L
  ASSERT_EQ(t.leaves.size(), 1u);
  const glm::quat q = t.leaves[0].orientation;  // leaf axes: X = −L, Y = H, Z = U
  EXPECT_TRUE(near(q * glm::vec3(0, 1, 0), {0, -1, 0}));   // H
  EXPECT_TRUE(near(q * glm::vec3(1, 0, 0), {0, 0, 1}));    // −L, so L = (0, 0, −1)
  EXPECT_TRUE(near(q * glm::vec3(0, 0, 1), {1, 0, 0}));    // U = H × L
  // In the plane a viewer on +Z sees, + turns anticlockwise ("turn left") and - clockwise, so
  // ABOP's 2D figures come out as printed.
  EXPECT_TRUE(near(grow_lsystem(text_params("#axiom +(90)F\n", 0), {}).position[1], {-1, 0, 0}));
  EXPECT_TRUE(near(grow_lsystem(text_params("#axiom -(90)F\n", 0), {}).position[1], {1, 0, 0}));
  // \ and / undo each other; & and ^ too.
  EXPECT_TRUE(near(grow_lsystem(text_params("#axiom &(30)\\(50)/(50)^(30)F\n", 0), {}).position[1], {0, 1, 0}));
  // Honda's tree builds a daughter's frame [+(α)/(φ)...] with the same functions.
  const glm::mat3 f = turtle_roll(turtle_turn(lsystem_start_frame(), 90), -90);
  EXPECT_TRUE(near(f[0], {-1, 0, 0}));
  EXPECT_TRUE(near(f[1], {0, 0, 1}));   // / = R_H(−90°) carries L = +Y to −U = +Z
}

TEST(LSystem, DollarRollsLeftVectorHorizontal) {
  // &(45) tilts H; /(30) then rolls about the tilted H, lifting L off the horizontal. $ brings it
  // back: L = V×H/|V×H| has no vertical component (ABOP §1.5). A leaf's local X axis is -L.
  auto leaf_x = [](const std::string& axiom) {
    tree_skeleton t = grow_lsystem(text_params("#axiom " + axiom + "\n", 0), {});
    return t.leaves.at(0).orientation * glm::vec3(1, 0, 0);
  };
  EXPECT_GT(std::fabs(leaf_x("&(45)/(30)L").y), 0.1f);
  const glm::vec3 x = leaf_x("&(45)/(30)$L");
  EXPECT_NEAR(x.y, 0, 1e-6f);
  EXPECT_NEAR(glm::length(x), 1, 1e-5f);
}

TEST(LSystem, RandIsSeeded) {
  const std::string src = "#axiom AAAA\nA -> B(rand(), rand(2,3))\n";
  const lsystem_string a = derive_text(src, 1, 5);
  ASSERT_EQ(a.params.size(), 8u);
  for (size_t i = 0; i < 8; i += 2) {
    EXPECT_GE(a.params[i], 0.0f);
    EXPECT_LT(a.params[i], 1.0f);
    EXPECT_GE(a.params[i + 1], 2.0f);
    EXPECT_LT(a.params[i + 1], 3.0f);
  }
  EXPECT_EQ(a.params, derive_text(src, 1, 5).params);
  EXPECT_NE(a.params, derive_text(src, 1, 6).params);
}

TEST(LSystemWidths, PipeWidthsThickenFromTheTips) {
  // Fig. 1.24a-like system with n = 1: F -> F[+F]F[-F]F gives one axis of three F with two
  // one-F branches, i.e. three tips. With the pipe model the first segment carries all three:
  // r = r0 * 3^(1/n).
  lsystem_params p;
  p.mode = lsystem_mode::text;
  p.source = "#angle 25\n#axiom F\nF -> F[+F]F[-F]F\n";
  p.derivations = 1;
  p.widths = lsystem_widths::pipe;
  p.pipe_exponent = 2;
  p.tip_radius = 0.01f;
  tree_skeleton t = grow_lsystem(p, {});
  ASSERT_EQ(validate_skeleton(t), "");
  ASSERT_EQ(t.size(), 6u);  // root + five F
  int tips = 0;
  std::vector<int> children(t.size(), 0);
  for (size_t i = 1; i < t.size(); ++i) ++children[t.parent[i]];
  for (size_t i = 0; i < t.size(); ++i) {
    if (children[i] == 0) {
      ++tips;
      EXPECT_FLOAT_EQ(t.radius[i], 0.01f);
    }
  }
  EXPECT_EQ(tips, 3);
  EXPECT_NEAR(t.radius[0], 0.01f * std::sqrt(3.0f), 1e-6f);
}

TEST(LsystemWarnings, UnbalancedBracketsIdleParametersAndDeadProductions) {
  // Clean sources warn about nothing (ABOP 1.24d, a parametric one with a condition holding '>').
  EXPECT_TRUE(lsystem_warnings("#axiom X\nX -> F[+X]F[-X]+X\nF -> FF\n").empty());
  EXPECT_TRUE(lsystem_warnings("#axiom A(1)\nA(s) : s >= 0 && s < 9 -> F(s)[+A(s*0.5)]A(s+1)\n").empty());
  // An unbalanced ']' at its column; an unclosed '['.
  std::vector<lsystem_error> w = lsystem_warnings("#axiom X\nX -> F]+X\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].line, 2);
  EXPECT_EQ(w[0].column, 7);
  EXPECT_NE(w[0].message.find("']'"), std::string::npos);
  w = lsystem_warnings("#axiom X\nX -> F[+X\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].column, 7);
  // A module with parameters that nothing reads.
  w = lsystem_warnings("#axiom X\nX -> F Q(2) X\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].column, 8);
  EXPECT_NE(w[0].message.find("'Q'"), std::string::npos);
  // A production for a symbol that never occurs.
  w = lsystem_warnings("#axiom X\nX -> F X\nB -> FF\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].line, 3);
  EXPECT_EQ(w[0].column, 1);
  // A source with an error has no warnings (the error is shown instead); the tree still grows.
  EXPECT_TRUE(lsystem_warnings("X -> F]").empty());
}
