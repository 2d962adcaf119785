// Growth history shared by the generators: seasons of unequal vigour, and lower limbs that die in
// the shade of the crown above and stay as short dead stubs (docs/design/02-generators.md, §2
// "Growth history"). Both are off by default: a generator that does not ask for them keeps its bits.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/skeleton.h"

namespace sylva {

// The seeded climate anomaly z_k of growth steps 0..steps (z_0 = 0): a first-order autoregressive
// sequence z_k = ρ·z_{k−1} + √(1−ρ²)·ε_k with unit variance, ρ = 0.5 and ε_k uniform; ring-width
// indices of trees show such year-to-year persistence (Fritts 1976, Tree Rings and Climate, ch. 5).
// A generator scales step k's shoot growth by season_vigour(a, z_k).
std::vector<float> season_anomalies(uint64_t seed, int steps);
// exp(a·z): a good season (z > 0) lengthens the shoots of its step, a poor one shortens them; exactly
// 1 when a = 0.
float season_vigour(float amplitude, float anomaly);

// Natural pruning of the lower limbs (Wilson 1984, The Growing Tree, ch. 8; foresters' live crown
// ratio): a limb leaving an order-0 axis at height y dies at the first step k after its birth at
// which y < (1 − live_crown)·H(k), where H(k) is the height of the tree at step k. Its wood within
// `stub_length` metres of the axis stays as a dead stub (t.dead = k: it stands, bare of leaves); the
// rest falls at k (died = k), and what the limb would have grown from k on is removed from the tree.
// live_crown >= 1 changes nothing. Generator leaves on removed nodes go with them. Returns the old
// index of every kept node (empty when nothing changed); the caller recomputes radii and whatever
// else it keeps per node.
std::vector<int32_t> self_prune(tree_skeleton& t, float live_crown, float stub_length);
// A dead stub keeps the girth it grew, as wood does not shrink (Shigo 1985, "How tree branches are
// attached to trunks"): at `step`, each node that stands as dead wood from dead ≤ step gets at least
// the pipe radius r_tip·m^(1/n) of the m shoot tips its limb carried through it in the step before
// it died (Shinozaki 1964; the fallen wood stays in the skeleton with died = that step), and no more
// than its parent's radius. Nothing changes when t.dead is empty.
void thicken_stubs(const tree_skeleton& t, int step, float exponent, float r_tip, std::vector<float>& radius);

// Phototropism of the whole tree towards open sky (Loehle 1986, "Phototropism of whole trees:
// effects of habitat and growth form", Am. Midl. Nat. 116: 190-196): a tree with one open side (a
// forest edge, a gap) leans its shoots and its crown out towards it. open_side_direction is the
// horizontal unit vector of the open side, `azimuth` degrees from +x towards +z.
glm::vec3 open_side_direction(float azimuth_degrees);
// A shoot's direction d leaned towards the open side ô: normalize(d + ψ·ô); d itself when ψ = 0
// (or d + ψ·ô is zero).
glm::vec3 lean_to_sky(const glm::vec3& d, float lean, const glm::vec3& open);
// The open side also has more light, so more of the crown's free space lies there: the chance
// that an attraction point at normalised horizontal offset u (|u| <= 1 from the crown's axis) is
// kept, 1 − ψ·(1 − u·ô)/2 (1 on the open rim, 1 − ψ on the shaded one).
float sky_keep_chance(const glm::vec3& u, float lean, const glm::vec3& open);

}  // namespace sylva
