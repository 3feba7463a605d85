// NodeItems (kernels/mpm/grid.hpp): how the grid update and P2G's gather cut a rectangle of nodes
// into parallel work items, whole rows (host threads) or single nodes (a GPU). Both cuttings must
// visit every node of the rectangle exactly once and nothing outside it; the single-node one is
// what a CUDA build runs, checked here on the host.
#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "kernels/mpm/grid.hpp"

namespace {
using lsi::mpm::NodeBox;
using lsi::mpm::NodeItemsOf;

template <bool WholeRows>
std::map<std::pair<int, int>, int> visits(const NodeBox& box) {
  const NodeItemsOf<WholeRows> items(box);
  std::map<std::pair<int, int>, int> seen;
  for (int t = 0; t < items.count(); ++t) {
    int j, i_begin, i_end;
    items.nodes(t, j, i_begin, i_end);
    for (int i = i_begin; i <= i_end; ++i) ++seen[{i, j}];
  }
  return seen;
}

template <bool WholeRows>
void expect_each_node_once(const NodeBox& box) {
  const auto seen = visits<WholeRows>(box);
  const int cols = box.i1 - box.i0 + 1, rows = box.j1 - box.j0 + 1;
  EXPECT_EQ(seen.size(), static_cast<size_t>(cols * rows));
  for (const auto& [node, count] : seen) {
    EXPECT_EQ(count, 1) << node.first << "," << node.second;
    EXPECT_GE(node.first, box.i0);
    EXPECT_LE(node.first, box.i1);
    EXPECT_GE(node.second, box.j0);
    EXPECT_LE(node.second, box.j1);
  }
}

TEST(NodeItems, WholeRowsVisitEachNodeOnce) {
  EXPECT_EQ(NodeItemsOf<true>(NodeBox{3, 9, 2, 5}).count(), 4);  // one item per row
  expect_each_node_once<true>(NodeBox{3, 9, 2, 5});
  expect_each_node_once<true>(NodeBox{0, 0, 7, 7});  // a single node
}

TEST(NodeItems, SingleNodesVisitEachNodeOnce) {
  EXPECT_EQ(NodeItemsOf<false>(NodeBox{3, 9, 2, 5}).count(), 28);  // one item per node
  expect_each_node_once<false>(NodeBox{3, 9, 2, 5});
  expect_each_node_once<false>(NodeBox{0, 0, 7, 7});
  expect_each_node_once<false>(NodeBox{5, 5, 0, 40});  // one column
}

TEST(NodeItems, AnEmptyBoxHasNoItems) {
  EXPECT_EQ(NodeItemsOf<true>(NodeBox{}).count(), 0);
  EXPECT_EQ(NodeItemsOf<false>(NodeBox{}).count(), 0);
}
}  // namespace
