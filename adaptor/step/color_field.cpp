#include "adaptor/step/color_field.hpp"

#include <span>

namespace tetray {
namespace {

template <typename T>
std::span<const T> values_of(const FieldView& field) {
  return {static_cast<const T*>(field.values), field.count};
}

}  // namespace

render::ValueRange local_field_range(const FieldView& field) {
  if (field.type == ScalarType::float32) return render::local_range(values_of<float>(field));
  return render::local_range(values_of<double>(field));
}

void usable_color_range(render::ValueRange& range) {
  if (range.empty()) range = {0, 1};
  // A constant field maps to the low end of the colormap instead of dividing by zero.
  if (range.hi <= range.lo) range.hi = range.lo + 1;
}

}  // namespace tetray
