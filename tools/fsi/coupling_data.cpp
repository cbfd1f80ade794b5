// Checks and stacking of the coupled interface vector z = [X; V] (coupling_data.hpp).
#include "fsi/coupling_data.hpp"

#include <string>

#include "core/error.hpp"

namespace finverse::fsi {

void InterfaceLayout::validate() const {
  if (n_position <= 0) {
    throw Error("fsi interface layout: expected a positive number of displacement entries, got " +
                std::to_string(n_position));
  }
  if (n_velocity != 0 && n_velocity != n_position) {
    throw Error("fsi interface layout: expected 0 or " + std::to_string(n_position) +
                " velocity entries (one per displacement entry), got " + std::to_string(n_velocity));
  }
}

void InterfaceLayout::check(const Eigen::VectorXd& z, const char* what) const {
  if (z.size() != size()) {
    throw Error(std::string("fsi ") + what + ": expected an interface vector of size " +
                std::to_string(size()) + ", got " + std::to_string(z.size()));
  }
  if (!z.allFinite()) {
    throw Error(std::string("fsi ") + what + ": expected finite interface values, got NaN or inf");
  }
}

Eigen::VectorXd InterfaceLayout::stack(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
  if (x.size() != n_position || v.size() != n_velocity) {
    throw Error("fsi interface layout: expected displacement and velocity blocks of sizes " +
                std::to_string(n_position) + " and " + std::to_string(n_velocity) + ", got " +
                std::to_string(x.size()) + " and " + std::to_string(v.size()));
  }
  Eigen::VectorXd z(size());
  z << x, v;
  return z;
}

}  // namespace finverse::fsi
