// Typed readers and writers of the stage files (DESIGN.md section 4). Each struct lists its
// datasets once in fields() and its root attributes in attributes(); the generic write() and
// read() below check every dataset against the written contract (contract_specs.cpp) on the
// way out and on the way in, so a producer cannot write what its consumer would reject.
//
//   stage::Motion m;  m.time = ...; m.points = ...;
//   stage::write("results/motion.h5", m, Provenance{"fin-mesh", config, {"kinematics.h5"}});
//   auto m2 = stage::read<stage::Motion>("results/motion.h5");
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/contract.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/nd_array.hpp"
#include "core/provenance.hpp"

namespace finverse::stage {

using Strings = std::vector<std::string>;

struct Truth {
  static constexpr const char* kSchema = "finverse/truth";
  NdArray<double> template_points;
  NdArray<std::int32_t> template_triangles;
  NdArray<double> time, points;
  Strings material_names, material_units;
  NdArray<double> material_values;
  // Root kinematics per ray (optional, empty = absent; files before issue 33 have none).
  NdArray<std::int32_t> root_ray_ids;
  NdArray<double> root_eta, root_heave_amplitude, root_heave_phase, root_pitch_amplitude, root_pitch_phase;
  std::optional<double> period;
  std::optional<std::string> effects, motion_source, root_drive;
  // The fish body's axis per frame (optional: realistic footage with a body, issue 47).
  NdArray<double> body_axis;

  template <class V> void fields(V&& v) {
    v("template/points", template_points);
    v("template/triangles", template_triangles);
    v("time", time);
    v("points", points);
    v("materials/names", material_names);
    v("materials/units", material_units);
    v("materials/values", material_values);
    v("root/ray_ids", root_ray_ids);
    v("root/eta", root_eta);
    v("root/heave_amplitude", root_heave_amplitude);
    v("root/heave_phase", root_heave_phase);
    v("root/pitch_amplitude", root_pitch_amplitude);
    v("root/pitch_phase", root_pitch_phase);
    v("body/axis", body_axis);
  }
  template <class A> void attributes(A&& a) {
    a("T", period);
    a("effects", effects);
    a("motion_source", motion_source);
    a("root_drive", root_drive);
  }
};

struct Kinematics {
  static constexpr const char* kSchema = "finverse/kinematics";
  NdArray<double> template_points;
  NdArray<std::int32_t> template_triangles, ray_offsets, ray_vertices;
  NdArray<double> time, points;
  NdArray<std::int32_t> joint_parent;
  NdArray<double> joint_rest, joint_angles;
  Strings views;
  NdArray<double> silhouette_iou, reprojection_rms;
  NdArray<std::uint8_t> view_valid;
  NdArray<std::uint8_t> frame_flags;  // optional: absent when no frame is flagged
  std::optional<double> period, fps;
  std::optional<std::string> fit_status;  // absent when the fit can be trusted

  template <class V> void fields(V&& v) {
    v("template/points", template_points);
    v("template/triangles", template_triangles);
    v("template/ray_offsets", ray_offsets);
    v("template/ray_vertices", ray_vertices);
    v("time", time);
    v("points", points);
    v("skeleton/joint_parent", joint_parent);
    v("skeleton/joint_rest", joint_rest);
    v("skeleton/joint_angles", joint_angles);
    v("quality/views", views);
    v("quality/silhouette_iou", silhouette_iou);
    v("quality/reprojection_rms", reprojection_rms);
    v("quality/valid", view_valid);
    v("quality/flags", frame_flags);
  }
  template <class A> void attributes(A&& a) {
    a("T", period);
    a("fps", fps);
    a("fit_status", fit_status);
  }
};

struct Mesh {
  static constexpr const char* kSchema = "finverse/mesh";
  NdArray<double> points;
  NdArray<std::int32_t> triangles;
  NdArray<double> shell_thickness;
  NdArray<std::int32_t> shell_region;
  NdArray<std::int32_t> beam_elements, beam_ray;
  NdArray<double> beam_s, beam_thickness, beam_width;
  NdArray<std::int32_t> root_nodes;
  NdArray<double> ibm_points;
  NdArray<std::int32_t> ibm_triangles, ibm_source_node, ibm_offset_sign;
  std::optional<double> ibm_thickness, chord;

