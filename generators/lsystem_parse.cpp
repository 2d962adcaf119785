// L-system source language: directives, productions, the expression compiler and editor helpers.
#include <array>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "generators/lsystem_engine.h"

namespace sylva {
namespace {

// Thrown only inside this file and caught by compile_lsystem, so nothing throws across the UI.
struct parse_failure {
  size_t at;  // 0-based index in the line
  std::string message;
};

struct source_line {
  size_t start, length;
};

std::vector<source_line> split_lines(const std::string& s) {
  std::vector<source_line> out;
  size_t b = 0;
  while (b <= s.size()) {
    size_t e = s.find('\n', b);
    if (e == std::string::npos) e = s.size();
    size_t len = e - b;
    if (len > 0 && s[b + len - 1] == '\r') --len;
    out.push_back({b, len});
    if (e == s.size()) break;
    b = e + 1;
  }
  return out;
}

bool is_space(char c) { return c == ' ' || c == '\t'; }
bool is_ident_start(char c) { return std::isalpha((unsigned char)c) || c == '_'; }
bool is_ident(char c) { return std::isalnum((unsigned char)c) || c == '_'; }

struct function_name {
  const char* name;
  uint8_t id;
  int arity;
};
constexpr function_name functions[] = {{"sqrt", fn_sqrt, 1}, {"sin", fn_sin, 1},     {"cos", fn_cos, 1},
                                       {"tan", fn_tan, 1},   {"exp", fn_exp, 1},     {"log", fn_log, 1},
                                       {"abs", fn_abs, 1},   {"floor", fn_floor, 1}, {"min", fn_min, 2},
                                       {"max", fn_max, 2}};

// Recursive-descent compiler from one line's text to stack bytecode. Precedence, loosest first:
// || && (== !=) (< <= > >=) (+ -) (* /) unary(- + !) ^ (right-associative, binds tighter than
// unary minus, so -2^2 = -4 as in mathematics).
struct expr_compiler {
  lsystem_program& prog;
  const std::string& text;
  size_t pos = 0;
  size_t end = 0;
  const std::vector<std::string>* vars = nullptr;
  int depth = 0, max_depth = 0;
  int nesting = 0;  // recursion depth of the parser itself, bounded so no input overflows the stack

  [[noreturn]] void fail(size_t at, std::string msg) { throw parse_failure{at, std::move(msg)}; }
  void skip() {
    while (pos < end && is_space(text[pos])) ++pos;
  }
  bool peek(const char* s) {
    skip();
    const size_t n = std::strlen(s);
    return pos + n <= end && text.compare(pos, n, s) == 0;
  }
  bool eat(const char* s) {
    if (!peek(s)) return false;
    pos += std::strlen(s);
    return true;
  }
  void emit(uint8_t code, int delta, uint8_t arg = 0, float value = 0) {
    prog.code.push_back({code, arg, value});
    depth += delta;
    max_depth = std::max(max_depth, depth);
  }

  // Compiles one expression and returns its index in prog.exprs.
  int compile() {
    const uint32_t begin = uint32_t(prog.code.size());
    depth = max_depth = nesting = 0;
    skip();
    const size_t at = pos;
    parse_or();
    if (max_depth > 60) fail(at, "expression too deeply nested");
    prog.exprs.push_back({begin, uint32_t(prog.code.size())});
    return int(prog.exprs.size() - 1);
  }

