// The coupling accelerations by name (DESIGN.md 5.3): "aitken" (the seed paper's rule, omega0 =
// omega), "iqn-ils" (omega0 = omega for the first iteration) or "constant" (omega), as fin-fsi's
// --acceleration flag names them.
#pragma once

#include <memory>
#include <string>

#include "fsi/acceleration.hpp"
#include "fsi/coupling_data.hpp"

namespace finverse::fsi {

// Throws finverse::Error naming the expected names.
std::unique_ptr<Acceleration> make_acceleration(const std::string& name, const InterfaceLayout& layout, double omega);

}  // namespace finverse::fsi
