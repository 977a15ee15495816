#pragma once
// Result::binding: per interval of a timed result, the label of the constraint that binds there.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pathpace {

/// Per interval k (N entries), the label of the constraint that binds on it, "" if none. Kept as one id per
/// interval into a table of labels shared by the intervals: a solve builds no string per interval (strings
/// cost a visible part of a fast solve). Indexing gives the label; strings() all of them.
class BindingLabels {
 public:
  BindingLabels() = default;
  /// ids[k] indexes names (-1: no binding constraint on interval k).
  BindingLabels(std::vector<int> ids, std::shared_ptr<const std::vector<std::string>> names);
  /// From the labels themselves (e.g. a pickled result); "" is no binding constraint.
  explicit BindingLabels(const std::vector<std::string>& labels);

  std::size_t size() const { return ids_.size(); }
  bool empty() const { return ids_.empty(); }
  /// The label on interval k ("" if none); k < size().
  const std::string& operator[](std::size_t k) const;
  std::vector<std::string> strings() const;

 private:
  std::vector<int> ids_;
  std::shared_ptr<const std::vector<std::string>> names_;
};

}  // namespace pathpace
