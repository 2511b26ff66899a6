/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "index/point_index.h"
#include "support/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace pcl::phaser {

namespace {

constexpr std::int64_t kBias = std::int64_t(1) << 20;

/** d2[j] = |p_(first + j) - q|^2 for j < m, the coordinates one array per axis; the
 *  same arithmetic as (p - q).squaredNorm(). AVX2 and the default (no FMA). */
[[gnu::target_clones("avx2", "default")]] void
squaredDistances(const double* x, const double* y, const double* z, Eigen::Index m,
                 double qx, double qy, double qz, double* d2)
{
  for (Eigen::Index j = 0; j < m; ++j) {
    const double dx = x[j] - qx, dy = y[j] - qy, dz = z[j] - qz;
    d2[j] = dx * dx + dy * dy + dz * dz;
  }
}

} // namespace

bool voxelKey(const Eigen::Vector3d& p, double voxel, std::int64_t& key)
{
  const Eigen::Array3d c = (p.array() / voxel).floor();
  if (!c.allFinite() || (c.abs() >= static_cast<double>(kBias - 1)).any())
    return false;
  key = 0;
  for (int a = 0; a < 3; ++a)
    key = (key << 21) | (static_cast<std::int64_t>(c[a]) + kBias);
  return true;
}

namespace {

std::int64_t offsetKey(std::int64_t key, int dx, int dy, int dz)
{
  constexpr std::int64_t kY = std::int64_t(1) << 21, kX = kY << 21;
  return key + dx * kX + dy * kY + dz;
}

/** Bit of the neighbor (dx, dy, dz) in PointIndex::Cell::occupied. */
std::uint32_t neighborBit(int dx, int dy, int dz)
{
  return std::uint32_t(1) << ((dx + 1) * 9 + (dy + 1) * 3 + (dz + 1));
}

/** Sorts \a keyed (increasing indices, keys below 2^\a bits) by key, then index, by a
 *  stable LSD radix sort: a fifth of std::sort's time on a lidar scan. */
void sortByKey(std::vector<std::pair<std::int64_t, Eigen::Index>>& keyed, int bits)
{
  constexpr int kDigitBits = 11;
  constexpr std::uint64_t kDigitMask = (std::uint64_t(1) << kDigitBits) - 1;
  std::vector<std::pair<std::int64_t, Eigen::Index>> buffer(keyed.size());
  std::vector<std::size_t> start(std::size_t(1) << kDigitBits);
  for (int shift = 0; shift < bits; shift += kDigitBits) {
    const auto digit = [&](std::int64_t key) {
      return static_cast<std::size_t>((static_cast<std::uint64_t>(key) >> shift) &
                                      kDigitMask);
    };
    std::fill(start.begin(), start.end(), 0);
    for (const auto& k : keyed)
      ++start[digit(k.first)];
    if (std::find(start.begin(), start.end(), keyed.size()) != start.end())
      continue; // one digit value for all: the order stays
    std::size_t sum = 0;
    for (std::size_t& s : start)
      sum += std::exchange(s, sum);
    for (const auto& k : keyed)
      buffer[start[digit(k.first)]++] = k;
    keyed.swap(buffer);
  }
}

/** Voxel keys (three 21-bit axis indices, x highest) packed as each axis's index less
 *  its least, in the bits its range needs: compress() keeps the keys' order, expand()
 *  undoes it, and the radix sort needs fewer passes. */
class CompactKeys {
public:
  explicit CompactKeys(const std::vector<std::pair<std::int64_t, Eigen::Index>>& keyed)
  {
    if (keyed.empty())
      return; // no bits: nothing to sort
    std::array<std::int64_t, 3> high{};
    low_.fill(kAxisMask);
    for (const auto& k : keyed)
      for (int a = 0; a < 3; ++a) {
        low_[a] = std::min(low_[a], axis(k.first, a));
        high[a] = std::max(high[a], axis(k.first, a));
      }
    for (int a = 0; a < 3; ++a)
      while (width_[a] < kAxisBits && (high[a] - low_[a]) >> width_[a] != 0)
        ++width_[a];
  }
  std::int64_t compress(std::int64_t key) const
  {
    std::int64_t out = 0;
    for (int a = 0; a < 3; ++a)
      out = (out << width_[a]) | (axis(key, a) - low_[a]);
    return out;
  }
  std::int64_t expand(std::int64_t compact) const
  {
    std::int64_t out = 0;
    int shift = bits();
    for (int a = 0; a < 3; ++a) {
      shift -= width_[a];
      const std::int64_t index =
          (compact >> shift) & ((std::int64_t(1) << width_[a]) - 1);
      out = (out << kAxisBits) | (index + low_[a]);
    }
    return out;
  }
  int bits() const { return width_[0] + width_[1] + width_[2]; }

private:
  static constexpr int kAxisBits = 21;
  static constexpr std::int64_t kAxisMask = (std::int64_t(1) << kAxisBits) - 1;
  /** Axis a's index (x is 0) of \a key. */
  static std::int64_t axis(std::int64_t key, int a)
  {
    return (key >> (kAxisBits * (2 - a))) & kAxisMask;
  }
  std::array<std::int64_t, 3> low_{};
  std::array<int, 3> width_{};
};

} // namespace

