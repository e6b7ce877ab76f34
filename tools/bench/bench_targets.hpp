// The targets, checked against one scene's figures with 2 threads, of two kinds: the fixed ones
// (trace rate, builds, BVH memory, agreement with the reference, refit against its memory bound,
// the rebuild policy), defined on the 1M-tet scene (n = 56); and those against the honest
// reference (Embree's coherent packets, tetray's default packets), defined per size on n = 56, 88
// and 133 (1M, 4M and 14M tets). The bench reports them for every scene, those of the nearest
// defined size where a scene has none of its own, and never fails because of them.
#pragma once

#include <string>
#include <vector>

#include <json/json.h>

#include "bench_results.hpp"

namespace tetray::bench {

// The scene the fixed targets are defined on.
inline constexpr int kFixedTargetScene = 56;

// The targets against the reference of one size.
struct ReferenceTargets {
  int n;
  double trace_vs_embree;  // exact trace / Embree trace of the extracted triangles, at most
  double step_speedup;     // reference step / in-situ step, at least
};
inline constexpr ReferenceTargets kReferenceTargets[] = {{56, 0.5, 6}, {88, 0.7, 8}, {133, 1.0, 8}};

// Those of size n, or of the nearest defined size.
const ReferenceTargets& reference_targets(int n);

struct TargetCheck {
  std::string name;
  std::string measured;
  std::string target;
  bool pass = false;
};

std::vector<TargetCheck> check_targets(const SceneFigures& figures);

// One row of the table ("name  measured  target  PASS|MISS"), and its JSON object.
void print_target(const TargetCheck& check);
Json::Value target_json(const TargetCheck& check);

// The in-situ budget of each modality against the plain frame of the same run: a shadowing point
// light, four transparent layers (against the same surfaces opaque), the smooth step with its
// gradients (against the flat step) and a clip cap. Part of check_targets.
std::vector<TargetCheck> check_modality_targets(const ShadingFigures& shading,
                                                const LayerFigures& layers, const CapFigures& cap);

}  // namespace tetray::bench
