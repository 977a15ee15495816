#include "pathpace/binding_labels.hpp"

#include <map>
#include <utility>

namespace pathpace {

namespace {
const std::string kNone;
}  // namespace

BindingLabels::BindingLabels(std::vector<int> ids, std::shared_ptr<const std::vector<std::string>> names)
    : ids_(std::move(ids)), names_(std::move(names)) {}

BindingLabels::BindingLabels(const std::vector<std::string>& labels) {
  auto names = std::make_shared<std::vector<std::string>>();
  std::map<std::string, int> index;
  ids_.reserve(labels.size());
  for (const std::string& l : labels) {
    if (l.empty()) {
      ids_.push_back(-1);
      continue;
    }
    auto [it, fresh] = index.emplace(l, static_cast<int>(names->size()));
    if (fresh) names->push_back(l);
    ids_.push_back(it->second);
  }
  names_ = std::move(names);
}

const std::string& BindingLabels::operator[](std::size_t k) const {
  const int id = ids_[k];
  return id < 0 || !names_ ? kNone : (*names_)[static_cast<std::size_t>(id)];
}

std::vector<std::string> BindingLabels::strings() const {
  std::vector<std::string> out;
  out.reserve(ids_.size());
  for (std::size_t k = 0; k < ids_.size(); ++k) out.push_back((*this)[k]);
  return out;
}

}  // namespace pathpace
