#include "moreau/constraints/particle_families.hpp"

#include <algorithm>

namespace moreau {

std::vector<std::string_view> constraint_error_names() {
  std::vector<std::string_view> names{"all"};
  const ParticleFamilies families;
  for_each_family(families, [&](const auto& family, int) {
    if (std::find(names.begin(), names.end(), family.kErrorName) == names.end()) names.push_back(family.kErrorName);
  });
  return names;
}

}  // namespace moreau
