// The flap's 3-D flow load near the root, linear in the tip (flap_flow_load.hpp).
#include "loop/flap_flow_load.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/hdf5_file.hpp"
#include "loop/errors.hpp"

namespace finverse::loop {

FlapFlowLoad read_flap_flow_load(const std::filesystem::path& path, double window) {
  const std::string where = path.string();
  if (!std::filesystem::exists(path)) throw InvalidInput(where + ": not found (fin-fsi flap --loads)");
  FlapFlowLoad f;
  f.source = path;
  try {
    auto file = h5::File::open_read(path);
    if (file.attr_string(".", "schema").value_or("") != "finverse/flap-loads")
      throw InvalidInput(where + ": expected schema finverse/flap-loads (fin-fsi flap --loads)");
    const auto tips = file.read_f64("tip_held");
    const auto loads = file.read_f64("nodal_load");
    f.tip0 = file.attr_double(".", "tip_at_root_m").value_or(NAN);
    f.viscosity_factor = file.attr_double(".", "viscosity_factor").value_or(1);
    f.inflow_factor = file.attr_double(".", "inflow_factor").value_or(1);
    f.youngs_modulus = file.attr_double(".", "youngs_modulus_pa").value_or(0);
    f.h = file.attr_double(".", "h_m").value_or(0);
    f.along = static_cast<int>(file.attr_int(".", "flap_along").value_or(0));
    f.across = static_cast<int>(file.attr_int(".", "flap_across").value_or(0));
    const std::size_t m = tips.data.size();
    if (loads.shape.size() != 2 || loads.shape[0] != m || m < 2 || !std::isfinite(f.tip0))
      throw InvalidInput(where + ": expected tip_held (m) and nodal_load (m x 3 nodes) for m >= 2 evaluations and "
                                 "the attribute tip_at_root_m");
    const std::size_t n = loads.shape[1];
    if (n != 3 * static_cast<std::size_t>((f.along + 1) * (f.across + 1)))
      throw InvalidInput(where + ": nodal_load has " + std::to_string(n) + " columns for a " +
                         std::to_string(f.along) + " x " + std::to_string(f.across) + " strip");
    // The evaluations within the window of the root, or the two nearest.
    std::vector<std::size_t> order(m);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) {
      return std::abs(tips(a) - f.tip0) < std::abs(tips(b) - f.tip0);
    });
    std::size_t used = 2;
    while (used < m && std::abs(tips(order[used]) - f.tip0) <= window) ++used;
    double tm = 0;
    for (std::size_t k = 0; k < used; ++k) tm += tips(order[k]) / static_cast<double>(used);
    double stt = 0;
    for (std::size_t k = 0; k < used; ++k) stt += std::pow(tips(order[k]) - tm, 2);
    if (!(stt > 0)) throw InvalidInput(where + ": the evaluations near the root share one tip: no slope");
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n)), sxy = mean;
    for (std::size_t k = 0; k < used; ++k)
      for (std::size_t c = 0; c < n; ++c) mean[static_cast<Eigen::Index>(c)] += loads(order[k], c) / double(used);
    for (std::size_t k = 0; k < used; ++k)
      for (std::size_t c = 0; c < n; ++c)
        sxy[static_cast<Eigen::Index>(c)] +=
            (tips(order[k]) - tm) * (loads(order[k], c) - mean[static_cast<Eigen::Index>(c)]);
    f.slope = sxy / stt;
    f.load0 = mean + (f.tip0 - tm) * f.slope;
    f.evaluations_used = static_cast<int>(used);
  } catch (const InvalidInput&) {
    throw;
  } catch (const std::exception& e) {
    throw InvalidInput(where + ": " + e.what());
  }
  if (!f.load0.allFinite() || !f.slope.allFinite()) throw InvalidInput(where + ": the loads are not finite");
  return f;
}

}  // namespace finverse::loop
