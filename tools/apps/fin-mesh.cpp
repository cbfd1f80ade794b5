// fin-mesh: structural and immersed-boundary meshes of the fin, and the motion carried onto the
// mesh nodes (DESIGN.md sections 1 and 4; seed paper section 4.1, Fig. 9).
//
//   fin-mesh --mesh results/c/mesh.h5 --vtu results/c/mesh.vtu
//            --motion-source results/c/truth.h5 --motion results/c/motion.h5 --motion-pvd results/c/motion.pvd
//
// The motion source is kinematics.h5 from fin-track. Until fin-track lands, truth.h5 from
// fin-synth is accepted as well (same template/points, template/triangles, time, points layout),
// so the downstream stages can run on the virtual experiment's truth motion.
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/log.hpp"
#include "core/output_paths.hpp"
#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "core/vtk_output.hpp"
#include "mesh/ibm_surface.hpp"
#include "mesh/motion_transfer.hpp"
#include "mesh/planform_mesher.hpp"
#include "mesh/structural_mesh.hpp"
#include "mesh/template_options.hpp"

namespace fs = std::filesystem;
using namespace finverse;

namespace {

struct SourceMotion {
  NdArray<double> rest, time, points;
  NdArray<std::int32_t> triangles;
  std::optional<double> period;
};

SourceMotion read_motion_source(const fs::path& path) {
  const auto schema = h5::File::open_read(path).attr_string(".", "schema");
  SourceMotion s;
  if (schema && *schema == stage::Kinematics::kSchema) {
    auto k = stage::read<stage::Kinematics>(path);
    s = {std::move(k.template_points), std::move(k.time), std::move(k.points), std::move(k.template_triangles), k.period};
  } else if (schema && *schema == stage::Truth::kSchema) {
    auto t = stage::read<stage::Truth>(path);
    s = {std::move(t.template_points), std::move(t.time), std::move(t.points), std::move(t.template_triangles), t.period};
  } else {
    throw Error(path.string() + ": --motion-source: schema is '" + schema.value_or("none") + "', expected " +
                stage::Kinematics::kSchema + " (or " + stage::Truth::kSchema + ")");
  }
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-mesh: mesh the fin planform (shells + ray beams), build the IBM surface, carry the motion"};
  cli::Standard standard(app, "fin-mesh");
  mesh::TemplateOptions tmpl;
  mesh::add_template_options(app, tmpl);
  mesh::PlanformMeshOptions mo;
  double ibm_thickness = 0.05, root_band = 0.0, max_source_distance = 0.01;
  fs::path mesh_out, vtu, motion_source, motion_out, motion_pvd, summary_out;
  app.add_option("--mesh", mesh_out, "output mesh.h5")->required()->check(cli::writable_output());
  app.add_option("--vtu", vtu, "output ParaView mesh (.vtu); the IBM surface goes to <stem>_ibm.pvd");
  app.add_option("--max-edge", mo.max_edge_over_chord, "largest element edge / c")->capture_default_str();
  app.add_option("--min-angle", mo.min_angle_deg, "smallest element angle (degrees)")->capture_default_str();
  app.add_option("--ibm-thickness", ibm_thickness, "thickness of the closed IBM body / c (a few CFD cells)")->capture_default_str();
  app.add_option("--root-band", root_band, "prescribed root nodes lie within this distance of the root / c")->capture_default_str();
  auto* src = app.add_option("--motion-source", motion_source, "kinematics.h5 (or truth.h5 until fin-track lands)")->check(CLI::ExistingFile);
  app.add_option("--motion", motion_out, "output motion.h5")->needs(src)->check(cli::writable_output());
  app.add_option("--motion-pvd", motion_pvd, "output ParaView motion series (.pvd)")->needs(src);
  app.add_option("--max-source-distance", max_source_distance,
                 "largest allowed distance of a mesh node from the motion source's rest surface / c")->capture_default_str();

  app.add_option("--summary", summary_out, "also write a validation summary.json of the mesh quality");

  return cli::run(app, standard, argc, argv, [&] {
    if (!motion_source.empty() && motion_out.empty()) throw Error("--motion: required with --motion-source");
    const auto t0 = std::chrono::steady_clock::now();
    bool summary_failed = false;
    const auto fin = mesh::make_template(tmpl);
    const double c = fin.chord;
    const auto pm = mesh::mesh_planform(fin, mo);
    std::size_t beams = 0;
    for (const auto& r : pm.ray_nodes) beams += r.size() - 1;
    log::info("planform: " + std::to_string(pm.points.size()) + " nodes, " + std::to_string(pm.triangles.size()) +
              " shell triangles, " + std::to_string(beams) + " beam elements on " + std::to_string(pm.ray_nodes.size()) +
              " rays; smallest angle " + std::to_string(pm.min_angle_deg) + " deg (requested " +
              std::to_string(mo.min_angle_deg) + "), longest edge " + std::to_string(pm.max_edge / c) + " c");

    const auto ibm = mesh::build_ibm_surface(pm, ibm_thickness * c);
    const auto check = mesh::check_surface(ibm.points, ibm.body.triangles);
    const double expected_volume = fin.area() * ibm.body.thickness;
    log::info("IBM surface: " + std::to_string(ibm.points.size()) + " vertices, " +
              std::to_string(ibm.body.triangles.size()) + " triangles, closed " + (check.closed ? "yes" : "NO") +
              ", self-intersecting " + (check.self_intersecting ? "YES" : "no") + ", outward " +
              (check.outward ? "yes" : "NO") + ", volume / (area t) " + std::to_string(check.volume / expected_volume));
    if (!check.closed || check.self_intersecting || !check.outward)
      throw Error("fin-mesh: the IBM surface is not a closed, outward-oriented surface free of self-intersections");

    auto m = mesh::assemble_mesh(fin, pm, ibm, root_band * c);
    const double mesh_seconds = seconds_since(t0);
    log::info("root nodes: " + std::to_string(m.root_nodes.size()) + "; meshing took " + std::to_string(mesh_seconds) + " s");
    // The motion is carried before anything is written: a bad source must not leave a complete
    // mesh.h5 behind (issue 46).
    std::optional<stage::Motion> motion;
    if (!motion_source.empty()) {
      const auto t1 = std::chrono::steady_clock::now();
      const auto src = read_motion_source(motion_source);
      const auto binding = mesh::bind_to_surface(src.rest, src.triangles, m.points);
      log::info("motion source " + motion_source.string() + ": " + std::to_string(src.time.size()) + " frames, " +
                std::to_string(src.rest.dim(0)) + " vertices; largest node distance to its rest surface " +
                std::to_string(binding.max_distance / c) + " c");
      if (binding.max_distance > max_source_distance * c)
        throw Error(motion_source.string() + ": /template/points: the mesh lies up to " +
                    std::to_string(binding.max_distance / c) + " c from the source's rest surface (allowed " +
                    std::to_string(max_source_distance) + " c): not the same fin");
      motion.emplace();
      motion->time = src.time;
      motion->points = mesh::carry_motion(binding, src.points);
      motion->velocity = mesh::velocities(src.time.data, motion->points, src.period);
      motion->period = src.period;
      log::info("motion carried onto " + std::to_string(m.points.dim(0)) + " nodes in " +
                std::to_string(seconds_since(t1)) + " s");
    }
    if (!summary_out.empty()) {
      double area = 0;
      for (const auto& t : pm.triangles) {
        const auto &a = pm.points[t[0]], &b = pm.points[t[1]], &q = pm.points[t[2]];
        area += 0.5 * ((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]));
      }
      Summary sum("validation", "fin_mesh_quality",
                  "fin-mesh on the default trout caudal fin: element quality, beams on mesh edges, closed IBM body, speed");
      sum.at_most("min_angle_shortfall", mo.min_angle_deg - pm.min_angle_deg, 0.0,
                  "requested minimum angle minus achieved (<= 0: criterion met)", "deg");
      sum.info("min_angle", pm.min_angle_deg, "deg");
      sum.at_most("max_edge", pm.max_edge / c, mo.max_edge_over_chord, "size criterion --max-edge", "1");
      sum.relative("mesh_area", area, fin.area(), 1e-9, "template outline area (shoelace)", "m2");
      sum.absolute("ibm_closed", check.closed ? 1 : 0, 1, 0, "CGAL::is_closed");
      sum.absolute("ibm_self_intersecting", check.self_intersecting ? 1 : 0, 0, 0, "CGAL PMP does_self_intersect");
      sum.relative("ibm_volume", check.volume, expected_volume, 1e-9, "planform area x IBM thickness", "m3");
      sum.at_most("mesh_wall_time", mesh_seconds, 5.0, "issue 5: fin-mesh <= 5 s for the default fin", "s");
      sum.info("nodes", static_cast<double>(pm.points.size()));
      sum.info("shell_triangles", static_cast<double>(pm.triangles.size()));
      sum.info("beam_elements", static_cast<double>(beams));
      sum.info("ibm_triangles", static_cast<double>(ibm.body.triangles.size()));
      sum.parameters() = cli::effective_config(app);
      sum.set_timing(mesh_seconds, cli::threads_in_use());
      sum.write(summary_out);
      summary_failed = !sum.pass();
    }
    Provenance prov{"fin-mesh", cli::effective_config(app), {}};
    prov.config["achieved"] = {{"min_angle_deg", pm.min_angle_deg}, {"max_edge_over_chord", pm.max_edge / c}};
    if (!tmpl.file.empty()) prov.inputs.push_back(tmpl.file);
    stage::write(mesh_out, m, prov);
    if (!vtu.empty()) {
      const std::size_t nt = m.triangles.dim(0), nb = m.beam_elements.dim(0);
      NdArray<double> ray({nt + nb}, 0.0), thick({nt + nb}), width({nt + nb}, 0.0);
      for (std::size_t i = 0; i < nt; ++i) thick(i) = m.shell_thickness(i);
      for (std::size_t b = 0; b < nb; ++b) {
        ray(nt + b) = m.beam_ray(b);
        thick(nt + b) = 0.5 * (m.beam_thickness(b, 0) + m.beam_thickness(b, 1));
        width(nt + b) = 0.5 * (m.beam_width(b, 0) + m.beam_width(b, 1));
      }
      NdArray<double> root({m.points.dim(0)}, 0.0);
      for (auto r : m.root_nodes.data) root(r) = 1;
      vtkio::write_unstructured(vtu, m.points, m.triangles, m.beam_elements, {{"root", root}},
                                {{"ray", ray}, {"thickness", thick}, {"width", width}});
      auto ibm_pvd = vtu;
      ibm_pvd.replace_filename(vtu.stem().string() + "_ibm.pvd");
      vtkio::SurfaceFrame f{m.ibm_points, {}, {}};
      vtkio::write_surface_series(ibm_pvd, {0.0}, m.ibm_triangles, {f});
    }

    if (motion) {
      // mesh_out among the inputs: readers of both check that this motion is on that mesh.
      Provenance mprov{"fin-mesh", prov.config, {motion_source, mesh_out}};
      stage::write(motion_out, *motion, mprov);
      if (!motion_pvd.empty()) {
        const std::size_t nf = motion->time.size(), nv = m.points.dim(0);
        std::vector<vtkio::SurfaceFrame> frames(nf);
        for (std::size_t k = 0; k < nf; ++k) {
          frames[k].points = NdArray<double>({nv, 3});
          std::copy_n(motion->points.data.begin() + k * nv * 3, nv * 3, frames[k].points.data.begin());
          NdArray<double> vel({nv, 3});
          std::copy_n(motion->velocity.data.begin() + k * nv * 3, nv * 3, vel.data.begin());
          frames[k].point_data.push_back({"velocity", std::move(vel)});
        }
        vtkio::write_surface_series(motion_pvd, motion->time.data, m.triangles, frames);
      }
    }
    if (summary_failed) log::error("a validation metric failed: see " + summary_out.string());
    return summary_failed ? kExitDifferent : kExitOk;  // README: exit 1 when a metric failed
  });
}
