// The coupling accelerations by name; see acceleration_factory.hpp.
#include "fsi/acceleration_factory.hpp"

#include "core/error.hpp"
#include "fsi/aitken.hpp"
#include "fsi/constant_relaxation.hpp"
#include "fsi/iqn_ils.hpp"

namespace finverse::fsi {

std::unique_ptr<Acceleration> make_acceleration(const std::string& name, const InterfaceLayout& layout,
                                                double omega) {
  if (name == "aitken") {
    AitkenOptions o;
    o.initial_omega = omega;
    return std::make_unique<AitkenRelaxation>(layout, o);
  }
  if (name == "iqn-ils") {
    IqnIlsOptions o;
    o.initial_omega = omega;
    return std::make_unique<IqnIls>(layout, o);
  }
  if (name == "constant") return std::make_unique<ConstantRelaxation>(omega);
  throw Error("fsi: acceleration '" + name + "': expected aitken, iqn-ils or constant");
}

}  // namespace finverse::fsi