  template <class V> void fields(V&& v) {
    v("points", points);
    v("triangles", triangles);
    v("shell/thickness", shell_thickness);
    v("shell/region", shell_region);
    v("beams/elements", beam_elements);
    v("beams/ray", beam_ray);
    v("beams/s", beam_s);
    v("beams/thickness", beam_thickness);
    v("beams/width", beam_width);
    v("root_nodes", root_nodes);
    v("ibm/points", ibm_points);
    v("ibm/triangles", ibm_triangles);
    v("ibm/source_node", ibm_source_node);
    v("ibm/offset_sign", ibm_offset_sign);
  }
  template <class A> void attributes(A&& a) {
    a("ibm_thickness", ibm_thickness);
    a("chord", chord);
  }
};

struct Motion {
  static constexpr const char* kSchema = "finverse/motion";
  NdArray<double> time, points, velocity;  // velocity optional (empty = absent)
  std::optional<double> period;
  std::optional<std::string> effects;  // structural responses only (fin-fem run --effects)

  template <class V> void fields(V&& v) {
    v("time", time);
    v("points", points);
    v("velocity", velocity);
  }
  template <class A> void attributes(A&& a) {
    a("T", period);
    a("effects", effects);
  }
};

// Force histories shared by loads.h5 and fsi.h5.
struct Forces {
  NdArray<double> nodal_force, force_total, thrust, lateral, vertical;
  std::optional<double> rho, U, reference_area, period;

  template <class V> void force_fields(V&& v) {
    v("nodal_force", nodal_force);
    v("force_total", force_total);
    v("coefficients/thrust", thrust);
    v("coefficients/lateral", lateral);
    v("coefficients/vertical", vertical);
  }
  template <class A> void attributes(A&& a) {
    a("rho", rho);
    a("U", U);
    a("reference_area", reference_area);
    a("T", period);
  }
};

struct Loads : Forces {
  static constexpr const char* kSchema = "finverse/loads";
  NdArray<double> time, pressure_jump;

  template <class V> void fields(V&& v) {
    v("time", time);
    force_fields(v);
    v("pressure_jump", pressure_jump);
  }
};

// Nodal forces without a flow (structural load cases); fin-fem run reads it like loads.h5.
struct NodalLoads {
  static constexpr const char* kSchema = "finverse/nodal_loads";
  NdArray<double> time, nodal_force;

  template <class V> void fields(V&& v) {
    v("time", time);
    v("nodal_force", nodal_force);
  }
  template <class A> void attributes(A&&) {}
};

struct Fsi : Forces {
  static constexpr const char* kSchema = "finverse/fsi";
  NdArray<double> time, points, velocity;
  NdArray<std::int32_t> coupling_iterations;
  NdArray<double> coupling_residual;
  // Optional (empty = absent).
  NdArray<double> coupling_relative_residual, reference_points;
  NdArray<std::int32_t> probe_nodes;
  NdArray<double> probe_time, probe_displacement;
  std::optional<std::string> effects;  // fin-fsi fin --effects