  void parse_or() {
    parse_and();
    while (eat("||")) { parse_and(); emit(op_or, -1); }
  }
  void parse_and() {
    parse_eq();
    while (eat("&&")) { parse_eq(); emit(op_and, -1); }
  }
  void parse_eq() {
    parse_cmp();
    for (;;) {
      if (eat("==")) { parse_cmp(); emit(op_eq, -1); }
      else if (eat("!=")) { parse_cmp(); emit(op_ne, -1); }
      else break;
    }
  }
  void parse_cmp() {
    parse_add();
    for (;;) {
      if (eat("<=")) { parse_add(); emit(op_le, -1); }
      else if (eat(">=")) { parse_add(); emit(op_ge, -1); }
      else if (eat("<")) { parse_add(); emit(op_lt, -1); }
      else if (eat(">")) { parse_add(); emit(op_gt, -1); }
      else break;
    }
  }
  void parse_add() {
    parse_mul();
    for (;;) {
      if (peek("->")) break;  // never part of an expression
      if (eat("+")) { parse_mul(); emit(op_add, -1); }
      else if (eat("-")) { parse_mul(); emit(op_sub, -1); }
      else break;
    }
  }
  void parse_mul() {
    parse_unary();
    for (;;) {
      if (peek("//")) break;
      if (eat("*")) { parse_unary(); emit(op_mul, -1); }
      else if (eat("/")) { parse_unary(); emit(op_div, -1); }
      else break;
    }
  }
  void parse_unary() {
    if (++nesting > 200) fail(pos, "expression too deeply nested");
    parse_unary_inner();
    --nesting;
  }
  void parse_unary_inner() {
    if (eat("-")) { parse_unary(); emit(op_neg, 0); }
    else if (eat("+")) parse_unary();
    else if (!peek("!=") && eat("!")) { parse_unary(); emit(op_not, 0); }
    else parse_power();
  }
  void parse_power() {
    parse_primary();
    if (eat("^")) { parse_unary(); emit(op_pow, -1); }
  }
  void parse_primary() {
    skip();
    if (pos >= end) fail(pos, "expression expected");
    const char c = text[pos];
    if (std::isdigit((unsigned char)c) || c == '.') {
      const char* b = text.c_str() + pos;
      char* e = nullptr;
      const double v = std::strtod(b, &e);
      if (e == b) fail(pos, "bad number");
      pos += size_t(e - b);
      if (pos > end) fail(size_t(b - text.c_str()), "bad number");
      emit(op_push, 1, 0, float(v));
      return;
    }
    if (c == '(') {
      ++pos;
      parse_or();
      if (!eat(")")) fail(pos, "')' expected");
      return;
    }
    if (!is_ident_start(c)) fail(pos, std::string("unexpected '") + c + "'");
    const size_t at = pos;
    while (pos < end && is_ident(text[pos])) ++pos;
    const std::string name = text.substr(at, pos - at);
    if (peek("(")) {
      ++pos;
      if (name == "rand") {
        if (eat(")")) { emit(op_rand, 1); return; }
        parse_or();
        if (!eat(",")) fail(pos, "rand takes no arguments or two (low, high)");
        parse_or();
        if (!eat(")")) fail(pos, "')' expected");
        emit(op_rand2, -1);
        return;
      }
      for (const function_name& f : functions) {
        if (name != f.name) continue;
        parse_or();
        if (f.arity == 2) {
          if (!eat(",")) fail(pos, name + " takes two arguments");
          parse_or();
        }
        if (!eat(")")) fail(pos, "')' expected");
        emit(f.arity == 1 ? op_call1 : op_call2, f.arity == 1 ? 0 : -1, f.id);
        return;
      }
      fail(at, "unknown function '" + name + "'");
    }
    if (vars) {
      for (size_t i = vars->size(); i-- > 0;) {
        if ((*vars)[i] == name) { emit(op_var, 1, uint8_t(i)); return; }
      }
    }
    for (const lsystem_constant& k : prog.constants) {
      if (k.name == name) { emit(op_push, 1, 0, k.value); return; }
    }
    fail(at, "unknown name '" + name + "'");
  }
};

// Evaluates a constant expression at compile time (no parameters).
float eval_constant(lsystem_program& prog, int expr, size_t at) {
  rng r(1);
  float v = 0;
  if (!eval_lsystem_expr(prog, expr, nullptr, r, v)) throw parse_failure{at, "division by zero"};
  if (!std::isfinite(v)) throw parse_failure{at, "value is not finite"};
  return v;
}

// Modules of a successor or axiom: a symbol, then optionally (expr, expr, ...).
lsystem_successor parse_modules(expr_compiler& ec) {
  lsystem_successor s;
  for (;;) {
    ec.skip();
    if (ec.pos >= ec.end) break;
    const char c = ec.text[ec.pos];
    if (c == '(' || c == ')' || c == ',') ec.fail(ec.pos, std::string("unexpected '") + c + "'");
    if ((unsigned char)c >= 128) ec.fail(ec.pos, "modules are ASCII characters (write -> for an arrow, - for a minus)");
    lsystem_module_template m;
    m.symbol = uint8_t(c);
    m.first = uint32_t(ec.prog.exprs.size());
    ++ec.pos;
    if (ec.peek("(")) {
      ++ec.pos;
      int count = 0;
      for (;;) {
        ec.compile();
        ++count;
        if (ec.eat(")")) break;
        if (!ec.eat(",")) ec.fail(ec.pos, "',' or ')' expected");
      }
      if (count > 255) ec.fail(ec.pos, "too many parameters");
      m.count = uint8_t(count);
    }
    s.modules.push_back(m);
  }
  return s;
}

// Context and predecessor patterns: symbols with formal parameter names.
std::vector<lsystem_pattern> parse_patterns(const std::string& text, size_t b, size_t e, std::vector<std::string>& vars) {
  std::vector<lsystem_pattern> out;
  size_t p = b;
  while (p < e) {
    if (is_space(text[p])) { ++p; continue; }
    const char c = text[p];
    if (c == '(' || c == ')' || c == ',') throw parse_failure{p, std::string("unexpected '") + c + "'"};
    if ((unsigned char)c >= 128) throw parse_failure{p, "modules are ASCII characters"};
    lsystem_pattern m;
    m.symbol = uint8_t(c);
    ++p;
    while (p < e && is_space(text[p])) ++p;
    if (p < e && text[p] == '(') {
      ++p;
      for (;;) {
        while (p < e && is_space(text[p])) ++p;
        const size_t at = p;
        while (p < e && is_ident(text[p])) ++p;
        if (p == at || !is_ident_start(text[at])) throw parse_failure{at, "parameter name expected"};
        const std::string name = text.substr(at, p - at);
        for (const std::string& v : vars)
          if (v == name) throw parse_failure{at, "parameter '" + name + "' appears twice"};
        if (vars.size() >= 255) throw parse_failure{at, "too many parameters"};
        vars.push_back(name);
        ++m.count;
        while (p < e && is_space(text[p])) ++p;
        if (p < e && text[p] == ',') { ++p; continue; }
        if (p < e && text[p] == ')') { ++p; break; }
        throw parse_failure{p, "',' or ')' expected"};
      }
    }
    out.push_back(m);
  }
  return out;
}

// Index of the first `c` at parenthesis depth 0 in [b, e), or e.
size_t find_top(const std::string& t, size_t b, size_t e, char c) {
  int d = 0;
  for (size_t i = b; i < e; ++i) {
    if (t[i] == '(') ++d;
    else if (t[i] == ')') --d;
    else if (d == 0 && t[i] == c) return i;
  }
  return e;
}

std::string strip_spaces(const std::string& t, size_t b, size_t e) {
  std::string out;
  for (size_t i = b; i < e; ++i)
    if (!is_space(t[i])) out += t[i];
  return out;
}

void parse_production(lsystem_program& prog, const std::string& text, size_t arrow, int line) {
  size_t colon = find_top(text, 0, arrow, ':');
  const size_t lt = find_top(text, 0, colon, '<');
  const size_t gt = find_top(text, lt < colon ? lt + 1 : 0, colon, '>');
  std::vector<std::string> vars;
  lsystem_rule rule;
  if (lt < colon) rule.left = parse_patterns(text, 0, lt, vars);
  const size_t pb = lt < colon ? lt + 1 : 0, pe = gt < colon ? gt : colon;
  std::vector<lsystem_pattern> pred = parse_patterns(text, pb, pe, vars);
  if (pred.size() != 1)
    throw parse_failure{pb, pred.empty() ? "predecessor expected before '->'" : "the predecessor is one module; "
                                                                               "use '<' and '>' for context"};
  rule.pred = pred[0];
  if (gt < colon) rule.right = parse_patterns(text, gt + 1, colon, vars);
  // Left context variables come first, then the predecessor's, then the right context's: the
  // derivation binds them in this order.
  expr_compiler ec{prog, text};
  ec.vars = &vars;
  if (colon < arrow) {
    ec.pos = colon + 1;
    ec.end = arrow;
    ec.skip();
    if (ec.pos < arrow && text[ec.pos] == '*' && strip_spaces(text, ec.pos, arrow) == "*") {
      // ABOP's "no condition"
    } else {
      rule.condition = ec.compile();
      ec.skip();
      if (ec.pos != arrow) ec.fail(ec.pos, "unexpected text in the condition");
    }
  } else {
    colon = arrow;
  }
  ec.pos = arrow + 2;
  ec.end = text.size();
  int probability = -1;
  if (ec.peek("(")) {
    ++ec.pos;
    probability = ec.compile();
    if (!ec.eat(")")) ec.fail(ec.pos, "')' expected after the probability");
  }
  lsystem_successor succ = parse_modules(ec);
  succ.probability = probability;
  for (size_t i = 0; i < succ.modules.size(); ++i)
    if (succ.modules[i].symbol == rule.pred.symbol) { succ.inherit = int(i); break; }
  rule.header = strip_spaces(text, 0, arrow);
  rule.text = text;
  rule.line = line;
  // Consecutive alternatives with one header and probabilities form one stochastic production.
  if (probability >= 0 && !prog.rules.empty() && prog.rules.back().header == rule.header &&
      prog.rules.back().successors.back().probability >= 0) {
    prog.rules.back().successors.push_back(std::move(succ));
    return;
  }
  rule.successors.push_back(std::move(succ));
  if (!rule.left.empty() || !rule.right.empty()) prog.has_context = true;
  prog.rules.push_back(std::move(rule));
}

// `#define NAME expr // [min,max] help`
void parse_define(lsystem_program& prog, const std::string& text, size_t p, int line) {
  while (p < text.size() && is_space(text[p])) ++p;
  const size_t at = p;
  while (p < text.size() && is_ident(text[p])) ++p;
  if (p == at || !is_ident_start(text[at])) throw parse_failure{at, "constant name expected"};
  lsystem_constant k;
  k.name = text.substr(at, p - at);
  k.line = line;
  for (const lsystem_constant& o : prog.constants)
    if (o.name == k.name) throw parse_failure{at, "constant '" + k.name + "' is defined twice"};
  const size_t comment = text.find("//", p);
  const size_t vend = comment == std::string::npos ? text.size() : comment;
  expr_compiler ec{prog, text, p, vend};
  const int e = ec.compile();
  ec.skip();
  if (ec.pos != vend) ec.fail(ec.pos, "unexpected text after the value");
  k.value = eval_constant(prog, e, p);
  k.min = k.value > 0 ? 0 : k.value < 0 ? 2 * k.value : 0;
  k.max = k.value > 0 ? 2 * k.value : k.value < 0 ? 0 : 1;
  if (comment != std::string::npos) {
    size_t c = comment + 2;
    while (c < text.size() && is_space(text[c])) ++c;
    if (c < text.size() && text[c] == '[') {
      const char* b = text.c_str() + c + 1;
      char* e1 = nullptr;
      char* e2 = nullptr;
      const float lo = std::strtof(b, &e1);
      if (e1 != b && *e1 == ',') {
        const float hi = std::strtof(e1 + 1, &e2);
        if (e2 != e1 + 1 && *e2 == ']' && lo < hi) {
          k.min = lo;
          k.max = hi;
          c = size_t(e2 + 1 - text.c_str());
        }
      }
    }
    while (c < text.size() && is_space(text[c])) ++c;
    k.help = text.substr(c);
  }
  prog.constants.push_back(std::move(k));
}

float parse_constant_expr(lsystem_program& prog, const std::string& text, size_t& p, size_t end) {
  expr_compiler ec{prog, text, p, end};
  ec.skip();
  const size_t at = ec.pos;
  const int e = ec.compile();
  p = ec.pos;
  return eval_constant(prog, e, at);
}

void parse_directive(lsystem_program& prog, const std::string& text, size_t p, bool& have_axiom) {
  const size_t at = p;
  ++p;  // '#'
  while (p < text.size() && is_ident(text[p])) ++p;
  const std::string word = text.substr(at + 1, p - at - 1);
  const size_t n = text.size();
  auto expect_end = [&](size_t q) {
    while (q < n && is_space(text[q])) ++q;
    if (q != n) throw parse_failure{q, "unexpected text after #" + word};
  };
  if (word == "define") return;  // handled in the first pass
  if (word == "axiom") {
    if (have_axiom) throw parse_failure{at, "a second #axiom"};
    expr_compiler ec{prog, text, p, n};
    prog.axiom = parse_modules(ec);
    have_axiom = true;
  } else if (word == "angle" || word == "step" || word == "width") {
    const float v = parse_constant_expr(prog, text, p, n);
    expect_end(p);
    (word == "angle" ? prog.angle : word == "step" ? prog.step : prog.width) = v;
  } else if (word == "tropism") {
    float v[4];
    for (int i = 0; i < 4; ++i) {
      v[i] = parse_constant_expr(prog, text, p, n);
      while (p < n && is_space(text[p])) ++p;
      if (i < 3) {
        if (p >= n || text[p] != ',') throw parse_failure{p, "#tropism x, y, z, e: ',' expected"};
        ++p;
      }
    }
    expect_end(p);
    prog.tropism = glm::vec3(v[0], v[1], v[2]);
    prog.susceptibility = v[3];
  } else if (word == "ignore" || word == "draw") {
    for (; p < n; ++p) {
      if (is_space(text[p])) continue;
      (word == "ignore" ? prog.ignored : prog.draws)[(unsigned char)text[p]] = true;
    }
  } else if (word == "derivations") {
    throw parse_failure{at, "the derivation count is the 'derivations' parameter, not part of the text"};
  } else {
    throw parse_failure{at, "unknown directive '#" + word + "' (define, axiom, angle, step, width, tropism, ignore, draw)"};
  }
}

lsystem_error compile_into(const std::string& source, lsystem_program& prog) {
  prog = lsystem_program{};
  const std::vector<source_line> lines = split_lines(source);
  int line_no = 0;
  size_t first = 0;
  auto content_start = [&](const std::string& t) {
    size_t p = 0;
    while (p < t.size() && is_space(t[p])) ++p;
    return p;
  };
  try {
    // Pass 1: constants, so that productions may use constants defined below them.
    for (const source_line& l : lines) {
      ++line_no;
      const std::string text = source.substr(l.start, l.length);
      first = content_start(text);
      if (text.compare(first, 7, "#define") == 0 && (first + 7 == text.size() || is_space(text[first + 7])))
        parse_define(prog, text, first + 7, line_no);
    }
    // Pass 2: everything else.
    line_no = 0;
    bool have_axiom = false;
    for (const source_line& l : lines) {
      ++line_no;
      const std::string text = source.substr(l.start, l.length);
      first = content_start(text);
      if (first == text.size() || text.compare(first, 2, "//") == 0) continue;
      if (text[first] == '#') {
        parse_directive(prog, text, first, have_axiom);
        continue;
      }
      const size_t arrow = text.find("->", first);
      if (arrow == std::string::npos)
        throw parse_failure{first, "expected a production 'pred -> succ', a #directive or a // comment"};
      parse_production(prog, text, arrow, line_no);
    }
    if (!have_axiom) {
      line_no = 1;
      first = 0;
      throw parse_failure{0, "no #axiom line"};
    }
  } catch (const parse_failure& f) {
    return {line_no, int(f.at) + 1, f.message};
  }
  if (prog.rules.size() > 65535) return {line_no, 1, "too many productions"};
  for (size_t i = 0; i < prog.rules.size(); ++i) prog.rules_of[prog.rules[i].pred.symbol].push_back(uint16_t(i));
  return {};
}

// Shortest text that reads back as v, plain where that is no longer: 30, not %g's 3e+01.
std::string format_float(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf - 1, v);
  *r.ptr = 0;
  return buf;
}

}  // namespace

