// Small, quick generator inputs shared by the generator tests.
#pragma once

#include <string>

#include "generators/guiding_vectors.h"
#include "generators/lsystem.h"

namespace sylva_test {

// A 3 × 4 × 3 m guiding-vectors domain with four short steps: a tree in well under a second.
inline sylva::guiding_vectors_params small_guiding_vectors() {
  sylva::guiding_vectors_params p;
  p.domain_size = {3, 4, 3};
  p.spacing = 0.25f;
  p.volume_offset = {0, 2.6f, 0};
  p.volume_outer = 1.2f;
  p.step_endpoints = {4, 10, 20, 30};
  p.step_hops = {1, 4, 3, 3};
  p.steps = 4;
  return p;
}

// An L-system in text mode from `src`, derived `n` times, at scale 1.
inline sylva::lsystem_params text_params(const std::string& src, int n) {
  sylva::lsystem_params p;
  p.mode = sylva::lsystem_mode::text;
  p.source = src;
  p.derivations = n;
  p.scale = 1;
  return p;
}

}  // namespace sylva_test
