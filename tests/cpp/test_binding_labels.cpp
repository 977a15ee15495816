// pathpace::BindingLabels (Result::binding): ids into a shared label table, and the same from strings.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "pathpace/binding_labels.hpp"

using pathpace::BindingLabels;

TEST(BindingLabels, IdsIndexTheSharedTable) {
  auto names = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"velocity joint 0 upper", "acceleration shoulder lower"});
  const BindingLabels b({-1, 1, 0, 1, -1}, names);
  ASSERT_EQ(b.size(), 5u);
  EXPECT_EQ(b[0], "");
  EXPECT_EQ(b[1], "acceleration shoulder lower");
  EXPECT_EQ(b[2], "velocity joint 0 upper");
  EXPECT_EQ(&b[1], &b[3]);  // one string, shared
  const std::vector<std::string> want = {"", "acceleration shoulder lower", "velocity joint 0 upper",
                                         "acceleration shoulder lower", ""};
  EXPECT_EQ(b.strings(), want);
}

TEST(BindingLabels, FromStringsRoundTrips) {
  const std::vector<std::string> labels = {"torque hand_x upper", "", "torque hand_x upper", "sddot = 0 at s_end"};
  const BindingLabels b(labels);
  EXPECT_EQ(b.strings(), labels);
  EXPECT_EQ(&b[0], &b[2]);
  const BindingLabels none;
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(none.strings().empty());
}
