#include "moreau/constraints/particle_families.hpp"

#include <algorithm>

namespace moreau {

std::vector<std::string_view> constraint_error_names() {
  std::vector<std::string_view> names{"all"};
  [&]<size_t... I>(std::index_sequence<I...>) {
    for (std::string_view name : {std::tuple_element_t<I, ParticleFamilies>::kErrorName...})
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }(std::make_index_sequence<kParticleFamilyCount>{});
  return names;
}

}  // namespace moreau
