// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file test_batch_lists.cpp
 * \brief pcl_phaser_batch's inputs: pair lists, scan lists and poses (good and
 * malformed), loop-closure candidates, shards.
 */
#include "batch_pairs.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <numeric>
#include <set>
#include <string>
#include <unistd.h>

namespace batch = pcl::phaser::batch;

namespace {

/** \brief A file in a fresh temporary folder, removed with it. */
struct TempFile {
  std::string folder, path;
  explicit TempFile(const std::string& text, const std::string& name = "list.txt")
  {
    char pattern[] = "/tmp/pcl_phaser_batch_test_XXXXXX";
    folder = ::mkdtemp(pattern);
    path = folder + "/" + name;
    std::ofstream(path) << text;
  }
  ~TempFile()
  {
    std::remove(path.c_str());
    ::rmdir(folder.c_str());
  }
};

} // namespace

TEST(BatchPairList, ReadsPairsGuessesAndCommentsWithPathsAgainstItsFolder)
{
  const TempFile list("# a comment\n"
                      "a.pcd b.pcd   # trailing comment\n"
                      "\n"
                      "/abs/c.pcd a.pcd 0 -1 0 1  1 0 0 2  0 0 1 3\n");
  batch::PairList pairs;
  ASSERT_EQ(batch::readPairList(list.path, pairs), "");
  ASSERT_EQ(pairs.pairs.size(), 2u);
  const batch::Pair& first = pairs.pairs[0];
  EXPECT_EQ(first.source, "a.pcd");
  EXPECT_EQ(first.source_path, list.folder + "/a.pcd");
  EXPECT_EQ(first.target_path, list.folder + "/b.pcd");
  EXPECT_FALSE(first.has_guess);
  const batch::Pair& second = pairs.pairs[1];
  EXPECT_EQ(second.source_path, "/abs/c.pcd");
  EXPECT_TRUE(second.has_guess);
  EXPECT_EQ(second.guess(0, 1), -1.0); // row-major 3x4
  EXPECT_EQ(second.guess(1, 3), 2.0);
  EXPECT_EQ(second.guess(2, 3), 3.0);
  EXPECT_EQ(second.guess(3, 3), 1.0);
  // Ids in order of first appearance, source before target.
  EXPECT_EQ(pairs.names, (std::vector<std::string>{"a.pcd", "b.pcd", "/abs/c.pcd"}));
  EXPECT_EQ(second.source_id, 2);
  EXPECT_EQ(second.target_id, 0);
  EXPECT_EQ(second.index, 1u);
}

TEST(BatchPairList, MalformedListsAreRefusedWithTheLine)
{
  const std::pair<const char*, const char*> cases[] = {
      {"a.pcd\n", "line 1: expected SOURCE TARGET"},
      {"a.pcd b.pcd 1 2 3\n", "line 1: expected SOURCE TARGET"},
      {"x y\na.pcd b.pcd 1 0 0 0 0 1 0 0 0 0 1 nan\n", "line 2: the guess"},
      {"a.pcd b.pcd 1 0 0 0 0 1 0 0 0 0 1 zero\n", "line 1: the guess"},
      {"a.pcd b.pcd\n\na.pcd b.pcd\n", "line 3: repeats the pair of line 1"},
      {"a.pcd b.pcd 2 0 0 0 0 1 0 0 0 0 1 0\n", "line 1: the guess is not a rigid"},
      {"a\xff.pcd b.pcd\n", "line 1: a path is not valid UTF-8"}};
  for (const auto& [text, reason] : cases) {
    const TempFile list(text);
    batch::PairList pairs;
    const std::string error = batch::readPairList(list.path, pairs);
    EXPECT_NE(error.find(reason), std::string::npos) << text << " -> " << error;
  }
  batch::PairList pairs;
  EXPECT_NE(batch::readPairList("/nonexistent/list.txt", pairs).find("cannot read"),
            std::string::npos);
}

