// Checkpoint encoding (checkpoint.hpp).
#include "fit/checkpoint.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "fit/errors.hpp"

namespace finverse::fit {

nlohmann::json pack_doubles(const double* data, std::size_t count) {
  std::vector<std::uint8_t> bytes(count * sizeof(double));
  if (count) std::memcpy(bytes.data(), data, bytes.size());
  return nlohmann::json::binary(std::move(bytes));
}

nlohmann::json pack_vector(const Eigen::VectorXd& v) {
  return pack_doubles(v.data(), static_cast<std::size_t>(v.size()));
}

std::vector<double> unpack_doubles(const nlohmann::json& j) {
  if (!j.is_binary()) throw InvalidInput("checkpoint: expected a binary array of doubles");
  const auto& bytes = j.get_binary();
  if (bytes.size() % sizeof(double) != 0)
    throw InvalidInput("checkpoint: binary array length is not a multiple of 8");
  std::vector<double> out(bytes.size() / sizeof(double));
  if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

Eigen::VectorXd unpack_vector(const nlohmann::json& j) {
  const std::vector<double> d = unpack_doubles(j);
  return Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
}

nlohmann::json run_result_to_json(const RunResult& run) {
  nlohmann::json history = nlohmann::json::array();
  for (const GenerationRecord& g : run.history)
    history.push_back({{"generation", g.generation},
                       {"best", pack_doubles(&g.best, 1)},
                       {"mean", pack_doubles(&g.mean, 1)},
                       {"evaluations", g.evaluations},
                       {"wall_seconds", g.wall_seconds},
                       {"best_x", pack_vector(g.best_x)}});
  return {{"method", run.method},
          {"seed", run.seed},
          {"best_x", pack_vector(run.best_x)},
          {"best_objective", pack_doubles(&run.best_objective, 1)},
          {"history", std::move(history)},
          {"evaluations", run.evaluations},
          {"cache_hits", run.cache_hits},
          {"failures", run.failures},
          {"wall_seconds", run.wall_seconds},
          {"converged", run.converged},
          {"polished_x", pack_vector(run.polished_x)},
          {"polished_objective", pack_doubles(&run.polished_objective, 1)},
          {"polished_sum_of_squares", pack_doubles(&run.polished_sum_of_squares, 1)},
          {"polish_evaluations", run.polish_evaluations},
          {"polish_wall_seconds", run.polish_wall_seconds}};
}

namespace {
double scalar(const nlohmann::json& j) {
  const std::vector<double> d = unpack_doubles(j);
  if (d.size() != 1) throw InvalidInput("checkpoint: expected one double");
  return d[0];
}
}  // namespace

RunResult run_result_from_json(const nlohmann::json& j) {
  RunResult run;
  run.method = j.at("method").get<std::string>();
  run.seed = j.at("seed").get<unsigned>();
  run.best_x = unpack_vector(j.at("best_x"));
  run.best_objective = scalar(j.at("best_objective"));
  for (const nlohmann::json& h : j.at("history")) {
    GenerationRecord g;
    g.generation = h.at("generation").get<int>();
    g.best = scalar(h.at("best"));
    g.mean = scalar(h.at("mean"));
    g.evaluations = h.at("evaluations").get<long>();
    g.wall_seconds = h.at("wall_seconds").get<double>();
    g.best_x = unpack_vector(h.at("best_x"));
    run.history.push_back(std::move(g));
  }
  run.evaluations = j.at("evaluations").get<long>();
  run.cache_hits = j.at("cache_hits").get<long>();
  run.failures = j.at("failures").get<long>();
  run.wall_seconds = j.at("wall_seconds").get<double>();
  run.converged = j.at("converged").get<bool>();
  run.polished_x = unpack_vector(j.at("polished_x"));
  run.polished_objective = scalar(j.at("polished_objective"));
  run.polished_sum_of_squares = scalar(j.at("polished_sum_of_squares"));
  run.polish_evaluations = j.at("polish_evaluations").get<long>();
  run.polish_wall_seconds = j.at("polish_wall_seconds").get<double>();
  return run;
}

nlohmann::json uncertainty_to_json(const Uncertainty& u) {
  const double misfit[4] = {u.misfit_correlation_length, u.misfit_neighbour_correlation, u.effective_residuals,
                            u.effective_channels};
  return {{"standard_error", pack_vector(u.standard_error)},
          {"lower95", pack_vector(u.lower95)},
          {"upper95", pack_vector(u.upper95)},
          {"correlation", pack_doubles(u.correlation.data(), static_cast<std::size_t>(u.correlation.size()))},
          {"correlation_rows", u.correlation.rows()},
          {"singular_values", pack_vector(u.singular_values)},
          {"residual_variance", pack_doubles(&u.residual_variance, 1)},
          {"degrees_of_freedom", u.degrees_of_freedom},
          {"identified", u.identified},
          {"verdict", u.verdict},
          {"systematic_misfit", u.systematic_misfit},
          {"misfit", pack_doubles(misfit, 4)}};
}

Uncertainty uncertainty_from_json(const nlohmann::json& j) {
  Uncertainty u;
  u.standard_error = unpack_vector(j.at("standard_error"));
  u.lower95 = unpack_vector(j.at("lower95"));
  u.upper95 = unpack_vector(j.at("upper95"));
  const std::vector<double> c = unpack_doubles(j.at("correlation"));
  const Eigen::Index rows = j.at("correlation_rows").get<Eigen::Index>();
  u.correlation = rows > 0 ? Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(
                                 c.data(), rows, static_cast<Eigen::Index>(c.size()) / rows))
                           : Eigen::MatrixXd();
  u.singular_values = unpack_vector(j.at("singular_values"));
  u.residual_variance = scalar(j.at("residual_variance"));
  u.degrees_of_freedom = j.at("degrees_of_freedom").get<int>();
  u.identified = j.at("identified").get<std::vector<int>>();
  u.verdict = j.at("verdict").get<std::vector<std::string>>();
  u.systematic_misfit = j.at("systematic_misfit").get<bool>();
  const std::vector<double> misfit = unpack_doubles(j.at("misfit"));
  u.misfit_correlation_length = misfit.at(0);
  u.misfit_neighbour_correlation = misfit.at(1);
  u.effective_residuals = misfit.at(2);
  if (misfit.size() > 3) u.effective_channels = misfit.at(3);  // written since the channel model
  return u;
}

void write_checkpoint(const std::filesystem::path& path, const nlohmann::json& state) {
  const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(state);
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InvalidInput(tmp.string() + ": cannot write the checkpoint");
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw InvalidInput(tmp.string() + ": write of the checkpoint failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InvalidInput(path.string() + ": cannot rename the checkpoint into place (" + ec.message() + ")");
}

std::optional<nlohmann::json> read_checkpoint(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(path.string() + ": cannot open the checkpoint");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    return nlohmann::json::from_cbor(bytes);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(path.string() + ": not a fit checkpoint (" + e.what() + ")");
  }
}

}  // namespace finverse::fit
