// NodeItems (kernels/mpm/grid.hpp): how the grid update and P2G's gather cut a rectangle of nodes
// into parallel work items, whole rows or runs of rows (host threads) or single nodes (a GPU).
// Every cutting must visit every node of the rectangle exactly once and nothing outside it; the
// single-node one is what a CUDA build runs, checked here on the host.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <utility>
#include <vector>

#include "kernels/mpm/grid.hpp"

namespace {
using lsi::mpm::NodeBox;
using lsi::mpm::NodeItemsOf;

template <bool WholeRows>
std::map<std::pair<int, int>, int> visits(const NodeBox& box, const int threads) {
  const NodeItemsOf<WholeRows> items(box, nullptr, threads);
  std::map<std::pair<int, int>, int> seen;
  for (int t = 0; t < items.count(); ++t)
    items.visit(t, [&](const int j, const int i_begin, const int i_end) {
      for (int i = i_begin; i <= i_end; ++i) ++seen[{i, j}];
    });
  return seen;
}

template <bool WholeRows>
void expect_each_node_once(const NodeBox& box, const int threads = 1) {
  const auto seen = visits<WholeRows>(box, threads);
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
  expect_each_node_once<true>(NodeBox{0, 0, 7, 7});                          // a single node
  EXPECT_EQ(NodeItemsOf<true>(NodeBox{3, 9, 2, 5}, nullptr, 4).count(), 4);  // no more rows
  EXPECT_EQ(NodeItemsOf<true>(NodeBox{3, 9, 2, 5}, nullptr, 8).count(), 4);  // than threads
}

TEST(NodeItems, RunsOfRowsVisitEachNodeOnce) {
  EXPECT_EQ(NodeItemsOf<true>(NodeBox{3, 9, 2, 5}, nullptr, 3).count(), 3);  // a run a thread
  for (const int threads : {2, 3, 7, 64}) {
    expect_each_node_once<true>(NodeBox{3, 9, 2, 5}, threads);
    expect_each_node_once<true>(NodeBox{0, 40, 0, 99}, threads);
  }
  // More threads than runs can hold: a row a work item.
  EXPECT_EQ(NodeItemsOf<true>(NodeBox{0, 3, 0, 99}, nullptr, 65).count(), 100);
  expect_each_node_once<true>(NodeBox{0, 3, 0, 99}, 65);
}

// A wedge of row spans, 60 nodes long at the bottom and 1 at the top (a flow piled against a
// barrier), cut for 2 and 4 threads: each run holds its share of the nodes to within one row
// (the cut falls after the row that reaches the share), the rows in order from the lowest,
// where equal numbers of rows would give the lowest run most of the nodes.
TEST(NodeItems, RunsOfRowsHoldEqualNumbersOfNodes) {
  const int rows = 60;
  std::vector<int> spans(2 * rows);
  long total = 0;
  for (int j = 0; j < rows; ++j) {
    spans[2 * j] = 10;
    spans[2 * j + 1] = 10 + (rows - 1 - j);  // row j: rows - j nodes
    total += rows - j;
  }
  for (const int threads : {2, 4}) {
    const NodeItemsOf<true> items(NodeBox{0, 200, 0, rows - 1}, spans.data(), threads);
    ASSERT_EQ(items.count(), threads);
    int next_row = 0;
    for (int t = 0; t < threads; ++t) {
      long nodes = 0;
      items.visit(t, [&](const int j, const int i_begin, const int i_end) {
        EXPECT_EQ(j, next_row++);
        EXPECT_EQ(i_begin, 10);
        nodes += i_end - i_begin + 1;
      });
      EXPECT_LE(std::abs(nodes - total / threads), rows) << threads << " threads, run " << t;
    }
    EXPECT_EQ(next_row, rows);
  }
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
