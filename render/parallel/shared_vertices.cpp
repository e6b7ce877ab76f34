#include "render/parallel/shared_vertices.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>

#include "render/core/hash.hpp"

namespace tetray::render {
namespace {

constexpr std::uint32_t kUnshared = ~std::uint32_t{0};

auto tied(const PointKey& k) { return std::tie(k.x, k.y, k.z); }

int home_of(const PointKey& k, int size) {
  return static_cast<int>(position_hash(k.x, k.y, k.z) % static_cast<std::uint64_t>(size));
}

std::vector<int> offsets_of(const std::vector<int>& counts) {
  std::vector<int> offsets(counts.size(), 0);
  std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
  return offsets;
}

// An MPI type of `bytes` contiguous bytes, freed with the object.
class Bytes {
 public:
  explicit Bytes(std::size_t bytes) {
    MPI_Type_contiguous(static_cast<int>(bytes), MPI_BYTE, &type_);
    MPI_Type_commit(&type_);
  }
  ~Bytes() { MPI_Type_free(&type_); }
  Bytes(const Bytes&) = delete;
  Bytes& operator=(const Bytes&) = delete;
  MPI_Datatype type() const { return type_; }

 private:
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
};

// Per received entry (key, sender rank), its slot among the keys that several ranks hold once
// each, or kUnshared; `slots` gets their number.
std::vector<std::uint32_t> match(std::span<const PointKey> keys, std::span<const int> sender,
                                 std::size_t& slots) {
  std::vector<std::uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tuple_cat(tied(keys[a]), std::tie(sender[a])) <
           std::tuple_cat(tied(keys[b]), std::tie(sender[b]));
  });
  std::vector<std::uint32_t> slot(keys.size(), kUnshared);
  slots = 0;
  for (std::size_t first = 0, last = 0; first < order.size(); first = last) {
    bool once_each = true;
    for (last = first + 1;
         last < order.size() && tied(keys[order[last]]) == tied(keys[order[first]]); ++last) {
      once_each = once_each && sender[order[last]] != sender[order[last - 1]];
    }
    if (last - first < 2 || !once_each) continue;
    for (std::size_t i = first; i < last; ++i) slot[order[i]] = static_cast<std::uint32_t>(slots);
    ++slots;
  }
  return slot;
}

}  // namespace

int SharedVertices::build(std::span<const PointKey> keys, MPI_Comm comm) {
  comm_ = comm;
  int size = 1;
  MPI_Comm_size(comm, &size);
  // The candidates grouped by home rank, each group in the candidates' order.
  std::vector<int> home(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) home[i] = home_of(keys[i], size);
  std::vector<std::uint32_t> candidates(keys.size());
  std::iota(candidates.begin(), candidates.end(), 0u);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return home[a] < home[b]; });
  std::vector<int> send_counts(size, 0), recv_counts(size, 0);
  for (int h : home) ++send_counts[h];
  int rc = MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  if (rc != MPI_SUCCESS) return rc;
  const std::vector<int> send_offsets = offsets_of(send_counts);
  const std::vector<int> recv_offsets = offsets_of(recv_counts);
  std::vector<PointKey> sent(keys.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) sent[i] = keys[candidates[i]];
  std::vector<PointKey> received(
      static_cast<std::size_t>(recv_offsets.back() + recv_counts.back()));
  const Bytes key_type(sizeof(PointKey));
  rc = MPI_Alltoallv(sent.data(), send_counts.data(), send_offsets.data(), key_type.type(),
                     received.data(), recv_counts.data(), recv_offsets.data(), key_type.type(),
                     comm);
  if (rc != MPI_SUCCESS) return rc;
  std::vector<int> sender(received.size());
  for (int r = 0; r < size; ++r) {
    std::fill_n(sender.begin() + recv_offsets[r], recv_counts[r], r);
  }
  const std::vector<std::uint32_t> slot = match(received, sender, slots_);
  // Each sender learns which of its candidates are shared; both sides keep only those.
  std::vector<std::uint8_t> answer(received.size()), is_shared(keys.size());
  for (std::size_t i = 0; i < slot.size(); ++i) answer[i] = slot[i] != kUnshared;
  rc = MPI_Alltoallv(answer.data(), recv_counts.data(), recv_offsets.data(), MPI_UINT8_T,
                     is_shared.data(), send_counts.data(), send_offsets.data(), MPI_UINT8_T, comm);
  if (rc != MPI_SUCCESS) return rc;
  shared_.clear();
  send_counts_.assign(size, 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!is_shared[i]) continue;
    shared_.push_back(candidates[i]);
    ++send_counts_[home[candidates[i]]];
  }
  slot_.clear();
  recv_counts_.assign(size, 0);
  for (std::size_t i = 0; i < slot.size(); ++i) {
    if (slot[i] == kUnshared) continue;
    slot_.push_back(slot[i]);
    ++recv_counts_[sender[i]];
  }
  send_offsets_ = offsets_of(send_counts_);
  recv_offsets_ = offsets_of(recv_counts_);
  return MPI_SUCCESS;
}

template <typename T, typename Combine>
int SharedVertices::combine(std::span<T> values, std::size_t width, T identity, Combine op) const {
  const Bytes row(width * sizeof(T));
  std::vector<T> received(slot_.size() * width);
  int rc =
      MPI_Alltoallv(values.data(), send_counts_.data(), send_offsets_.data(), row.type(),
                    received.data(), recv_counts_.data(), recv_offsets_.data(), row.type(), comm_);
  if (rc != MPI_SUCCESS) return rc;
  std::vector<T> combined(slots_ * width, identity);
  for (std::size_t i = 0; i < slot_.size(); ++i) {
    for (std::size_t j = 0; j < width; ++j) {
      T& c = combined[slot_[i] * width + j];
      c = op(c, received[i * width + j]);
    }
  }
  for (std::size_t i = 0; i < slot_.size(); ++i) {
    std::copy_n(&combined[slot_[i] * width], width, &received[i * width]);
  }
  return MPI_Alltoallv(received.data(), recv_counts_.data(), recv_offsets_.data(), row.type(),
                       values.data(), send_counts_.data(), send_offsets_.data(), row.type(), comm_);
}

int SharedVertices::max(std::span<std::int16_t> values, std::size_t width) const {
  return combine(values, width, std::numeric_limits<std::int16_t>::min(),
                 [](std::int16_t a, std::int16_t b) { return std::max(a, b); });
}

int SharedVertices::sum(std::span<std::int32_t> values, std::size_t width) const {
  return combine(values, width, 0, [](std::int32_t a, std::int32_t b) { return a + b; });
}

// The values are exact sums (render/update/vertex_gradients.hpp): adding them never rounds.
int SharedVertices::sum(std::span<double> values, std::size_t width) const {
  return combine(values, width, 0.0, [](double a, double b) { return a + b; });
}

}  // namespace tetray::render