VoxelGroups groupByVoxel(const Eigen::Matrix3Xd& points, double voxel_size)
{
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size))
    throw InvalidArgument("voxel size must be positive");
  std::vector<std::pair<std::int64_t, Eigen::Index>> keyed;
  keyed.reserve(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    std::int64_t key = 0;
    if (voxelKey(points.col(i), voxel_size, key))
      keyed.emplace_back(key, i);
  }
  const CompactKeys compact(keyed);
  for (auto& k : keyed)
    k.first = compact.compress(k.first);
  sortByKey(keyed, compact.bits());
  VoxelGroups groups;
  groups.voxel_size = voxel_size;
  groups.order.reserve(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) {
      groups.keys.push_back(compact.expand(keyed[i].first));
      groups.offsets.push_back(static_cast<Eigen::Index>(i));
    }
    groups.order.push_back(keyed[i].second);
  }
  groups.offsets.push_back(static_cast<Eigen::Index>(keyed.size()));
  return groups;
}

Eigen::Matrix3Xd voxelCentroids(const Eigen::Matrix3Xd& points, double voxel_size,
                                int min_points)
{
  const VoxelGroups groups = groupByVoxel(points, voxel_size);
  Eigen::Matrix3Xd out(3, groups.size());
  Eigen::Index count = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Eigen::Index begin = groups.offsets[g], end = groups.offsets[g + 1];
    if (end - begin < min_points)
      continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Eigen::Index k = begin; k < end; ++k)
      sum += points.col(groups.order[k]);
    out.col(count++) = sum / static_cast<double>(end - begin);
  }
  out.conservativeResize(3, count);
  return out;
}

PointIndex::PointIndex(const Eigen::Matrix3Xd& points, double radius,
                       const Eigen::Matrix3Xd& normals)
    : radius_(radius)
{
  if (normals.cols() != 0 && normals.cols() != points.cols())
    throw InvalidArgument("PointIndex: one normal per point, or none");
  const VoxelGroups groups = groupByVoxel(points, radius);
  points_.resize(3, static_cast<Eigen::Index>(groups.order.size()));
  if (normals.cols() != 0)
    normals_.resize(3, points_.cols());
  for (std::size_t k = 0; k < groups.order.size(); ++k) {
    points_.col(static_cast<Eigen::Index>(k)) = points.col(groups.order[k]);
    if (normals.cols() != 0)
      normals_.col(static_cast<Eigen::Index>(k)) = normals.col(groups.order[k]);
  }
  has_normal_.resize(static_cast<std::size_t>(normals_.cols()));
  for (Eigen::Index k = 0; k < normals_.cols(); ++k)
    has_normal_[static_cast<std::size_t>(k)] = !normals_.col(k).isZero();
  // Open addressing with linear probing, at most a quarter full. Each cell with points
  // marks itself in the 27 cells around it, so a query probes only those that hold
  // points.
  slots_.assign(16, Cell{});
  slot_shift_ = 60;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t i = insert(groups.keys[g]);
    slots_[i].first = groups.offsets[g];
    slots_[i].last = groups.offsets[g + 1];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          slots_[insert(offsetKey(groups.keys[g], dx, dy, dz))].occupied |=
              neighborBit(-dx, -dy, -dz);
  }
  buildDirectory();
}