  template <class V> void fields(V&& v) {
    v("time", time);
    v("points", points);
    v("velocity", velocity);
    force_fields(v);
    v("coupling/iterations", coupling_iterations);
    v("coupling/residual", coupling_residual);
    v("coupling/relative_residual", coupling_relative_residual);
    v("reference_points", reference_points);
    v("probes/nodes", probe_nodes);
    v("probes/time", probe_time);
    v("probes/displacement", probe_displacement);
  }
  template <class A> void attributes(A&& a) {
    Forces::attributes(a);
    a("effects", effects);
  }
};

struct Materials {
  static constexpr const char* kSchema = "finverse/materials";
  Strings names, units, scale;
  NdArray<double> lower, upper, truth, best;  // truth: optional
  NdArray<double> objective, sum_of_squares;  // scalars: shape {}, one value
  NdArray<std::int64_t> evaluations;          // scalar
  Strings run_method;
  NdArray<std::int64_t> run_seed, run_evaluations;
  NdArray<double> run_best, run_objective;
  NdArray<std::int32_t> run_generations, run_converged;
  NdArray<double> run_history, run_history_evaluations, run_history_best;
  NdArray<double> run_polished, run_polished_objective;  // optional
  NdArray<std::int64_t> run_polish_evaluations;          // optional
  NdArray<double> standard_error, ci95, correlation, singular_values, residual_variance;  // optional
  NdArray<std::int32_t> identified;  // optional
  Strings verdict;                   // always written (string lists cannot be absent)
  std::optional<std::string> objective_kind;

