// A fluid's "interfacial_tension": {"<other fluid>": sigma (N/m), ...} gives the interface between
// two liquids of the scene a tension of its own (interfacial_tension.hpp). Read once every object
// is added, since a fluid may name one that comes after it.
#include <fmt/format.h>

#include "moreau/fluids/surface_tension.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

void add_fluid_interfaces(const std::vector<ObjectSpec>& objects, Model& model,
                          const std::function<SpecPlace(Index object)>& object_place) {
  FluidModel& fm = model.fluid;
  std::vector<std::pair<Index, Index>> given;  // the phase pairs named so far, with any tension
  for (size_t k = 0; k < objects.size(); ++k) {
    const auto* spec = std::get_if<FluidSpec>(&objects[k]);
    if (!spec) continue;
    const SpecPlace place = object_place(static_cast<Index>(k)).at("interfacial_tension");
    const Index own = model.objects[k].fluid_phase;
    for (const FluidInterfaceSpec& entry : spec->interfacial_tension) {
      const Index other_object = model.find_object(entry.fluid);
      if (other_object < 0 || model.objects[other_object].kind != ObjectKind::fluid) {
        std::string fluids;
        for (const ObjectInfo& o : model.objects)
          if (o.kind == ObjectKind::fluid && o.name != spec->name) fluids += fmt::format("{}'{}'", fluids.empty() ? "" : ", ", o.name);
        place.fail(entry.fluid, fmt::format("{} '{}'; the keys name the other fluids of the scene{}",
                                            other_object < 0 ? "there is no object" : "it is not a fluid:", entry.fluid,
                                            fluids.empty() ? " (it has no other)" : ": " + fluids));
      }
      const Index other = model.objects[other_object].fluid_phase;
      if (other == own) place.fail(entry.fluid, "a fluid has no interface with itself; name another fluid");
      const Real tension = place.number(entry.fluid, entry.tension, Range::non_negative());
      const FluidPhase &a = fm.phases[own], &b = fm.phases[other];
      if (a.gas || b.gas)
        place.fail(entry.fluid, "an interfacial tension acts between two liquids; a \"gas\" in open air has none");
      for (const auto& [p, q] : given)
        if ((p == other && q == own) || (p == own && q == other))
          place.fail(entry.fluid, fmt::format("the fluid '{}' already gives this interface a tension; give it once", entry.fluid));
      // Brackbill et al.'s (1992) capillary limit with the two liquids' mean density.
      const Real spacing = 2 * fm.particle_radius;
      const Real limit = capillary_time_step(0.5 * (a.rest_density + b.rest_density), spacing, tension);
      if (tension > 0 && model.settings.dt > limit)
        place.fail(entry.fluid,
                   fmt::format("interfacial tension {} N/m needs dt <= sqrt(rho (2r)^3 / (2 pi sigma)) = {:.3g} s (rho the "
                               "two liquids' mean density) to resolve the capillary waves on the particle spacing 2r = "
                               "{} m; settings.dt is {} s: lower dt or the tension, or use larger particles",
                               tension, limit, spacing, model.settings.dt));
      given.emplace_back(own, other);
      if (tension > 0) fm.interfaces.push_back({own, other, tension});
    }
  }
}

}  // namespace moreau
