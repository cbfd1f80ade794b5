// loads.h5 or nodal_loads.h5, told apart by the schema (see nodal_force_file.hpp).
#include "fem/io/nodal_force_file.hpp"

#include "core/hdf5_file.hpp"

namespace finverse::fem::io {

NodalForceFile read_nodal_force_file(const std::filesystem::path& path) {
  NodalForceFile f;
  const auto schema = h5::File::open_read(path).attr_string(".", "schema");
  if (schema && *schema == stage::NodalLoads::kSchema) {
    auto nodal = stage::read<stage::NodalLoads>(path);
    f.loads.time = std::move(nodal.time);
    f.loads.nodal_force = std::move(nodal.nodal_force);
    f.structural = true;
  } else {
    f.loads = stage::read<stage::Loads>(path);
  }
  return f;
}

}  // namespace finverse::fem::io
