// General L-system engine (ABOP): source language, bytecode expressions, derivation, 3D turtle.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/lsystem.h"
#include "generators/skeleton.h"

// The language (text mode), one statement per line:
//   // comment                      whole-line comments only ('/' and '//' are roll modules)
//   #define NAME expr // [min,max] help   a constant; becomes a slider; usable anywhere, also above
//   #axiom modules                   the start string, e.g. !(1)F(200)/(45)A
//   #angle expr   #step expr   #width expr      default δ (degrees), F/f length, !-width
//   #tropism x, y, z, e              tropism vector T and susceptibility e (ABOP §2.4)
//   #ignore + - /                    symbols skipped when matching context
//   #draw a b                        further symbols that draw like F
//   left < pred > right : cond -> (prob) successor
// A module is one ASCII character with an optional (expr, ...) list; predecessors and contexts
// name their parameters instead. `: *` means no condition. Lines with equal headers and a
// (prob) form one stochastic production; weights need not sum to 1. The first production that
// matches rewrites a module; an unmatched module is copied. The derivation count is the schema's
// `derivations` field (a slider, and the growth-step count), not part of the text.
// Expressions: + - * / ^ (right-assoc., tighter than unary minus), < <= > >= == != && || !,
// sqrt sin cos tan (degrees) exp log abs floor min max, rand() in [0,1) and rand(a,b), seeded.
// Turtle: F(l) f(l) + - & ^ \ / (optional angle) | [ ] !(w) $ L(size) ' as in ABOP ch. 1.
namespace sylva {

// A parse or evaluation error; line and column are 1-based, line 0 means "no error".
struct lsystem_error {
  int line = 0;
  int column = 0;
  std::string message;
  bool ok() const { return message.empty(); }
};

// A `#define NAME value // [min,max] help` constant: the editor shows it as a slider.
struct lsystem_constant {
  std::string name;
  float value = 0, min = 0, max = 1;
  std::string help;
  int line = 0;
};

// One bytecode instruction of a stack machine over float; an expression is a range of them.
struct lsystem_op {
  uint8_t code = 0;
  uint8_t arg = 0;   // variable slot or function id
  float value = 0;   // literal (constants are folded in at compile time)
};
struct lsystem_expr {
  uint32_t begin = 0, end = 0;  // range in lsystem_program::code
};

// A module of a successor or the axiom: its parameters are expressions exprs[first, first+count).
struct lsystem_module_template {
  uint8_t symbol = 0;
  uint8_t count = 0;
  uint32_t first = 0;
};
struct lsystem_successor {
  int probability = -1;  // expression index, -1 when deterministic
  std::vector<lsystem_module_template> modules;
  int inherit = -1;      // module that keeps the predecessor's birth step (first with its symbol)
};
struct lsystem_pattern {
  uint8_t symbol = 0;
  uint8_t count = 0;     // number of formal parameters
};
// A production `left < pred > right : cond -> succ`, with one successor per stochastic alternative.
struct lsystem_rule {
  lsystem_pattern pred;
  std::vector<lsystem_pattern> left, right;  // context, nearest module last (left) / first (right)
  int condition = -1;                        // expression index, -1 for none
  std::vector<lsystem_successor> successors;
  int line = 0;
  std::string text;   // the production as written, for error messages
  std::string header; // normalised "left<pred>right:cond", to group stochastic alternatives
};

struct lsystem_program {
  std::vector<lsystem_op> code;
  std::vector<lsystem_expr> exprs;
  std::vector<lsystem_rule> rules;
  std::array<std::vector<uint16_t>, 256> rules_of{};  // rule indices by predecessor symbol
  lsystem_successor axiom;
  std::vector<lsystem_constant> constants;
  std::array<bool, 256> ignored{};  // skipped when matching context (#ignore)
  std::array<bool, 256> draws{};    // symbols drawn like F (#draw); F is always drawn
  bool has_context = false;
  float angle = 90;                 // default δ in degrees (#angle)
  float step = 1;                   // default F / f length (#step)
  float width = 1;                  // default width, model units (#width)
  glm::vec3 tropism{0, -1, 0};      // T (#tropism x, y, z, e)
  float susceptibility = 0;         // e
};

// A derived string, stored compactly: 8 bytes per module plus 4 per parameter.
struct lsystem_module {
  uint8_t symbol = 0;
  uint8_t count = 0;    // parameters at params[param, param+count)
  uint16_t born = 0;    // derivation that created the module (0: axiom)
  uint32_t param = 0;
};
struct lsystem_string {
  std::vector<lsystem_module> modules;
  std::vector<float> params;
};

struct lsystem_derive_report {
  int derivations = 0;                  // derivations completed
  std::vector<size_t> module_counts;    // modules after derivation k (k = 0: the axiom)
  bool hit_module_cap = false;
  bool cancelled = false;
  bool error = false;
  std::string message;
};

enum lsystem_opcode : uint8_t {
  op_push, op_var, op_add, op_sub, op_mul, op_div, op_pow, op_neg, op_not,
  op_lt, op_le, op_gt, op_ge, op_eq, op_ne, op_and, op_or, op_call1, op_call2, op_rand, op_rand2,
};
enum lsystem_function : uint8_t {
  fn_sqrt, fn_sin, fn_cos, fn_tan, fn_exp, fn_log, fn_abs, fn_floor, fn_min, fn_max,
};

// Runs one compiled expression; false on division by zero. Trig functions take degrees, like the
// turtle's angles (as in cpfg). The stack depth is bounded at compile time.
inline bool eval_lsystem_expr(const lsystem_program& prog, int expr, const float* vars, rng& r, float& out) {
  float st[64];
  int n = 0;
  const lsystem_expr& e = prog.exprs[size_t(expr)];
  constexpr float deg = 0.017453292519943295f;
  for (uint32_t i = e.begin; i < e.end; ++i) {
    const lsystem_op& op = prog.code[i];
    switch (op.code) {
      case op_push: st[n++] = op.value; break;
      case op_var: st[n++] = vars[op.arg]; break;
      case op_add: --n; st[n - 1] += st[n]; break;
      case op_sub: --n; st[n - 1] -= st[n]; break;
      case op_mul: --n; st[n - 1] *= st[n]; break;
      case op_div: --n; if (st[n] == 0) return false; st[n - 1] /= st[n]; break;
      case op_pow: --n; st[n - 1] = std::pow(st[n - 1], st[n]); break;
      case op_neg: st[n - 1] = -st[n - 1]; break;
      case op_not: st[n - 1] = st[n - 1] == 0 ? 1.0f : 0.0f; break;
      case op_lt: --n; st[n - 1] = st[n - 1] < st[n]; break;
      case op_le: --n; st[n - 1] = st[n - 1] <= st[n]; break;
      case op_gt: --n; st[n - 1] = st[n - 1] > st[n]; break;
      case op_ge: --n; st[n - 1] = st[n - 1] >= st[n]; break;
      case op_eq: --n; st[n - 1] = st[n - 1] == st[n]; break;
      case op_ne: --n; st[n - 1] = st[n - 1] != st[n]; break;
      case op_and: --n; st[n - 1] = (st[n - 1] != 0 && st[n] != 0); break;
      case op_or: --n; st[n - 1] = (st[n - 1] != 0 || st[n] != 0); break;
      case op_call1: {
        float& x = st[n - 1];
        switch (op.arg) {
          case fn_sqrt: x = std::sqrt(x); break;
          case fn_sin: x = std::sin(x * deg); break;
          case fn_cos: x = std::cos(x * deg); break;
          case fn_tan: x = std::tan(x * deg); break;
          case fn_exp: x = std::exp(x); break;
          case fn_log: x = std::log(x); break;
          case fn_abs: x = std::fabs(x); break;
          default: x = std::floor(x); break;
        }
        break;
      }
      case op_call2: --n; st[n - 1] = op.arg == fn_min ? std::min(st[n - 1], st[n]) : std::max(st[n - 1], st[n]); break;
      case op_rand: st[n++] = r.uniform(); break;
      default: --n; st[n - 1] = r.uniform(st[n - 1], st[n]); break;  // op_rand2
    }
  }
  out = st[0];
  return true;
}

// Parses and compiles a source; on error `out` is unspecified.
lsystem_error compile_lsystem(const std::string& source, lsystem_program& out);

// Derives `derivations` steps from the axiom. Stops before a string would exceed module_cap,
// and at the first division by zero or non-finite value (the message names the production).
lsystem_string derive_lsystem(const lsystem_program& prog, int derivations, uint64_t seed, int64_t module_cap,
                              const grow_options& o, lsystem_derive_report& report);

// Interprets a derived string with the 3D turtle (ABOP ch. 1). Node `born` is the derivation of
// its F module (never earlier than its parent), so the final string alone carries the history.
tree_skeleton interpret_lsystem(const lsystem_program& prog, const lsystem_string& s, const lsystem_params& p,
                                int steps, grow_report& report, const grow_options* o = nullptr);

// "F(1,2.5)[+A]..." for the first `first_n` modules (all when first_n < 0).
std::string format_lsystem_string(const lsystem_string& s, long first_n = -1);

// Text mode of grow_lsystem: compile, derive, interpret.
tree_skeleton grow_lsystem_text(const lsystem_params& p, const grow_options& o, grow_report* report = nullptr);

// --- Editor support ---

// The #define constants of a source with their ranges and help (empty on a parse error before them).
std::vector<lsystem_constant> lsystem_constants(const std::string& source);
// Rewrites the value of `#define name ...`, keeping its comment; false when there is no such line.
bool set_lsystem_constant(std::string& source, const std::string& name, float value);
// First error of a source, or an ok() error.
lsystem_error lsystem_check(const std::string& source);
// Warnings for a source that compiles but probably does not say what was meant, each at its line
// and column: an unbalanced '[' or ']' in the axiom or a successor; a module with parameters that
// is neither a turtle command nor the predecessor of a production (its parameters do nothing); a
// production whose predecessor occurs in neither the axiom nor any successor (it never applies).
// The tree still grows as written. Empty when the source has an error.
std::vector<lsystem_error> lsystem_warnings(const std::string& source);

// Derivation inspector: module count per step and the first modules of the last string.
struct lsystem_inspection {
  lsystem_error error;               // parse error, if any
  std::vector<size_t> module_counts; // after derivation k, k = 0 the axiom
  std::string first_modules;         // text of the first N modules after the last derivation
  std::string message;               // module cap / evaluation error, "" when all went well
};
lsystem_inspection inspect_lsystem(const std::string& source, int derivations, long first_n = 200,
                                   uint64_t seed = 1, int64_t module_cap = 4000000);

}  // namespace sylva
