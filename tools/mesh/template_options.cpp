// Template flags shared by fin-synth and fin-mesh (seed paper section 4.1).
#include "mesh/template_options.hpp"

namespace finverse::mesh {

void add_template_options(CLI::App& app, TemplateOptions& o) {
  auto& p = o.params;
  app.add_option("--template", o.file, "fin template JSON (overrides the parametric fin below)")->check(CLI::ExistingFile);
  app.add_option("--chord", p.chord_m, "chord c (m), root to lobe tips")->capture_default_str();
  app.add_option("--height-over-chord", p.height_over_chord, "dorsal-ventral span of the trailing edge / c")->capture_default_str();
  app.add_option("--rays", p.rays, "number of fin rays (1 = dorsal edge)")->capture_default_str();
  app.add_option("--fork-depth", p.fork_depth, "depth of the trailing-edge fork / c")->capture_default_str();
  app.add_option("--root-height", p.root_height, "height of the root (peduncle) / c")->capture_default_str();
  app.add_option("--edge-ray-thickness", p.edge_root_thickness, "root thickness of the edge rays / c")->capture_default_str();
  app.add_option("--center-ray-thickness", p.center_root_thickness, "root thickness of the middle ray / c")->capture_default_str();
  app.add_option("--tip-thickness-ratio", p.tip_thickness_ratio, "ray thickness at the tip / at the root")->capture_default_str();
  app.add_option("--ray-width-ratio", p.width_over_thickness, "in-plane ray width / thickness")->capture_default_str();
  app.add_option("--membrane-thickness", p.membrane_thickness, "membrane thickness / c")->capture_default_str();
  app.add_option("--ray-points", p.points_per_ray, "polyline points per ray")->capture_default_str();
}

FinTemplate make_template(const TemplateOptions& o) {
  return o.file.empty() ? make_caudal_fin(o.params) : read_template(o.file);
}

}  // namespace finverse::mesh
