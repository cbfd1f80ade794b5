// The contracts of the stage files of DESIGN.md section 4, written down once. Readers and
// writers in stage_files.hpp check against these; CONTRACTS.md is rendered from them.
// A change of meaning or shape of an existing dataset bumps the schema version.
#include "core/contract.hpp"

namespace finverse::contract {
namespace {

using h5::DType;
constexpr auto f64 = DType::f64;
constexpr auto i32 = DType::i32;
constexpr auto i64 = DType::i64;
constexpr auto u8 = DType::u8;
constexpr auto str = DType::str;

DatasetSpec opt(DatasetSpec d) {
  d.required = false;
  return d;
}
// Indices into the rows of the dim `symbol` (e.g. node numbers < nv).
DatasetSpec indexes(DatasetSpec d, const std::string& symbol) {
  d.index_of = symbol;
  return d;
}
DatasetSpec may_be_nan(DatasetSpec d) {
  d.finite = false;
  return d;
}

AttributeSpec effects_attr() {
  return {"effects", "", "JSON array of the candidate effects (fem/effects) the structure ran with; absent: none",
          false, true};
}
AttributeSpec period_attr() { return {"T", "s", "period of periodic data; absent when not periodic"}; }
std::vector<AttributeSpec> flow_attrs() {
  return {{"rho", "kg m-3", "fluid density used for the coefficients", true},
          {"U", "m s-1", "reference (free-stream) speed", true},
          {"reference_area", "m2", "area that normalises the force coefficients", true},
          period_attr()};
}
std::vector<DatasetSpec> force_datasets(const std::string& nt) {
  return {
      {"nodal_force", f64, {nt, "nv", "3"}, "N", "net hydrodynamic force on each mid-surface node (both sides)"},
      {"force_total", f64, {nt, "3"}, "N", "total hydrodynamic force on the fin; thrust is -x"},
      {"coefficients/thrust", f64, {nt}, "1", "C_T = -F_x / (0.5 rho U^2 A)"},
      {"coefficients/lateral", f64, {nt}, "1", "C_Y = F_y / (0.5 rho U^2 A)"},
      {"coefficients/vertical", f64, {nt}, "1", "C_Z = F_z / (0.5 rho U^2 A)"},
  };
}

std::vector<FileSpec> build() {
  std::vector<FileSpec> specs;

  specs.push_back(
      {"finverse/truth",
       1,
       "truth.h5",
       "fin-synth",
       "The virtual experiment's ground truth, for scoring only: the motion of the truth fin, "
       "its materials and the effects it contains.",
       {
           {"template/points", f64, {"nv", "3"}, "m", "truth surface vertices at rest"},
           indexes({"template/triangles", i32, {"ntri", "3"}, "", "truth surface triangles (0-based)"}, "nv"),
           {"time", f64, {"nf"}, "s", "frame times"},
           {"points", f64, {"nf", "nv", "3"}, "m", "truth vertex positions per frame"},
           {"materials/names",
            str,
            {"np"},
            "",
            "material parameter names, e.g. E_membrane, E_ray1, nu (fin-fit's names)"},
           {"materials/units", str, {"np"}, "", "unit of each parameter"},
           {"materials/values", f64, {"np"}, "", "truth values in the units of materials/units"},
           // Optional, added with the FSI truth (issue 33): the root drive per ray.
           opt({"root/ray_ids", i32, {"nr"}, "", "ray id of each row (1 = dorsal edge ray, mesh.h5 beams/ray)"}),
           opt({"root/eta",
                f64,
                {"nr"},
                "1",
                "place across the fin: +1 dorsal edge ray .. -1 ventral, linear in the ray index"}),
           opt({"root/heave_amplitude", f64, {"nr"}, "m", "root heave half amplitude: y = a sin(2 pi t / T + phase)"}),
           opt({"root/heave_phase", f64, {"nr"}, "rad", "root heave phase"}),
           opt({"root/pitch_amplitude", f64, {"nr"}, "rad", "root pitch amplitude about the dorsal axis z"}),
           opt({"root/pitch_phase", f64, {"nr"}, "rad", "root pitch phase relative to the heave (< 0: lags)"}),
           // Optional (issue 47): fin-synth's fish body, snout to peduncle, the 2-D mode's true midline.
           opt({"body/axis",
                f64,
                {"nf", "nb", "3"},
                "m",
                "the body's axis per frame: snout, cross-section centres, peduncle"}),
       },
       {period_attr(),
        {"effects", "",
         "JSON object of the extra effects in the truth model (structural: the fem/effects list planted by "
         "truth.effects)",
         false, true},
        {"motion_source", "", "what moved the truth: prescribed_kinematics or fsi", false, true},
        {"root_drive", "", "JSON object of the root drive parameters (drive.json of the FSI truth)", false, true}}});

  specs.push_back(
      {"finverse/kinematics",
       1,
       "kinematics.h5",
       "fin-track",
       "Reconstructed fin motion: the template driven by the fitted skeleton, per frame, with the fit "
       "quality in every view.",
       {
           {"template/points", f64, {"nv", "3"}, "m", "template surface vertices at rest"},
           indexes({"template/triangles", i32, {"ntri", "3"}, "", "template triangles (0-based)"}, "nv"),
           {"template/ray_offsets", i32, {"nr+1"}, "", "CSR offsets of each ray's vertex polyline"},
           indexes({"template/ray_vertices", i32, {"nrv"}, "", "template vertices along each ray, root to tip"}, "nv"),
           {"time", f64, {"nf"}, "s", "frame times"},
           {"points", f64, {"nf", "nv", "3"}, "m", "reconstructed vertex positions"},
           {"skeleton/joint_parent", i32, {"nj"}, "", "parent joint, -1 for the root"},
           {"skeleton/joint_rest", f64, {"nj", "3"}, "m", "joint positions in the template"},
           {"skeleton/joint_angles", f64, {"nf", "nj", "3"}, "rad", "fitted joint rotation vectors"},
           {"quality/views", str, {"nviews"}, "", "camera view names"},
           may_be_nan({"quality/silhouette_iou",
                       f64,
                       {"nf", "nviews"},
                       "1",
                       "silhouette intersection over union; NaN where the view is missing"}),
           may_be_nan({"quality/reprojection_rms",
                       f64,
                       {"nf", "nviews"},
                       "px",
                       "RMS feature reprojection error; NaN where the view is missing"}),
           {"quality/valid", u8, {"nf", "nviews"}, "", "1 where the view's frame was present and used"},
           {"quality/flags",
            u8,
            {"nf"},
            "",
            "per-frame doubts (bits): 1 fewer than two views, 2 a view's IoU low, 4 root drifted, 8 silhouette "
            "area off the template's scale, 16 segmentation unsure; absent when no frame is flagged",
            false},
       },
       {period_attr(),
        {"fps", "s-1", "camera frame rate"},
        {"fit_status", "", "why the views cannot constrain the fit (fin-track exits 1); absent when it can be trusted",
         false, true}}});

  specs.push_back(
      {"finverse/mesh",
       1,
       "mesh.h5",
       "fin-mesh",
       "Structural mesh of the fin (membrane shells, ray beams on mesh edges, root node set) and the "
       "closed thin surface the immersed-boundary solver sees.",
       {
           {"points", f64, {"nv", "3"}, "m", "mid-surface nodes at rest"},
           indexes({"triangles", i32, {"ntri", "3"}, "", "shell elements (0-based nodes)"}, "nv"),
           {"shell/thickness", f64, {"ntri"}, "m", "membrane thickness per shell element"},
           {"shell/region", i32, {"ntri"}, "", "material region of each shell element (0 = membrane)"},
           indexes({"beams/elements", i32, {"nb", "2"}, "", "beam elements on mesh edges (0-based nodes)"}, "nv"),
           {"beams/ray", i32, {"nb"}, "", "ray number of each beam element, 1 = dorsal edge"},
           {"beams/s", f64, {"nb", "2"}, "1", "arc-length fraction along the ray at both ends"},
           {"beams/thickness", f64, {"nb", "2"}, "m", "section thickness (flapping direction) at both ends"},
           {"beams/width", f64, {"nb", "2"}, "m", "section width (in the fin plane) at both ends"},
           indexes({"root_nodes", i32, {"nroot"}, "", "nodes whose motion is prescribed (the fin root)"}, "nv"),
           // Optional (issue 45): a structural mesh (a user's own FEM or test rig) has no
           // flow surface; fin-cfd and fin-fsi name the missing dataset.
           opt({"ibm/points", f64, {"nvi", "3"}, "m", "closed thin immersed-boundary surface at rest"}),
           opt(indexes({"ibm/triangles", i32, {"ntri_ibm", "3"}, "", "its triangles, outward normals"}, "nvi")),
           opt(indexes({"ibm/source_node", i32, {"nvi"}, "", "mid-surface node each surface vertex is offset from"},
                       "nv")),
           opt({"ibm/offset_sign", i32, {"nvi"}, "", "+1/-1: side of the mid-surface, 0 on the rim"}),
       },
       {{"ibm_thickness", "m", "thickness of the closed immersed-boundary body"}, {"chord", "m", "fin chord c"}}});

  specs.push_back({"finverse/motion", 1, "motion.h5", "fin-mesh",
                   "The reconstructed motion carried onto the structural mesh nodes.",
                   {
                       {"time", f64, {"nf"}, "s", "sample times"},
                       {"points", f64, {"nf", "nv", "3"}, "m", "mesh node positions"},
                       opt({"velocity", f64, {"nf", "nv", "3"}, "m s-1", "mesh node velocities"}),
                   },
                   {period_attr(), effects_attr()}});

  {
    FileSpec s{"finverse/loads", 1, "loads.h5", "fin-cfd",
               "Hydrodynamic loads on the fin under prescribed motion. Nodal forces and coefficients come from the "
               "same surface traction, so they agree.",
               {{"time", f64, {"nt"}, "s", "output times"}},
               flow_attrs()};
    for (auto& d : force_datasets("nt")) s.datasets.push_back(d);
    s.datasets.push_back({"pressure_jump", f64, {"nt", "ntri"}, "Pa",
                          "p(back) - p(front) of each shell element (front: where its right-hand normal n points); "
                          "its net pressure force is pressure_jump * area * n"});
    specs.push_back(s);
  }

  specs.push_back({"finverse/nodal_loads", 1, "nodal_loads.h5", "a user's structural load case",
                   "Nodal forces on a structure without a flow (fin-fem run --loads): point loads, a "
                   "pressure lumped to nodes, a test rig. The loads.h5 of fin-cfd is also accepted there.",
                   {
                       {"time", f64, {"nt"}, "s", "sample times (linear in between, held after the last)"},
                       {"nodal_force", f64, {"nt", "nv", "3"}, "N", "force on each mesh node"},
                   },
                   {}});

  specs.push_back(
      {"finverse/materials",
       1,
       "materials.h5",
       "fin-fit",
       "Inverse-fit result (issue 31): the parameters and their bounds, the best values, every "
       "optimiser run with its history per generation and its Levenberg-Marquardt polish, and the "
       "uncertainty at the optimum. Values are SI in the units of parameters/units; moduli are "
       "searched as log10 (parameters/scale), and standard errors are in that search scale. Wall "
       "times are not stored (same inputs, seed and threads give a byte-identical file); fin-fit "
       "writes them to its summary JSON.",
       {
           {"parameters/names", str, {"np"}, "", "parameter names, e.g. E_membrane, E_ray1, nu"},
           {"parameters/units", str, {"np"}, "", "unit of each parameter"},
           {"parameters/scale", str, {"np"}, "", "search scale: log10 or linear"},
           {"parameters/lower", f64, {"np"}, "", "lower bounds (units per parameters/units)"},
           {"parameters/upper", f64, {"np"}, "", "upper bounds"},
           opt({"parameters/truth", f64, {"np"}, "", "truth values (twin validation cases only)"}),
           {"best", f64, {"np"}, "", "best parameter values (after the polish)"},
           {"objective", f64, {}, "m", "distance objective at the best values: weighted mean point-to-point distance"},
           {"sum_of_squares", f64, {}, "m2", "least-squares objective |r|^2 at the best values"},
           {"evaluations", i64, {}, "", "FEM evaluations of all runs and polishes (cache hits not counted)"},
           {"runs/method", str, {"nruns"}, "", "optimiser of each independent run: ga or cmaes"},
           {"runs/seed", i64, {"nruns"}, "", "seed of each independent run"},
           {"runs/best", f64, {"nruns", "np"}, "", "best values of each run (before the polish)"},
           {"runs/objective", f64, {"nruns"}, "m", "final objective of each run"},
           {"runs/generations", i32, {"nruns"}, "", "generations run"},
           {"runs/converged", i32, {"nruns"}, "", "1 when the stopping rule was met before the generation cap"},
           {"runs/evaluations", i64, {"nruns"}, "", "FEM evaluations of each run"},
           may_be_nan({"runs/history",
                       f64,
                       {"nruns", "ngen"},
                       "m",
                       "best objective after each generation; NaN after a run stopped"}),
           may_be_nan({"runs/history_evaluations",
                       f64,
                       {"nruns", "ngen"},
                       "",
                       "evaluations after each generation; NaN after a run stopped"}),
           may_be_nan({"runs/history_best",
                       f64,
                       {"nruns", "ngen", "np"},
                       "",
                       "best values after each generation; NaN after a run stopped"}),
           opt({"runs/polished", f64, {"nruns", "np"}, "", "values after the polish from each run's best"}),
           opt({"runs/polished_objective", f64, {"nruns"}, "m", "objective after each polish"}),
           opt({"runs/polish_evaluations", i64, {"nruns"}, "", "evaluations of each polish"}),
           opt(may_be_nan({"uncertainty/standard_error",
                           f64,
                           {"np"},
                           "",
                           "standard error in the search scale (decades for log10); Inf when not constrained"})),
           opt(may_be_nan({"uncertainty/ci95", f64, {"np", "2"}, "", "95% interval in parameter units"})),
           opt(may_be_nan({"uncertainty/correlation", f64, {"np", "np"}, "1", "parameter correlation matrix"})),
           opt({"uncertainty/singular_values", f64, {"np"}, "m", "singular values of the weighted Jacobian dr/dz"}),
           opt(may_be_nan({"uncertainty/residual_variance", f64, {}, "m2", "s^2 = |r|^2 / (m - n); NaN when m <= n"})),
           opt({"uncertainty/identified", i32, {"np"}, "", "1: identified; 0: not (see verdict)"}),
           {"uncertainty/verdict", str, {"np"}, "", "identifiability verdict per parameter"},
       },
       {{"objective_kind", "", "dynamic (eq. 1), quasi_static (eq. 2) or static (load levels at rest)", true, true}}});

  {
    FileSpec s{"finverse/fsi", 1, "fsi.h5", "fin-fsi",
               "Fully coupled flow-structure simulation: the structure's motion, its loads and the coupling history.",
               {
                   {"time", f64, {"nt"}, "s", "output times"},
                   {"points", f64, {"nt", "nv", "3"}, "m", "mesh node positions"},
                   opt({"velocity", f64, {"nt", "nv", "3"}, "m s-1", "mesh node velocities"}),
               },
               flow_attrs()};
    s.attributes.push_back(effects_attr());
    for (auto& d : force_datasets("nt")) s.datasets.push_back(d);
    s.datasets.push_back({"coupling/iterations", i32, {"nt"}, "", "coupling iterations of each step"});
    s.datasets.push_back({"coupling/residual", f64, {"nt"}, "m", "final interface displacement change of each step"});
    // Optional, added with the first writer (fin-fsi turek_hron, issue 32); 2-D runs store z = 0
    // and forces per metre depth.
    s.datasets.push_back(opt({"coupling/relative_residual", f64, {"nt"}, "1",
                              "final |x_out - x_in| / |x_out| of the interface displacement of each step"}));
    s.datasets.push_back(opt({"reference_points", f64, {"nv", "3"}, "m", "node positions of the undeformed structure"}));
    s.datasets.push_back(opt({"probes/nodes", i32, {"np"}, "", "nodes whose displacement is tracked every step (e.g. the Turek-Hron point A)"}));
    s.datasets.push_back(opt({"probes/time", f64, {"ns"}, "s", "every coupled step's end time"}));
    s.datasets.push_back(opt({"probes/displacement", f64, {"ns", "np", "3"}, "m", "displacement of the probe nodes at every step"}));
    specs.push_back(s);
  }
  // Closing the loop (issue 34, fin-loop): the residual and its decomposition, then the trail of
  // the effect tracing.
  {
    FileSpec s{"finverse/residual", 1, "residual.h5", "fin-loop",
               "Model prediction minus reconstruction per node and frame on one mesh and time base, with its "
               "cycle mean, harmonics of the beat frequency, principal spatial modes (POD), where they sit "
               "and their phase against the root motion.",
               {
                   {"time", f64, {"nf"}, "s", "frame times"},
                   {"residual", f64, {"nf", "nv", "3"}, "m", "prediction - reconstruction"},
                   {"regions/names", str, {"nreg"}, "", "region names: root, distal, dorsal_edge, ventral_edge, middle"},
                   {"regions/node_region", i32, {"nv"}, "", "region of each node (index into regions/names)"},
                   {"root/displacement", f64, {"nf"}, "m", "root region's mean displacement along its principal direction"},
                   opt({"harmonics/mean", f64, {"nv", "3"}, "m", "cycle mean of the residual (constant term of the harmonic fit)"}),
                   opt({"harmonics/amplitude", f64, {"nk", "nv"}, "m", "amplitude of harmonic k = 1..nk of the beat frequency per node"}),
                   opt({"harmonics/phase", f64, {"nk", "nv"}, "rad", "phase of harmonic k (x = A cos(k w t + phase)) on the node's dominant axis"}),
                   {"modes/energy_fraction", f64, {"nm"}, "1", "share of the weighted residual energy of each POD mode"},
                   {"modes/shape", f64, {"nm", "nv", "3"}, "1", "spatial shape of each mode (unit area-weighted norm)"},
                   {"modes/coefficient", f64, {"nf", "nm"}, "m", "time coefficient of each mode"},
                   {"modes/region_fraction", f64, {"nm", "nreg"}, "1", "share of each mode's energy per region"},
                   {"modes/rho", f64, {"nm", "3"}, "1", "correlation of the coefficient with the root displacement, velocity, acceleration"},
                   {"modes/character", str, {"nm"}, "", "stiffness-like, damping-like, inertia-like, or stiffness- or inertia-like"},
               },
               {period_attr(),
                {"prediction_kind", "", "what the prediction is: fsi or fem", false, true},
                {"flags", "", "JSON list of reasons a part of the analysis cannot be trusted; absent when none", false, true}}};
    specs.push_back(s);
  }
  specs.push_back({"finverse/loop", 1, "loop.h5", "fin-loop",
                   "Effect tracing: per step the candidates' score statistics, the effect tried, its fitted "
                   "magnitude with a 95% interval, and the error before and after.",
                   {
                       {"candidates", str, {"nc"}, "", "candidate effects (name or name:group)"},
                       {"steps/tried", str, {"ns"}, "", "candidate refitted at each step; empty when none was significant"},
                       {"steps/accepted", i32, {"ns"}, "", "1 when BIC improved and the held-out error fell"},
                       may_be_nan({"steps/score", f64, {"ns", "nc"}, "1", "score (Lagrange-multiplier) statistic of each candidate; NaN once added"}),
                       may_be_nan({"steps/p_value", f64, {"ns", "nc"}, "1", "chi-square tail of the score; NaN once added"}),
                       may_be_nan({"steps/projected_fraction", f64, {"ns", "nc"}, "1", "share of the candidate's sensitivity off span(J); NaN once added"}),
                       {"steps/parameter_names", str, {"ns"}, "", "the tried effect's parameters, comma-separated"},
                       may_be_nan({"steps/magnitude", f64, {"ns", "2"}, "", "the tried effect's fitted parameters (NaN-padded)"}),
                       may_be_nan({"steps/lower95", f64, {"ns", "2"}, "", "lower 95% bound of each"}),
                       may_be_nan({"steps/upper95", f64, {"ns", "2"}, "", "upper 95% bound of each"}),
                       {"steps/bic_before", f64, {"ns"}, "1", "BIC on the training frames before the step"},
                       may_be_nan({"steps/bic_after", f64, {"ns"}, "1", "BIC after the refit; NaN when none was tried"}),
                       {"steps/held_out_before", f64, {"ns"}, "m", "RMS error on the held-out frames before"},
                       may_be_nan({"steps/held_out_after", f64, {"ns"}, "m", "after; NaN when none was tried"}),
                       {"steps/trailing_edge_before", f64, {"ns"}, "m", "residual RMS over the trailing edge before"},
                       may_be_nan({"steps/trailing_edge_after", f64, {"ns"}, "m", "after; NaN when none was tried"}),
                       {"parameters/names", str, {"np"}, "", "the final model's refitted parameters (base, then effects)"},
                       {"parameters/values", f64, {"np"}, "", "their values"},
                       {"held_out_frames", i32, {"nh"}, "", "frames no fit used"},
                       // The report's residual maps and before/after errors (optional: added after
                       // version 1's first files).
                       opt(may_be_nan({"steps/node_rms_after", f64, {"ns", "nv"}, "m", "per-node RMS residual over all frames after each step's refit; NaN when none was tried or the node is not compared"})),
                       opt(may_be_nan({"nodes/rms_before", f64, {"nv"}, "m", "per-node RMS residual over all frames, the refitted base before any effect; NaN where the node is not compared (root)"})),
                       opt(may_be_nan({"nodes/rms_after", f64, {"nv"}, "m", "the same after the last accepted effect (the base when none)"})),
                       opt({"errors/trailing_edge", f64, {"3"}, "m", "trailing-edge residual RMS: the fit's values, the refitted base, the final model"}),
                       opt({"errors/held_out", f64, {"3"}, "m", "held-out RMS error of the same three states"}),
                       opt({"errors/bic", f64, {"3"}, "1", "training BIC of the same three states"}),
                   },
                   {{"stop_reason", "", "why the tracing stopped", true, true},
                    {"held_out_kind", "", "last_cycle, or interleaved frames when fewer than two periods", true, true},
                    {"trailing_edge_excursion", "m", "the reconstruction's trailing-edge excursion", false, false}}});
  (void)i64;
  return specs;
}

}  // namespace

const std::vector<FileSpec>& all() {
  static const std::vector<FileSpec> specs = build();
  return specs;
}

}  // namespace finverse::contract
