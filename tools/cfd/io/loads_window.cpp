// The centred mean of the per-step loads over an output interval (see loads_window.hpp).
#include "cfd/io/loads_window.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd::io {

LoadsWindow::LoadsWindow(long m, std::size_t nodes, std::size_t shell, long first_output_step, long last_output_step,
                         long last_step, bool sample)
    : m_(m),
      first_(first_output_step),
      last_out_(last_output_step),
      last_step_(last_step),
      sample_(sample),
      nodes_(nodes),
      shell_(shell) {
  if (m < 1 || last_step < last_output_step)
    throw Error("loads window: need m >= 1 steps per output and the last step at or after the last output");
}

long LoadsWindow::half_width(long s) const {
  if (sample_) return 0;
  const long q = m_ % 2 ? (m_ - 1) / 2 : m_ / 2;
  return std::max(0L, std::min({q, last_step_ - s, s - 1}));
}

double LoadsWindow::weight(long s, long n) const {
  const long q = half_width(s), d = std::abs(n - s);
  if (d > q) return 0;
  // The full box of an even m ends half-way through its end steps (shared with the neighbour).
  if (m_ % 2 == 0 && q == m_ / 2 && d == q && q > 0) return 0.5;
  return 1;
}

bool LoadsWindow::needs(long n) const {
  const long s1 = (n / m_) * m_;
  for (long s : {s1, s1 + m_})
    if (s >= first_ && s <= last_out_ && s > 0 && weight(s, n) > 0) return true;
  return false;
}

std::vector<LoadsWindow::Output> LoadsWindow::add(long n, const std::vector<Vec3>& nodal, const Vec3& total,
                                                  const std::vector<double>& jump) {
  if (nodal.size() != nodes_ || jump.size() != shell_)
    throw Error("loads window: " + std::to_string(nodal.size()) + " nodal forces and " + std::to_string(jump.size()) +
                " pressure jumps for " + std::to_string(nodes_) + " nodes and " + std::to_string(shell_) +
                " shell triangles");
  std::vector<Output> done;
  const long s1 = (n / m_) * m_;
  for (long s : {s1, s1 + m_}) {
    if (s < first_ || s > last_out_ || s <= 0) continue;
    const double w = weight(s, n);
    if (w == 0) continue;
    auto it = std::find_if(open_.begin(), open_.end(), [s](const Open& o) { return o.step == s; });
    if (it == open_.end()) {
      if (n != s - half_width(s))
        throw Error("loads window: step " + std::to_string(n) + " opens the window of step " + std::to_string(s) +
                    ", which starts at step " + std::to_string(s - half_width(s)));
      Open o;
      o.step = s;
      o.nodal.assign(3 * nodes_, 0.0);
      o.jump.assign(shell_, 0.0);
      open_.push_back(std::move(o));
      it = std::prev(open_.end());
    }
    it->weight += w;
    for (std::size_t i = 0; i < nodes_; ++i)
      for (std::size_t d = 0; d < 3; ++d) it->nodal[3 * i + d] += w * nodal[i][d];
    for (std::size_t d = 0; d < 3; ++d) it->total[d] += w * total[d];
    for (std::size_t j = 0; j < shell_; ++j) it->jump[j] += w * jump[j];
    if (n == s + half_width(s)) {
      Output out;
      out.step = s;
      out.nodal.resize(nodes_);
      for (std::size_t i = 0; i < nodes_; ++i)
        for (std::size_t d = 0; d < 3; ++d) out.nodal[i][d] = it->nodal[3 * i + d] / it->weight;
      for (std::size_t d = 0; d < 3; ++d) out.total[d] = it->total[d] / it->weight;
      out.jump.resize(shell_);
      for (std::size_t j = 0; j < shell_; ++j) out.jump[j] = it->jump[j] / it->weight;
      done.push_back(std::move(out));
      open_.erase(it);
    }
  }
  std::sort(done.begin(), done.end(), [](const Output& a, const Output& b) { return a.step < b.step; });
  return done;
}

std::vector<double> LoadsWindow::state() const {
  std::vector<double> s{static_cast<double>(open_.size())};
  for (const Open& o : open_) {
    s.push_back(static_cast<double>(o.step));
    s.push_back(o.weight);
    s.insert(s.end(), o.total.begin(), o.total.end());
    s.insert(s.end(), o.nodal.begin(), o.nodal.end());
    s.insert(s.end(), o.jump.begin(), o.jump.end());
  }
  return s;
}

void LoadsWindow::restore(const std::vector<double>& s) {
  const std::size_t per = 5 + 3 * nodes_ + shell_;
  if (s.empty() || s.size() != 1 + per * static_cast<std::size_t>(std::lround(s[0])))
    throw Error("loads window: a restored state of " + std::to_string(s.size()) + " values does not fit " +
                std::to_string(nodes_) + " nodes and " + std::to_string(shell_) + " shell triangles");
  open_.clear();
  for (std::size_t k = 0, at = 1; k < static_cast<std::size_t>(std::lround(s[0])); ++k, at += per) {
    Open o;
    o.step = std::lround(s[at]);
    o.weight = s[at + 1];
    for (std::size_t d = 0; d < 3; ++d) o.total[d] = s[at + 2 + d];
    o.nodal.assign(s.begin() + static_cast<long>(at + 5), s.begin() + static_cast<long>(at + 5 + 3 * nodes_));
    o.jump.assign(s.begin() + static_cast<long>(at + 5 + 3 * nodes_), s.begin() + static_cast<long>(at + per));
    open_.push_back(std::move(o));
  }
}

}  // namespace finverse::cfd::io