lsystem_error compile_lsystem(const std::string& source, lsystem_program& out) { return compile_into(source, out); }

lsystem_error lsystem_check(const std::string& source) {
  lsystem_program prog;
  return compile_into(source, prog);
}

std::vector<lsystem_error> lsystem_warnings(const std::string& source) {
  std::vector<lsystem_error> out;
  lsystem_program prog;
  if (!compile_into(source, prog).ok()) return out;
  // Symbols that occur in the axiom or a successor, and those that have a production.
  std::array<bool, 256> occurs{}, produced{};
  for (const lsystem_module_template& m : prog.axiom.modules) occurs[m.symbol] = true;
  for (const lsystem_rule& r : prog.rules) {
    produced[r.pred.symbol] = true;
    for (const lsystem_successor& s : r.successors)
      for (const lsystem_module_template& m : s.modules) occurs[m.symbol] = true;
  }
  auto turtle = [&](unsigned char c) {
    return c == 'F' || c == 'f' || c == '+' || c == '-' || c == '&' || c == '^' || c == '/' || c == '\\' ||
           c == '|' || c == '[' || c == ']' || c == '!' || c == '$' || c == 'L' || c == '\'' || prog.draws[c];
  };
  int line_no = 0;
  for (const source_line& l : split_lines(source)) {
    ++line_no;
    std::string text = source.substr(l.start, l.length);
    size_t first = 0;
    while (first < text.size() && is_space(text[first])) ++first;
    if (first == text.size() || text.compare(first, 2, "//") == 0) continue;
    // The module text: after "#axiom", or after "->" (with a stochastic "(p)" before it or not).
    size_t b = std::string::npos;
    size_t pred_at = std::string::npos;
    if (text.compare(first, 6, "#axiom") == 0) {
      b = first + 6;
    } else if (text[first] != '#') {
      const size_t arrow = text.find("->", first);
      if (arrow == std::string::npos) continue;
      b = arrow + 2;
      // The predecessor: the symbol before '>' (context) or the first symbol, before ':' or '('.
      const size_t head = find_top(text, first, arrow, ':');   // a condition may hold '<' and '>'
      const size_t lt = find_top(text, first, head, '<');
      // left < pred > right, left < pred, pred > right or pred.
      size_t p = lt < head ? lt + 1 : first;
      while (p < head && is_space(text[p])) ++p;
      pred_at = p;
    } else {
      continue;
    }
    size_t e = text.find("//", b);
    if (e == std::string::npos) e = text.size();
    if (pred_at != std::string::npos) {
      const unsigned char c = static_cast<unsigned char>(text[pred_at]);
      if (!occurs[c])
        out.push_back({line_no, int(pred_at) + 1,
                       std::string("production for '") + char(c) + "' never applies: '" + char(c) +
                           "' occurs in neither the axiom nor any successor"});
    }
    // Brackets at parenthesis depth 0, and modules with parameters that nothing reads.
    std::vector<size_t> open;
    int depth = 0;
    for (size_t i = b; i < e; ++i) {
      const char c = text[i];
      if (c == '(') { ++depth; continue; }
      if (c == ')') { --depth; continue; }
      if (depth > 0 || is_space(c)) continue;
      if (c == '[') open.push_back(i);
      else if (c == ']') {
        if (open.empty()) out.push_back({line_no, int(i) + 1, "unbalanced ']': no '[' before it (the turtle ignores it)"});
        else open.pop_back();
      }
      size_t j = i + 1;
      while (j < e && is_space(text[j])) ++j;
      const unsigned char u = static_cast<unsigned char>(c);
      if (j < e && text[j] == '(' && !turtle(u) && !produced[u])
        out.push_back({line_no, int(i) + 1,
                       std::string("module '") + c + "' has parameters but no production and no turtle meaning: they do nothing"});
    }
    for (size_t i : open) out.push_back({line_no, int(i) + 1, "unbalanced '[': never closed with ']' on this line"});
  }
  return out;
}