void PointIndex::buildDirectory()
{
  std::vector<Cell> cells;
  cells.reserve(used_);
  Eigen::Array3i low = Eigen::Array3i::Constant(std::numeric_limits<int>::max());
  Eigen::Array3i high = Eigen::Array3i::Constant(std::numeric_limits<int>::min());
  for (const Cell& cell : slots_)
    if (cell.key != kEmptyKey) {
      cells.push_back(cell);
      low = low.min(keyAxes(cell.key));
      high = high.max(keyAxes(cell.key));
    }
  if (cells.empty())
    return;
  const Eigen::Array3i dims = high - low + 1;
  if (static_cast<double>(dims.cast<double>().prod()) > kMaxDirectoryCells)
    return; // too sparse a box: the hash table serves
  // Keys order x, then y, then z, like the directory: cells next along z sit together.
  std::sort(cells.begin(), cells.end(),
            [](const Cell& a, const Cell& b) { return a.key < b.key; });
  directory_.assign(static_cast<std::size_t>(dims.prod()), -1);
  directory_low_ = low;
  directory_dims_ = dims;
  for (std::size_t c = 0; c < cells.size(); ++c)
    directory_[directoryIndex(keyAxes(cells[c].key))] = static_cast<std::int32_t>(c);
  cells_ = std::move(cells);
  std::vector<Cell>().swap(slots_);
}

Eigen::Array3i PointIndex::keyAxes(std::int64_t key)
{
  constexpr std::int64_t kMask = (std::int64_t(1) << 21) - 1;
  return {static_cast<int>(key >> 42), static_cast<int>((key >> 21) & kMask),
          static_cast<int>(key & kMask)};
}

std::size_t PointIndex::directoryIndex(const Eigen::Array3i& axes) const
{
  const Eigen::Array3i c = axes - directory_low_;
  return (static_cast<std::size_t>(c.x()) *
              static_cast<std::size_t>(directory_dims_.y()) +
          static_cast<std::size_t>(c.y())) *
             static_cast<std::size_t>(directory_dims_.z()) +
         static_cast<std::size_t>(c.z());
}

std::size_t PointIndex::insert(std::int64_t key)
{
  if (4 * (used_ + 1) > slots_.size()) {
    std::vector<Cell> old(2 * slots_.size());
    old.swap(slots_);
    --slot_shift_;
    for (const Cell& cell : old) {
      if (cell.key == kEmptyKey)
        continue;
      std::size_t i = slotOf(cell.key);
      while (slots_[i].key != kEmptyKey)
        i = (i + 1) & (slots_.size() - 1);
      slots_[i] = cell;
    }
  }
  std::size_t i = slotOf(key);
  while (slots_[i].key != key) {
    if (slots_[i].key == kEmptyKey) {
      slots_[i].key = key;
      ++used_;
      return i;
    }
    i = (i + 1) & (slots_.size() - 1);
  }
  return i;
}

const PointIndex::Cell* PointIndex::find(std::int64_t key) const
{
  if (!directory_.empty()) {
    const Eigen::Array3i axes = keyAxes(key);
    if ((axes < directory_low_).any() ||
        (axes >= directory_low_ + directory_dims_).any())
      return nullptr;
    const std::int32_t c = directory_[directoryIndex(axes)];
    return c < 0 ? nullptr : &cells_[static_cast<std::size_t>(c)];
  }
  std::size_t i = slotOf(key);
  while (slots_[i].key != key) {
    if (slots_[i].key == kEmptyKey)
      return nullptr;
    i = (i + 1) & (slots_.size() - 1);
  }
  return &slots_[i];
}

double PointIndex::nearestSquaredDistance(const Eigen::Vector3d& q,
                                          const Eigen::Vector3d& normal,
                                          double min_cosine) const
{
  const Eigen::Index k = nearest(q, normal, min_cosine);
  return k < 0 ? std::numeric_limits<double>::infinity()
               : (points_.col(k) - q).squaredNorm();
}

