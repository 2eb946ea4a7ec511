#include "hba/dist/group.hpp"

namespace hba::dist {
namespace {

class SingleProcess final : public Group {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::vector<Bytes> allGather(const Bytes& mine) const override { return {mine}; }
  std::vector<Bytes> allToAll(const std::vector<Bytes>& to_each) const override { return {to_each.at(0)}; }
};

}  // namespace

Bytes fromRoot(const Group& group, const Bytes& mine) {
  if (group.size() == 1) return mine;
  return group.allGather(group.root() ? mine : Bytes{}).front();
}

const Group& singleProcess() {
  static const SingleProcess group;
  return group;
}

}  // namespace hba::dist
