// L-system derivation: parallel rewriting with context, conditions and stochastic choice (ABOP ch. 1).
#include "generators/lsystem_engine.h"

namespace sylva {
namespace {

// Left context (ABOP §1.8): walking left along the path to the root, whole branches "[...]" are
// skipped, a '[' is stepped out of, and #ignore'd symbols are passed over.
bool match_left(const lsystem_program& prog, const lsystem_string& s, const std::vector<int32_t>& match, size_t i,
                const lsystem_rule& r, float* vars, int left_vars) {
  long j = long(i) - 1;
  int slot = left_vars;
  for (size_t k = r.left.size(); k-- > 0;) {
    for (;;) {
      if (j < 0) return false;
      const uint8_t sym = s.modules[size_t(j)].symbol;
      if (sym == ']') { j = long(match[size_t(j)]) - 1; continue; }
      if (sym == '[' || prog.ignored[sym]) { --j; continue; }
      break;
    }
    const lsystem_module& m = s.modules[size_t(j)];
    if (m.symbol != r.left[k].symbol || m.count != r.left[k].count) return false;
    slot -= m.count;
    for (int c = 0; c < m.count; ++c) vars[slot + c] = s.params[m.param + size_t(c)];
    --j;
  }
  return true;
}

// Right context: walking right along the same axis, lateral branches are skipped and the end of
// the current branch (']') fails the match.
bool match_right(const lsystem_program& prog, const lsystem_string& s, const std::vector<int32_t>& match, size_t i,
                 const lsystem_rule& r, float* vars, int slot) {
  size_t j = i + 1;
  const size_t n = s.modules.size();
  for (const lsystem_pattern& pat : r.right) {
    for (;;) {
      if (j >= n) return false;
      const uint8_t sym = s.modules[j].symbol;
      if (sym == '[') { j = size_t(match[j]) + 1; continue; }
      if (sym == ']') return false;
      if (prog.ignored[sym]) { ++j; continue; }
      break;
    }
    const lsystem_module& m = s.modules[j];
    if (m.symbol != pat.symbol || m.count != pat.count) return false;
    for (int c = 0; c < m.count; ++c) vars[slot + c] = s.params[m.param + size_t(c)];
    slot += m.count;
    ++j;
  }
  return true;
}

// Bracket partners; an unmatched ']' gets -1 and an unmatched '[' gets n, which both end a walk.
void match_brackets(const lsystem_string& s, std::vector<int32_t>& match) {
  const size_t n = s.modules.size();
  match.assign(n, 0);
  std::vector<int32_t> stack;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t sym = s.modules[i].symbol;
    if (sym == '[') {
      stack.push_back(int32_t(i));
      match[i] = int32_t(n);
    } else if (sym == ']') {
      if (stack.empty()) { match[i] = -1; continue; }
      match[i] = stack.back();
      match[size_t(stack.back())] = int32_t(i);
      stack.pop_back();
    }
  }
}

enum class emit_status { ok, div_zero, not_finite };

emit_status emit_successor(const lsystem_program& prog, const lsystem_successor& succ, const float* vars, rng& r,
                           uint16_t born, uint16_t inherited_born, lsystem_string& out) {
  for (size_t t = 0; t < succ.modules.size(); ++t) {
    const lsystem_module_template& m = succ.modules[t];
    out.modules.push_back({m.symbol, m.count, int(t) == succ.inherit ? inherited_born : born,
                           uint32_t(out.params.size())});
    for (int c = 0; c < m.count; ++c) {
      float v = 0;
      if (!eval_lsystem_expr(prog, int(m.first) + c, vars, r, v)) return emit_status::div_zero;
      if (!std::isfinite(v)) return emit_status::not_finite;
      out.params.push_back(v);
    }
  }
  return emit_status::ok;
}

std::string describe(emit_status s) {
  return s == emit_status::div_zero ? "division by zero" : "non-finite value (NaN or infinity)";
}

std::string where(const lsystem_rule& r, int k) {
  return " in the production at line " + std::to_string(r.line) + " \"" + r.text + "\" (derivation " +
         std::to_string(k) + ")";
}

}  // namespace