Eigen::Index PointIndex::nearest(const Eigen::Vector3d& q,
                                 const Eigen::Vector3d& normal, double min_cosine) const
{
  std::int64_t key = 0;
  if (points_.cols() == 0 || !voxelKey(q, radius_, key))
    return -1;
  // Squared gaps from q to the faces of its cell, per axis and offset -1, 0, 1: a
  // neighbor cell's points lie at least the sum over its axes away. Slightly shrunk,
  // so rounding never skips a cell that holds a candidate.
  const Eigen::Array3d below = q.array() - (q.array() / radius_).floor() * radius_;
  double gap2[3][3];
  for (int a = 0; a < 3; ++a) {
    const double low = std::max(0.0, below[a] * (1.0 - 1e-9));
    const double high = std::max(0.0, (radius_ - below[a]) * (1.0 - 1e-9));
    gap2[a][0] = low * low;
    gap2[a][1] = 0.0;
    gap2[a][2] = high * high;
  }
  double best = radius_ * radius_;
  Eigen::Index found = -1;
  // The own cell first, then the nearest slab and row first: near points bound the
  // search early, and a slab or row beyond the bound is skipped whole.
  const Cell* own = find(key);
  if (own == nullptr)
    return -1; // no cell around q holds points
  scanCell(*own, q, normal, min_cosine, best, found);
  constexpr int kOrder[3] = {0, -1, 1};
  for (const int dx : kOrder) {
    const double gx = gap2[0][dx + 1];
    if (gx > best)
      continue;
    for (const int dy : kOrder) {
      const double gxy = gx + gap2[1][dy + 1];
      if (gxy > best)
        continue;
      for (const int dz : kOrder)
        if ((dx != 0 || dy != 0 || dz != 0) &&
            (own->occupied & neighborBit(dx, dy, dz)) && gxy + gap2[2][dz + 1] <= best)
          scanCell(*find(offsetKey(key, dx, dy, dz)), q, normal, min_cosine, best,
                   found);
    }
  }
  return found;
}

std::size_t PointIndex::slotOf(std::int64_t key) const
{
  // Fibonacci hashing: the top bits of the product depend on every bit of the key.
  return static_cast<std::size_t>(
      (static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> slot_shift_);
}

void PointIndex::scanCell(const Cell& cell, const Eigen::Vector3d& q,
                          const Eigen::Vector3d& normal, double min_cosine,
                          double& best, Eigen::Index& found) const
{
  // In chunks: the squared distances (+infinity where the normal disagrees) in a loop
  // the compiler vectorizes, then the nearest in point order (the last of equals, as a
  // plain scan), with the same arithmetic as (p - q).squaredNorm() and n.dot(normal).
  constexpr Eigen::Index kChunk = 64;
  const bool check = normals_.cols() != 0 && !normal.isZero();
  const double* x = points_.row(0).data();
  const double* y = points_.row(1).data();
  const double* z = points_.row(2).data();
  const double qx = q.x(), qy = q.y(), qz = q.z();
  const double infinity = std::numeric_limits<double>::infinity();
  double d2[kChunk];
  for (Eigen::Index base = cell.first; base < cell.last; base += kChunk) {
    const Eigen::Index m = std::min(kChunk, cell.last - base);
    squaredDistances(x + base, y + base, z + base, m, qx, qy, qz, d2);
    if (check) {
      const double* nx = normals_.row(0).data();
      const double* ny = normals_.row(1).data();
      const double* nz = normals_.row(2).data();
      const char* has = has_normal_.data();
      for (Eigen::Index j = 0; j < m; ++j) {
        const Eigen::Index k = base + j;
        const double dot = nx[k] * normal.x() + ny[k] * normal.y() + nz[k] * normal.z();
        d2[j] = has[k] && dot < min_cosine ? infinity : d2[j];
      }
    }
    for (Eigen::Index j = 0; j < m; ++j)
      if (d2[j] <= best) {
        best = d2[j];
        found = base + j;
      }
  }
}

} // namespace pcl::phaser