TEST(BatchPoses, ReadTheLast12NumbersOfKittiAndIndexedLines)
{
  const TempFile poses("# index time then the pose\n"
                       "0 1630577758.5 1 0 0 1 0 1 0 2 0 0 1 3\n"
                       "1 0 0 0 1 4 0 1 0 5 -1 0 0 6\n");
  std::vector<Eigen::Matrix4d> read;
  ASSERT_EQ(batch::readPoses(poses.path, read), "");
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(Eigen::Vector3d(read[0].topRightCorner<3, 1>()), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(read[1](0, 2), 1.0);
  EXPECT_EQ(read[1](2, 0), -1.0);
  const TempFile short_line("1 0 0 0 1 0 0 0 1 0\n");
  EXPECT_NE(batch::readPoses(short_line.path, read).find("line 1"), std::string::npos);
}

TEST(BatchCandidates, PairScansWithinTheRadiusAndTheGapEarlierAsTarget)
{
  std::vector<Eigen::Matrix4d> poses(5, Eigen::Matrix4d::Identity());
  const double x[] = {0.0, 1.0, 50.0, 0.5, 19.9};
  for (int i = 0; i < 5; ++i)
    poses[i](0, 3) = x[i];
  const std::vector<std::string> names = {"s0", "s1", "s2", "s3", "s4"};
  const batch::PairList list = batch::makeCandidates(names, names, poses, 20.0, 2);
  std::set<std::pair<int, int>> got;
  for (const batch::Pair& p : list.pairs) {
    EXPECT_LT(p.target_id, p.source_id);
    EXPECT_EQ(p.target, names[p.target_id]);
    got.insert({p.target_id, p.source_id});
  }
  // 0-2 too far, 1-2 too far, 0-4 at 19.9 m, 1-3 at 0.5 m, 0-3, 1-4 at 18.9 m; 2-4 far.
  EXPECT_EQ(got, (std::set<std::pair<int, int>>{{0, 3}, {0, 4}, {1, 3}, {1, 4}}));
}

TEST(BatchShard, ParsesKOfNAndRefusesTheRest)
{
  EXPECT_EQ(batch::parseShard("0/1"), std::make_pair(0, 1));
  EXPECT_EQ(batch::parseShard("3/4"), std::make_pair(3, 4));
  for (const char* bad :
       {"3/2", "2/2", "-1/2", "1/0", "a/b", "1", "1/2/3", "0.5/2", ""})
    EXPECT_FALSE(batch::parseShard(bad)) << bad;
}

TEST(BatchShard, PartsAreDisjointCoverTheListAndKeepTargetsTogether)
{
  batch::PairList list;
  const int targets[] = {0, 1, 0, 2, 1, 3, 3, 0, 4, 2, 5, 5};
  for (std::size_t i = 0; i < std::size(targets); ++i) {
    batch::Pair p;
    p.index = i;
    p.target_id = targets[i];
    p.source_id = 10 + static_cast<int>(i);
    list.pairs.push_back(p);
  }
  for (const int n : {1, 2, 3, 5}) {
    std::multiset<std::size_t> all;
    std::set<int> seen_targets;
    for (int k = 0; k < n; ++k) {
      const std::vector<std::size_t> part = batch::shardPairs(list, k, n);
      EXPECT_EQ(part, batch::shardPairs(list, k, n)); // the list alone decides
      std::set<int> mine;
      for (const std::size_t i : part) {
        all.insert(i);
        mine.insert(list.pairs[i].target_id);
      }
      for (const int t : mine) { // no group exceeds a share (3 pairs or more)
        EXPECT_TRUE(seen_targets.insert(t).second) << "target " << t;
      }
      for (std::size_t a = 1; a < part.size(); ++a) { // grouped: a target never returns
        if (list.pairs[part[a]].target_id == list.pairs[part[a - 1]].target_id)
          continue;
        for (std::size_t b = a; b < part.size(); ++b)
          EXPECT_NE(list.pairs[part[b]].target_id, list.pairs[part[a - 1]].target_id);
      }
    }
    std::vector<std::size_t> expected(list.pairs.size());
    std::iota(expected.begin(), expected.end(), 0);
    EXPECT_EQ(std::vector<std::size_t>(all.begin(), all.end()), expected) << n;
  }
}

TEST(BatchShard, AGroupLargerThanAShareIsCut)
{
  batch::PairList list; // one map, ten queries: two shards share the work
  for (std::size_t i = 0; i < 10; ++i) {
    batch::Pair p;
    p.index = i;
    list.pairs.push_back(p);
  }
  EXPECT_EQ(batch::shardPairs(list, 0, 2).size(), 5u);
  EXPECT_EQ(batch::shardPairs(list, 1, 2).size(), 5u);
}