std::vector<lsystem_constant> lsystem_constants(const std::string& source) {
  lsystem_program prog;
  compile_into(source, prog);  // the constants pass runs first, so they survive later errors
  return prog.constants;
}

bool set_lsystem_constant(std::string& source, const std::string& name, float value) {
  for (const source_line& l : split_lines(source)) {
    const std::string_view t(source.data() + l.start, l.length);
    size_t p = 0;
    while (p < t.size() && is_space(t[p])) ++p;
    if (t.substr(p, 7) != "#define") continue;
    p += 7;
    const size_t before = p;
    while (p < t.size() && is_space(t[p])) ++p;
    if (p == before) continue;
    const size_t nb = p;
    while (p < t.size() && is_ident(t[p])) ++p;
    if (t.substr(nb, p - nb) != name) continue;
    const size_t comment = t.find("//", p);
    size_t vend = comment == std::string_view::npos ? t.size() : comment;
    while (vend > p && is_space(t[vend - 1])) --vend;
    std::string repl(1, ' ');
    repl += format_float(value);
    source.replace(l.start + p, vend - p, repl);
    return true;
  }
  return false;
}

std::string format_lsystem_string(const lsystem_string& s, long first_n) {
  std::string out;
  const size_t n = first_n < 0 ? s.modules.size() : std::min(s.modules.size(), size_t(first_n));
  for (size_t i = 0; i < n; ++i) {
    const lsystem_module& m = s.modules[i];
    out += char(m.symbol);
    if (m.count == 0) continue;
    out += '(';
    for (int k = 0; k < m.count; ++k) {
      if (k) out += ',';
      out += format_float(s.params[m.param + size_t(k)]);
    }
    out += ')';
  }
  return out;
}

lsystem_inspection inspect_lsystem(const std::string& source, int derivations, long first_n, uint64_t seed,
                                   int64_t module_cap) {
  lsystem_inspection out;
  lsystem_program prog;
  out.error = compile_into(source, prog);
  if (!out.error.ok()) return out;
  lsystem_derive_report rep;
  const lsystem_string s = derive_lsystem(prog, derivations, seed, module_cap, {}, rep);
  out.module_counts = rep.module_counts;
  out.first_modules = format_lsystem_string(s, first_n);
  out.message = rep.message;
  return out;
}

}  // namespace sylva
