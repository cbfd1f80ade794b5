// The fit's evaluations across MPI ranks (see rank_pool.hpp).
#include "fit/rank_pool.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#ifdef FINVERSE_HAVE_MPI
#include <mpi.h>
#endif

#include "core/cli.hpp"
#include "core/log.hpp"
#include "fit/errors.hpp"

namespace finverse::fit {
namespace {

RankPool* g_current = nullptr;

// What rank 0 sends before each message: the command, the function, the vectors and their size,
// whether residuals come back, and the threads each rank uses.
enum Command : int { kEvaluate = 1, kExpectNear = 2, kRelease = 3 };
struct Header {
  int command = 0, function = 0, count = 0, dim = 0, keep = 0, threads = 1;
};

}  // namespace

bool launched_by_mpi() { return cli::mpi_launch_size() > 1; }

RankPool* RankPool::current() { return g_current; }

#ifdef FINVERSE_HAVE_MPI

namespace {

// Rank 0's broadcast of a header and `data` (count x dim doubles, or dim for one vector).
void broadcast(Header& h, std::vector<double>& data) {
  MPI_Bcast(&h, sizeof(Header), MPI_BYTE, 0, MPI_COMM_WORLD);
  const std::size_t n = h.command == kEvaluate     ? static_cast<std::size_t>(h.count) * h.dim
                        : h.command == kExpectNear ? static_cast<std::size_t>(h.dim)
                                                   : 0;
  data.resize(n);
  if (n > 0) MPI_Bcast(data.data(), static_cast<int>(n), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

// This rank's share of a batch: the vectors i with i mod size = rank.
std::vector<int> share(int count, int rank, int size) {
  std::vector<int> mine;
  for (int i = rank; i < count; i += size) mine.push_back(i);
  return mine;
}

BatchEvaluation evaluate_share(const ParameterSpace& space, const ResidualFunction& function, const Header& h,
                               const std::vector<double>& data, const std::vector<int>& mine) {
  std::vector<Eigen::VectorXd> xs;
  for (int i : mine)
    xs.push_back(Eigen::Map<const Eigen::VectorXd>(data.data() + static_cast<std::size_t>(i) * h.dim, h.dim));
  return evaluate_batch_here(space, function, xs, h.threads, h.keep != 0);
}

// One rank's results packed: per vector its objective (+inf: failed), then its residuals when
// kept and not failed.
std::vector<double> pack(const BatchEvaluation& b, bool keep) {
  std::vector<double> out;
  for (std::size_t k = 0; k < b.objective.size(); ++k) {
    out.push_back(b.objective[k]);
    if (keep && std::isfinite(b.objective[k]))
      out.insert(out.end(), b.residuals[k].data(), b.residuals[k].data() + b.residuals[k].size());
  }
  return out;
}

}  // namespace

RankPool::RankPool() {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (size_ != cli::mpi_launch_size()) {  // srun without an MPI plugin: unconnected singletons
    const int launched = cli::mpi_launch_size();
    MPI_Finalize();
    throw InvalidInput("started as " + std::to_string(launched) + " tasks, but MPI sees " + std::to_string(size_) +
                       " rank(s): the launcher did not connect them (srun needs --mpi=pmix, or the site's MPI plugin)");
  }
  g_current = this;
}

RankPool::~RankPool() {
  if (g_current != this) return;
  if (rank_ == 0) release();
  g_current = nullptr;
  MPI_Finalize();
}

void RankPool::release() {
  if (rank_ != 0 || released_ || size_ < 2) return;  // released_ starts true: nobody serves yet
  released_ = true;
  if (!counts_.empty()) {
    std::string line = "fin-fit: evaluations per rank in batches:";
    for (long c : counts_) line += " " + std::to_string(c);
    log::info(line);
  }
  Header h;
  h.command = kRelease;
  std::vector<double> none;
  broadcast(h, none);
}

BatchEvaluation RankPool::evaluate(int function, const ParameterSpace& space,
                                   const std::vector<Eigen::VectorXd>& scaled, int threads, bool keep_residuals) {
  Header h;
  h.command = kEvaluate, h.function = function, h.count = static_cast<int>(scaled.size());
  h.dim = scaled.empty() ? 0 : static_cast<int>(scaled[0].size());
  h.keep = keep_residuals, h.threads = threads;
  std::vector<double> data;
  for (const auto& z : scaled) data.insert(data.end(), z.data(), z.data() + z.size());
  broadcast(h, data);
  const ResidualFunction& f = *functions_.at(function);
  BatchEvaluation out;
  out.objective.assign(scaled.size(), std::numeric_limits<double>::infinity());
  if (keep_residuals) out.residuals.resize(scaled.size());
  const auto place = [&](const std::vector<int>& idx, const double* p) {
    for (int i : idx) {
      out.objective[i] = *p++;
      if (!std::isfinite(out.objective[i])) {
        ++out.failures;
      } else if (keep_residuals) {
        out.residuals[i] = Eigen::Map<const Eigen::VectorXd>(p, f.residual_count());
        p += f.residual_count();
      }
    }
  };
  const auto own = share(h.count, 0, size_);
  const auto here = pack(evaluate_share(space, f, h, data, own), keep_residuals);
  place(own, here.data());
  if (counts_.empty()) counts_.assign(static_cast<std::size_t>(size_), 0);
  for (int r = 0; r < size_; ++r)
    counts_[static_cast<std::size_t>(r)] += static_cast<long>(share(h.count, r, size_).size());
  for (int r = 1; r < size_; ++r) {
    MPI_Status status;
    MPI_Probe(r, 0, MPI_COMM_WORLD, &status);
    int n = 0;
    MPI_Get_count(&status, MPI_DOUBLE, &n);
    std::vector<double> buffer(static_cast<std::size_t>(n));
    MPI_Recv(buffer.data(), n, MPI_DOUBLE, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    place(share(h.count, r, size_), buffer.data());
  }
  return out;
}

void RankPool::expect_near(int function, const Eigen::VectorXd& physical) {
  Header h;
  h.command = kExpectNear, h.function = function, h.dim = static_cast<int>(physical.size());
  std::vector<double> data(physical.data(), physical.data() + physical.size());
  broadcast(h, data);
  functions_.at(function)->expect_near(physical);
}

void RankPool::serve(const ParameterSpace& space) {
  try {
    serve_until_released(space);
  } catch (...) {
    // Rank 0 waits for this rank's results: the job cannot go on.
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
}

void RankPool::serve_until_released(const ParameterSpace& space) {
  for (;;) {
    Header h;
    std::vector<double> data;
    broadcast(h, data);
    if (h.command == kRelease) return;
    const ResidualFunction& f = *functions_.at(h.function);
    if (h.command == kExpectNear) {
      f.expect_near(Eigen::Map<const Eigen::VectorXd>(data.data(), h.dim));
      continue;
    }
    const auto mine = share(h.count, rank_, size_);
    const auto packed = pack(evaluate_share(space, f, h, data, mine), h.keep != 0);
    MPI_Send(packed.data(), static_cast<int>(packed.size()), MPI_DOUBLE, 0, 0, MPI_COMM_WORLD);
  }
}

#else  // built without MPI

RankPool::RankPool() {
  if (launched_by_mpi())
    throw InvalidInput(
        "started by an MPI launcher, but this fin-fit was built without MPI: rebuild with "
        "-DFINVERSE_MPI=ON (Debian: libopenmpi-dev) or run it without mpirun");
}
RankPool::~RankPool() = default;
void RankPool::release() {}
BatchEvaluation RankPool::evaluate(int function, const ParameterSpace& space,
                                   const std::vector<Eigen::VectorXd>& scaled, int threads, bool keep_residuals) {
  return evaluate_batch_here(space, *functions_.at(function), scaled, threads, keep_residuals);
}
void RankPool::expect_near(int function, const Eigen::VectorXd& physical) {
  functions_.at(function)->expect_near(physical);
}
void RankPool::serve(const ParameterSpace&) {}
void RankPool::serve_until_released(const ParameterSpace&) {}

#endif

void RankPool::set_functions(std::vector<const ResidualFunction*> functions) {
  functions_ = std::move(functions);
  released_ = false;  // rank 0 now owes the serving ranks their release
}

std::optional<int> RankPool::id_of(const ResidualFunction& function) const {
  for (std::size_t i = 0; i < functions_.size(); ++i)
    if (functions_[i] == &function) return static_cast<int>(i);
  return std::nullopt;
}

void expect_near_everywhere(const ResidualFunction& function, const Eigen::VectorXd& physical) {
  RankPool* pool = RankPool::current();
  const auto id = pool && pool->size() > 1 ? pool->id_of(function) : std::nullopt;
  if (id)
    pool->expect_near(*id, physical);
  else
    function.expect_near(physical);
}

}  // namespace finverse::fit