lsystem_string derive_lsystem(const lsystem_program& prog, int derivations, uint64_t seed, int64_t module_cap,
                              const grow_options& o, lsystem_derive_report& rep) {
  rep = lsystem_derive_report{};
  rng r(seed);
  lsystem_string cur, next;
  float vars[256] = {};
  const emit_status st = emit_successor(prog, prog.axiom, vars, r, 0, 0, cur);
  if (st != emit_status::ok) {
    rep.error = true;
    rep.message = describe(st) + " in the axiom";
    return {};
  }
  rep.module_counts.push_back(cur.modules.size());
  std::vector<int32_t> match;
  std::vector<float> weights;
  derivations = std::clamp(derivations, 0, int(never_died) - 1);
  for (int k = 1; k <= derivations; ++k) {
    if (o.cancelled()) { rep.cancelled = true; break; }
    if (prog.has_context) match_brackets(cur, match);
    next.modules.clear();
    next.params.clear();
    const size_t n = cur.modules.size();
    for (size_t i = 0; i < n; ++i) {
      if ((i & 0xFFFF) == 0xFFFF && o.cancelled()) { rep.cancelled = true; return cur; }
      const lsystem_module m = cur.modules[i];
      bool rewritten = false;
      for (const uint16_t ri : prog.rules_of[m.symbol]) {
        const lsystem_rule& rule = prog.rules[ri];
        if (rule.pred.count != m.count) continue;
        int left_vars = 0;
        for (const lsystem_pattern& p : rule.left) left_vars += p.count;
        for (int c = 0; c < m.count; ++c) vars[left_vars + c] = cur.params[m.param + size_t(c)];
        if (!rule.left.empty() && !match_left(prog, cur, match, i, rule, vars, left_vars)) continue;
        if (!rule.right.empty() && !match_right(prog, cur, match, i, rule, vars, left_vars + m.count)) continue;
        if (rule.condition >= 0) {
          float c = 0;
          if (!eval_lsystem_expr(prog, rule.condition, vars, r, c) || !std::isfinite(c)) {
            rep.error = true;
            rep.message = "division by zero or non-finite value in the condition" + where(rule, k);
            return cur;
          }
          if (c == 0) continue;
        }
        // Stochastic L-systems (ABOP §1.7): pick an alternative with probability ∝ its weight.
        const lsystem_successor* succ = &rule.successors[0];
        if (succ->probability >= 0) {
          weights.clear();
          float total = 0;
          for (const lsystem_successor& s : rule.successors) {
            float w = 0;
            if (!eval_lsystem_expr(prog, s.probability, vars, r, w) || !std::isfinite(w)) {
              rep.error = true;
              rep.message = "division by zero or non-finite value in a probability" + where(rule, k);
              return cur;
            }
            w = std::max(w, 0.0f);
            total += w;
            weights.push_back(total);
          }
          if (!(total > 0)) continue;
          const float x = r.uniform() * total;
          size_t pick = 0;
          while (pick + 1 < weights.size() && !(x < weights[pick])) ++pick;
          succ = &rule.successors[pick];
        }
        const emit_status es = emit_successor(prog, *succ, vars, r, uint16_t(k), m.born, next);
        if (es != emit_status::ok) {
          rep.error = true;
          rep.message = describe(es) + where(rule, k);
          return cur;
        }
        rewritten = true;
        break;
      }
      if (!rewritten) {
        next.modules.push_back({m.symbol, m.count, m.born, uint32_t(next.params.size())});
        next.params.insert(next.params.end(), cur.params.begin() + m.param, cur.params.begin() + m.param + m.count);
      }
      if (int64_t(next.modules.size()) > module_cap || next.params.size() > 0xFFFFFFF0ull) {
        rep.hit_module_cap = true;
        rep.message = "module cap reached: derivation " + std::to_string(k) + " would exceed " +
                      std::to_string(module_cap) + " modules; stopped after derivation " + std::to_string(k - 1) +
                      " (raise module_cap or lower the derivation count)";
        return cur;
      }
    }
    std::swap(cur, next);
    rep.derivations = k;
    rep.module_counts.push_back(cur.modules.size());
    if (o.progress) o.progress(0.8f * float(k) / float(derivations));
  }
  return cur;
}

}  // namespace sylva