  template <class V> void fields(V&& v) {
    v("parameters/names", names);
    v("parameters/units", units);
    v("parameters/scale", scale);
    v("parameters/lower", lower);
    v("parameters/upper", upper);
    v("parameters/truth", truth);
    v("best", best);
    v("objective", objective);
    v("sum_of_squares", sum_of_squares);
    v("evaluations", evaluations);
    v("runs/method", run_method);
    v("runs/seed", run_seed);
    v("runs/best", run_best);
    v("runs/objective", run_objective);
    v("runs/generations", run_generations);
    v("runs/converged", run_converged);
    v("runs/evaluations", run_evaluations);
    v("runs/history", run_history);
    v("runs/history_evaluations", run_history_evaluations);
    v("runs/history_best", run_history_best);
    v("runs/polished", run_polished);
    v("runs/polished_objective", run_polished_objective);
    v("runs/polish_evaluations", run_polish_evaluations);
    v("uncertainty/standard_error", standard_error);
    v("uncertainty/ci95", ci95);
    v("uncertainty/correlation", correlation);
    v("uncertainty/singular_values", singular_values);
    v("uncertainty/residual_variance", residual_variance);
    v("uncertainty/identified", identified);
    v("uncertainty/verdict", verdict);
  }
  template <class A> void attributes(A&& a) { a("objective_kind", objective_kind); }
};

// ---------------------------------------------------------------------------------------------
namespace detail {

template <class T> constexpr h5::DType dtype_of() {
  if constexpr (std::is_same_v<T, double>) return h5::DType::f64;
  else if constexpr (std::is_same_v<T, float>) return h5::DType::f32;
  else if constexpr (std::is_same_v<T, std::int64_t>) return h5::DType::i64;
  else if constexpr (std::is_same_v<T, std::int32_t>) return h5::DType::i32;
  else if constexpr (std::is_same_v<T, std::uint8_t>) return h5::DType::u8;
  else static_assert(sizeof(T) == 0, "unsupported element type");
}

template <class T> bool absent(const NdArray<T>& a) { return a.shape.empty() && a.data.empty(); }
inline bool absent(const Strings&) { return false; }

// Checks one in-memory dataset against its contract before it is written.
template <class T>
void check_outgoing(const std::string& file, const contract::DatasetSpec& d, const NdArray<T>& a, contract::Dims& dims) {
  if (d.dtype != dtype_of<T>())
    throw Error(file + ": /" + d.path + ": internal: contract wants " + h5::to_string(d.dtype));
  if (NdArray<T>::element_count(a.shape) != a.data.size())
    throw Error(file + ": /" + d.path + ": internal: " + std::to_string(a.data.size()) + " values for shape " +
                shape_string(a.shape));
  contract::check_shape(file, d, a.shape, dims);
  if constexpr (std::is_floating_point_v<T>) {
    if (d.finite)
      for (std::size_t i = 0; i < a.data.size(); ++i)
        if (!std::isfinite(a.data[i]))
          throw Error(file + ": /" + d.path + ": refusing to write non-finite value at flat index " + std::to_string(i));
  }
}
inline void check_outgoing(const std::string& file, const contract::DatasetSpec& d, const Strings& s, contract::Dims& dims) {
  if (d.dtype != h5::DType::str) throw Error(file + ": /" + d.path + ": internal: contract wants " + h5::to_string(d.dtype));
  contract::check_shape(file, d, {s.size()}, dims);
}

template <class T> void write_one(h5::File& f, const contract::DatasetSpec& d, const NdArray<T>& a) {
  f.write(d.path, a, h5::WriteOptions{d.units, true});
}
inline void write_one(h5::File& f, const contract::DatasetSpec& d, const Strings& s) { f.write(d.path, s); }

template <class T> void read_one(const h5::File& f, const std::string& path, NdArray<T>& a) {
  if constexpr (std::is_same_v<T, double>) a = f.read_f64(path);
  else if constexpr (std::is_same_v<T, std::int64_t>) a = f.read_i64(path);
  else if constexpr (std::is_same_v<T, std::int32_t>) a = f.read_i32(path);
  else if constexpr (std::is_same_v<T, std::uint8_t>) a = f.read_u8(path);
  else static_assert(sizeof(T) == 0, "unsupported element type");
}
inline void read_one(const h5::File& f, const std::string& path, Strings& s) { s = f.read_strings(path); }

}  // namespace detail

// Writes `s` atomically to `path` after checking it against its contract.
template <class S>
void write(const std::filesystem::path& path, S& s, const Provenance& provenance) {
  const auto& spec = contract::get(S::kSchema);
  const std::string name = path.string();
  contract::Dims dims;
  // Check everything before creating the file: a rejected write leaves nothing behind.
  s.fields([&](const char* field, const auto& a) {
    const auto* d = spec.find(field);
    if (!d) throw Error(name + ": /" + std::string(field) + ": internal: not in the contract of " + spec.schema);
    if (detail::absent(a)) {
      if (d->required) throw Error(name + ": /" + d->path + ": required dataset was not set");
      return;
    }
    detail::check_outgoing(name, *d, a, dims);
  });
  auto file = h5::File::create(path);
  write_provenance(file, spec.schema, spec.version, provenance);
  s.fields([&](const char* field, const auto& a) {
    if (!detail::absent(a)) detail::write_one(file, *spec.find(field), a);
  });
  s.attributes([&](const char* key, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    const bool required = [&] {
      for (const auto& a : spec.attributes)
        if (a.name == key) return a.required;
      throw Error(name + ": root attribute '" + std::string(key) + "': internal: not in the contract");
    }();
    if (!value) {
      if (required) throw Error(name + ": required root attribute '" + std::string(key) + "' was not set");
      return;
    }
    if constexpr (std::is_same_v<V, std::optional<double>>) file.set_attr(".", key, *value);
    else file.set_attr(".", key, std::string(*value));
  });
  file.commit();
}

// Reads and checks a stage file; any violation of the contract is a one-line finverse::Error.
template <class S>
S read(const std::filesystem::path& path) {
  const auto& spec = contract::get(S::kSchema);
  const auto file = h5::File::open_read(path);
  contract::check(file, spec);
  S s;
  s.fields([&](const char* field, auto& a) {
    if (file.is_dataset(field)) detail::read_one(file, field, a);
  });
  s.attributes([&](const char* key, auto& value) {
    using V = std::decay_t<decltype(value)>;
    if (!file.has_attr(".", key)) return;
    if constexpr (std::is_same_v<V, std::optional<double>>) value = file.attr_double(".", key);
    else value = file.attr_string(".", key);
  });
  return s;
}

}  // namespace finverse::stage
