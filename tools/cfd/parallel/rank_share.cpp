// The process's rank share; see rank_share.hpp.
#include "cfd/parallel/rank_share.hpp"

#include <utility>

namespace finverse::cfd {

namespace {
std::shared_ptr<const RankShare>& installed() {
  static std::shared_ptr<const RankShare> share;
  return share;
}
}  // namespace

void install_rank_share(std::shared_ptr<const RankShare> share) { installed() = std::move(share); }

const RankShare* rank_share() { return installed().get(); }

}  // namespace finverse::cfd
