// The report of one case: scores and figure data from the stage files (see fin_report.hpp).
#include "report/fin_report.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "report/fin_profiles.hpp"
#include "report/loop_section.hpp"
#include "report/force_statistics.hpp"
#include "report/modulus_scores.hpp"
#include "report/motion_distance.hpp"
#include "report/ray_sections.hpp"
#include "report/root_pitch.hpp"
#include "report/trailing_edge.hpp"
#include "report/w_shape.hpp"

namespace finverse::report {

namespace {

using nlohmann::json;
const std::string kIssue = "issue 33 scores";
const std::string kNeedsFsi = "needs fsi.h5 (the coupled run with the fitted materials; not in this case)";

std::vector<double> vec(const NdArray<double>& a) { return a.data; }

// A motion on some rest geometry: what the trailing-edge and profile measures are taken on.
struct Deforming {
  std::string label;
  const NdArray<double>* rest;
  const NdArray<double>* points;
  const NdArray<double>* time;
};

struct Measures {
  std::array<double, 3> peak_to_peak{};  // in chords
  WShape w;
  std::size_t midway = 0;
};

Measures measure(const Deforming& d, double chord, json& te_fig, json& profile_fig) {
  Measures m;
  const auto te = trailing_edge_points(*d.rest);
  json series = json::array();
  for (std::size_t p = 0; p < 3; ++p) {
    auto y = node_series(*d.points, te[p]);
    m.peak_to_peak[p] = peak_to_peak(y) / chord;
    for (double& v : y) v = (v - (*d.rest)(te[p], 1)) / chord;
    series.push_back(y);
  }
  te_fig.push_back({{"label", d.label}, {"time", vec(*d.time)}, {"points", series},
                    {"peak_to_peak_over_chord", m.peak_to_peak}});
  const auto chordwise = chordwise_line(*d.rest);
  const auto spanwise = spanwise_line(*d.rest, chord);
  json cw = json::array(), sw = json::array();
  const std::size_t nf = d.points->dim(0);
  for (std::size_t f = 0; f < nf; ++f) {
    cw.push_back(lateral_profile(*d.points, chordwise, f));
    sw.push_back(lateral_profile(*d.points, spanwise, f));
  }
  // Mid-stroke: the middle node of the spanwise line passes the middle of its range.
  m.midway = midway_frame(node_series(*d.points, spanwise.nodes[spanwise.nodes.size() / 2]));
  m.w = w_shape(spanwise.coordinate, lateral_profile(*d.points, spanwise, m.midway), chord);
  profile_fig.push_back({{"label", d.label},
                         {"chordwise_x", chordwise.coordinate},
                         {"chordwise_y", cw},
                         {"spanwise_z", spanwise.coordinate},
                         {"spanwise_y", sw},
                         {"midway_frame", m.midway},
                         {"w_shape", {{"alpha1_deg", m.w.alpha1_deg}, {"alpha2_deg", m.w.alpha2_deg},
                                      {"d1_over_chord", m.w.d1}, {"d2_over_chord", m.w.d2}}}});
  return m;
}

void force_figure(const std::string& label, const NdArray<double>& time, const stage::Forces& f, json& fig) {
  fig.push_back({{"label", label}, {"time", vec(time)}, {"C_T", vec(f.thrust)}, {"C_L", vec(f.lateral)}});
}

// Each motion's measures, where the motion is present.
struct MotionMeasures {
  std::optional<Measures> truth, kinematics, motion, fsi;
};

// Fig. 11 and scores 1-2: fitted moduli against the truth.
void modulus_section(const ReportInputs& in, Report& r) {
  auto& scores = r.scores;
  json& fig = r.figures;
  if (in.materials && !in.truth_materials.empty()) {
    const auto rows = modulus_rows(*in.materials, in.truth_materials);
    for (auto& s : modulus_scores(rows, "truth: " + in.truth_materials_source)) scores.push_back(s);
    std::map<int, double> second_moment;
    if (in.mesh) second_moment = root_second_moments(*in.mesh);
    json rays = json::array();
    for (const auto& row : rows) {
      json j{{"name", row.name}, {"E", row.fitted}, {"E_lower", row.lower}, {"E_upper", row.upper},
             {"identified", row.identified}};
      j["E_truth"] = row.truth ? json(*row.truth) : json(nullptr);
      if (row.name.rfind("E_ray", 0) == 0 && row.name != "E_rays") {
        const int id = std::stoi(row.name.substr(5));
        j["ray"] = id;
        if (auto it = second_moment.find(id); it != second_moment.end()) j["I"] = it->second;
      }
      rays.push_back(j);
    }
    fig["moduli"] = rays;
  } else {
    const std::string why = in.materials ? "no truth materials for this case" : "needs materials.h5";
    for (const char* n : {"fitted ray E vs truth, median relative error", "fitted ray E vs truth, worst identified ray"})
      scores.push_back(unavailable(n, std::string(n).find("median") != std::string::npos ? 0.05 : 0.15, kIssue, why));
    scores.push_back(unavailable("membrane E vs truth, relative error", 0.10, kIssue, why));
  }
}

// Fig. 10: the pressure jump at a quarter and three quarters of the record.
void pressure_jump_figure(const ReportInputs& in, json& fig) {
  if (in.loads && in.mesh && in.loads->pressure_jump.rank() == 2 &&
      in.loads->pressure_jump.dim(1) == in.mesh->triangles.dim(0)) {
    const auto& pj = in.loads->pressure_jump;
    json instants = json::array();
    const std::size_t nt = pj.dim(0), ntri = pj.dim(1);
    for (std::size_t f : {nt / 4, (3 * nt) / 4}) {
      std::vector<double> v(pj.data.begin() + static_cast<std::ptrdiff_t>(f * ntri),
                            pj.data.begin() + static_cast<std::ptrdiff_t>((f + 1) * ntri));
      instants.push_back({{"time", in.loads->time(f)}, {"values", v}});
    }
    fig["pressure_jump"] = {{"points", vec(in.mesh->points)}, {"triangles", in.mesh->triangles.data},
                            {"instants", instants}};
  }
}

// Fig. 12: root pitch per ray, reconstruction (and truth on the same template).
void root_pitch_figure(const ReportInputs& in, json& fig) {
  if (in.kinematics && in.kinematics->ray_offsets.size() > 1) {
    const auto& k = *in.kinematics;
    json rp{{"time", vec(k.time)}, {"reconstruction", root_pitch_deg(k.points, k.ray_offsets, k.ray_vertices)}};
    if (in.truth && in.truth->points.rank() == 3 && in.truth->points.dim(1) == k.points.dim(1))
      rp["truth"] = root_pitch_deg(in.truth->points, k.ray_offsets, k.ray_vertices), rp["truth_time"] = vec(in.truth->time);
    // The truth's root drive per ray (truth.h5 root/*, issue 33): amplitude (U) and phase (W), deg.
    if (in.truth && !in.truth->root_pitch_amplitude.data.empty()) {
      const auto& t = *in.truth;
      std::vector<double> amp, phase;
      for (double a : t.root_pitch_amplitude.data) amp.push_back(a * 180 / std::numbers::pi);
      for (double a : t.root_pitch_phase.data) phase.push_back(a * 180 / std::numbers::pi);
      rp["truth_drive"] = {{"ray_ids", t.root_ray_ids.data}, {"eta", t.root_eta.data},
                           {"pitch_amplitude_deg", amp}, {"pitch_phase_deg", phase}};
    }
    fig["root_pitch"] = rp;
  }
}

// Figs. 14 and 15: trailing-edge points and profiles of every motion present.
MotionMeasures measure_motions(const ReportInputs& in, double chord, json& fig) {
  fig["trailing_edge"] = json::array();
  fig["profiles"] = json::array();
  MotionMeasures m;
  if (in.truth)
    m.truth = measure({"truth", &in.truth->template_points, &in.truth->points, &in.truth->time}, chord,
                      fig["trailing_edge"], fig["profiles"]);
  if (in.kinematics)
    m.kinematics = measure({"reconstruction (kinematics.h5)", &in.kinematics->template_points,
                            &in.kinematics->points, &in.kinematics->time},
                           chord, fig["trailing_edge"], fig["profiles"]);
  if (in.motion && in.mesh) {
    if (in.motion->points.dim(1) != in.mesh->points.dim(0))
      throw Error("report: motion.h5 has " + std::to_string(in.motion->points.dim(1)) + " nodes, mesh.h5 " +
                  std::to_string(in.mesh->points.dim(0)));
    m.motion = measure({"reconstruction (motion.h5)", &in.mesh->points, &in.motion->points, &in.motion->time}, chord,
                       fig["trailing_edge"], fig["profiles"]);
  }
  if (in.fsi && in.mesh) {
    if (in.fsi->points.dim(1) != in.mesh->points.dim(0))
      throw Error("report: fsi.h5 has " + std::to_string(in.fsi->points.dim(1)) + " nodes, mesh.h5 " +
                  std::to_string(in.mesh->points.dim(0)));
    m.fsi = measure({"FSI (fsi.h5)", &in.mesh->points, &in.fsi->points, &in.fsi->time}, chord, fig["trailing_edge"],
                    fig["profiles"]);
  }
  return m;
}

// The trailing-edge and W-shape scores, FSI against the reconstruction.
void shape_scores(const ReportInputs& in, const MotionMeasures& m, std::vector<Score>& scores) {
  for (std::size_t p = 0; p < 3; ++p) {
    const std::string n = "trailing-edge point " + std::to_string(p + 1) + " peak-to-peak, FSI vs reconstruction";
    if (m.fsi && m.motion)
      scores.push_back(graded(n, relative_difference(m.fsi->peak_to_peak[p], m.motion->peak_to_peak[p]), 0.03, kIssue,
                              "relative difference; paper: 8 %, 5.6 %, 10 %"));
    else
      scores.push_back(unavailable(n, 0.03, kIssue, in.motion ? kNeedsFsi : "needs motion.h5 and fsi.h5"));
  }
  const std::array<std::pair<const char*, double WShape::*>, 4> w_names{
      {{"alpha1", &WShape::alpha1_deg}, {"alpha2", &WShape::alpha2_deg}, {"d1", &WShape::d1}, {"d2", &WShape::d2}}};
  for (const auto& [name, member] : w_names) {
    const std::string n = std::string("W-shape ") + name + ", FSI vs reconstruction";
    if (m.fsi && m.motion)
      scores.push_back(graded(n, relative_difference(m.fsi->w.*member, m.motion->w.*member), 0.10, kIssue,
                              "relative difference at mid-stroke"));
    else
      scores.push_back(unavailable(n, 0.10, kIssue, kNeedsFsi));
  }
}

// Fig. 16 and the thrust scores; returns the loads' statistics for the reading numbers.
std::optional<ForceStatistics> force_section(const ReportInputs& in, Report& r) {
  auto& scores = r.scores;
  json& fig = r.figures;
  fig["forces"] = json::array();
  std::optional<ForceStatistics> loads_ct, fsi_ct;
  if (in.loads && !in.loads->thrust.data.empty()) {
    loads_ct = force_statistics(vec(in.loads->time), vec(in.loads->thrust));
    force_figure("reconstruction (loads.h5)", in.loads->time, *in.loads, fig["forces"]);
  }
  if (in.fsi && !in.fsi->thrust.data.empty()) {
    fsi_ct = force_statistics(vec(in.fsi->time), vec(in.fsi->thrust));
    force_figure("FSI (fsi.h5)", in.fsi->time, *in.fsi, fig["forces"]);
  }
  if (loads_ct && fsi_ct) {
    scores.push_back(graded("mean C_T, FSI vs reconstruction", relative_difference(fsi_ct->mean, loads_ct->mean), 0.10,
                            kIssue, "paper: 0.058 vs 0.042"));
    scores.push_back(graded("C_T peak, FSI vs reconstruction", relative_difference(fsi_ct->peak, loads_ct->peak), 0.05,
                            kIssue));
  } else {
    const std::string why = loads_ct ? kNeedsFsi : "needs loads.h5 and fsi.h5";
    scores.push_back(unavailable("mean C_T, FSI vs reconstruction", 0.10, kIssue, why));
    scores.push_back(unavailable("C_T peak, FSI vs reconstruction", 0.05, kIssue, why));
  }
  return loads_ct;
}

// Motions against each other on the mesh's nodes: the truth carried onto them (motion_distance).
void distance_scores(const ReportInputs& in, double chord, std::vector<Score>& scores) {
  std::optional<NdArray<double>> truth_nodes;
  if (in.truth && in.mesh) truth_nodes = truth_on_mesh(*in.truth, *in.mesh);
  if (truth_nodes && in.motion)
    scores.push_back(info("reconstructed motion (motion.h5) vs truth, mean node distance",
                          mean_node_distance(in.motion->time, in.motion->points, in.truth->time, *truth_nodes) / chord,
                          "c", "truth carried onto the mesh's nodes"));
  if (in.fsi && in.motion)
    scores.push_back(info("FSI vs reconstructed motion, mean node distance",
                          mean_node_distance(in.fsi->time, in.fsi->points, in.motion->time, in.motion->points) / chord,
                          "c", "the reconstruction interpolated in time to the FSI's frames"));
  const std::string fsi_truth = "FSI motion vs truth motion, mean vertex distance";
  if (in.fsi && truth_nodes)
    scores.push_back(graded(fsi_truth,
                            mean_node_distance(in.fsi->time, in.fsi->points, in.truth->time, *truth_nodes) / chord,
                            0.01, kIssue, "in chords; truth carried onto the mesh's nodes", "c"));
  else
    scores.push_back(unavailable(fsi_truth, 0.01, kIssue, in.fsi ? "needs truth.h5 and mesh.h5" : kNeedsFsi));
}

// Closing the loop (issue 34): the tracer's residual maps, decision trail and errors.
void closing_the_loop(const ReportInputs& in, Report& r) {
  if (in.loop) {
    const std::string source = in.loop_source.empty() ? "loop.h5" : in.loop_source;
    if (!in.mesh) throw Error(source + ": the loop section needs mesh.h5 (--mesh) for its residual maps");
    auto section = loop_section(*in.loop, *in.mesh, source);
    r.scores.insert(r.scores.end(), section.scores.begin(), section.scores.end());
    r.figures["loop"] = std::move(section.figure);
  }
}

// The reconstruction's own numbers (and the truth's), for reading the graded ones.
void reading_scores(const std::optional<ForceStatistics>& loads_ct, const MotionMeasures& m,
                    std::vector<Score>& scores) {
  if (loads_ct) {
    scores.push_back(info("mean C_T, reconstruction (loads.h5)", loads_ct->mean, "", "paper: 0.042"));
    scores.push_back(info("C_T peak, reconstruction (loads.h5)", loads_ct->peak));
  }
  if (m.kinematics && m.truth)
    for (std::size_t p = 0; p < 3; ++p)
      scores.push_back(info("trailing-edge point " + std::to_string(p + 1) +
                                " peak-to-peak, reconstruction vs truth (relative difference)",
                            relative_difference(m.kinematics->peak_to_peak[p], m.truth->peak_to_peak[p])));
  for (const auto& [label, one] : {std::pair{"reconstruction (motion.h5)", m.motion}, std::pair{"truth", m.truth}})
    if (one) {
      for (std::size_t p = 0; p < 3; ++p)
        scores.push_back(info("trailing-edge point " + std::to_string(p + 1) + " peak-to-peak, " + label,
                              one->peak_to_peak[p], "c", p == 0 ? "paper: 1.10c, 0.90c, 1.07c (reconstruction)" : ""));
      scores.push_back(info(std::string("W-shape alpha1, ") + label, one->w.alpha1_deg, "deg", "paper: 41 deg"));
      scores.push_back(info(std::string("W-shape alpha2, ") + label, one->w.alpha2_deg, "deg", "paper: 32 deg"));
      scores.push_back(info(std::string("W-shape d1, ") + label, one->w.d1, "c", "paper: 0.086c"));
      scores.push_back(info(std::string("W-shape d2, ") + label, one->w.d2, "c", "paper: 0.165c"));
    }
}

}  // namespace

Report build_report(const ReportInputs& in) {
  Report r;
  r.figures = json::object();
  double chord = in.chord;
  if (!(chord > 0) && in.mesh && in.mesh->chord) chord = *in.mesh->chord;
  if (!(chord > 0)) throw Error("report: no chord (give --chord or a mesh.h5 with its chord attribute)");
  r.figures["chord"] = chord;
  modulus_section(in, r);
  pressure_jump_figure(in, r.figures);
  root_pitch_figure(in, r.figures);
  const MotionMeasures m = measure_motions(in, chord, r.figures);
  shape_scores(in, m, r.scores);
  const auto loads_ct = force_section(in, r);
  distance_scores(in, chord, r.scores);
  closing_the_loop(in, r);
  reading_scores(loads_ct, m, r.scores);
  return r;
}

nlohmann::json summary_json(const ReportInputs& in, const Report& r) {
  json counts{{"met", 0}, {"missed", 0}, {"not available", 0}, {"info", 0}};
  for (const auto& s : r.scores) counts[to_string(s.status)] = counts[to_string(s.status)].get<int>() + 1;
  json j = {{"schema", "finverse/report"},
          {"schema_version", 1},
          {"case", in.case_name},
          {"scores", to_json(r.scores)},
          {"counts", counts},
          {"inputs",
           {{"truth", in.truth.has_value()}, {"kinematics", in.kinematics.has_value()}, {"mesh", in.mesh.has_value()},
            {"motion", in.motion.has_value()}, {"loads", in.loads.has_value()}, {"materials", in.materials.has_value()},
            {"fsi", in.fsi.has_value()}, {"truth_materials", in.truth_materials_source}}}};
  if (in.loop) j["inputs"]["loop"] = true;
  if (!in.scope.empty()) j["scope"] = in.scope;
  return j;
}

}  // namespace finverse::report
