#include "render/composite/composite_plan.hpp"

#include <algorithm>
#include <functional>

namespace tetray::render {
namespace {

// Prime factors of n, all at most max_prime, or nothing when n has a larger one.
std::vector<int> small_prime_factors(int n, int max_prime) {
  std::vector<int> primes;
  for (int p = 2; p <= max_prime; ++p) {
    while (n % p == 0) {
      primes.push_back(p);
      n /= p;
    }
  }
  if (n != 1) primes.clear();
  return primes;
}

// Packs prime factors into radices of at most kMaxRadix, first fit decreasing: fewer rounds,
// each with a handful of partners.
std::vector<int> pack_radices(std::vector<int> primes) {
  std::sort(primes.begin(), primes.end(), std::greater<>());
  std::vector<int> radices;
  for (int p : primes) {
    auto fit =
        std::find_if(radices.begin(), radices.end(), [&](int k) { return k * p <= kMaxRadix; });
    if (fit == radices.end()) {
      radices.push_back(p);
    } else {
      *fit *= p;
    }
  }
  return radices;
}

CompositePlan binary_swap_plan(int rank_count) {
  CompositePlan plan{rank_count, 1, {}};
  while (plan.swap_count * 2 <= rank_count) {
    plan.swap_count *= 2;
    plan.radices.push_back(2);
  }
  return plan;
}

CompositePlan radix_k_plan(int rank_count) {
  int swap_count = rank_count;
  std::vector<int> primes = small_prime_factors(swap_count, kMaxPrimeRadix);
  while (swap_count > 1 && primes.empty()) {
    primes = small_prime_factors(--swap_count, kMaxPrimeRadix);
  }
  return {rank_count, swap_count, pack_radices(primes)};
}

}  // namespace

CompositePlan make_plan(int rank_count, CompositeAlgorithm algorithm) {
  switch (algorithm) {
    case CompositeAlgorithm::gather:
      return {rank_count, rank_count, {}};
    case CompositeAlgorithm::binary_swap:
      return binary_swap_plan(rank_count);
    case CompositeAlgorithm::radix_k:
      return radix_k_plan(rank_count);
    case CompositeAlgorithm::automatic:
      break;
  }
  // Radix-k with the largest radices for every count: fewer rounds on the critical path, in
  // the swap and in the assembly that takes them back, and the same bytes as binary swap. It
  // is the faster of the two at every rank count, image size and coverage of the simulated
  // sweep (docs/scaling.md).
  return radix_k_plan(rank_count);
}

bool interlace_rows(CompositeRows rows, int tallest_active_rows, int height) {
  switch (rows) {
    case CompositeRows::natural:
      return false;
    case CompositeRows::interlaced:
      return true;
    case CompositeRows::automatic:
      break;
  }
  return tallest_active_rows <= kInterlaceBelow * height;
}

RoundPosition round_position(const CompositePlan& plan, int round, int virtual_rank) {
  int stride = 1;
  for (int r = 0; r < round; ++r) stride *= plan.radices[static_cast<std::size_t>(r)];
  return {(virtual_rank / stride) % plan.radices[static_cast<std::size_t>(round)], stride};
}

}  // namespace tetray::render
