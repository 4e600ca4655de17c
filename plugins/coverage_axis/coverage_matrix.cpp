#include "coverage_matrix.hpp"

#include <medax/services/kdtree.hpp>

#include <algorithm>

namespace medax::coverage_axis {

std::vector<std::vector<Index>> row_columns(const SetCover& cover) {
  std::vector<std::vector<Index>> rows(cover.rows);
  for (Index j = 0; j < cover.columns.size(); ++j)
    for (Index r : cover.columns[j]) rows[r].push_back(j);
  return rows;
}

bool covers_all(const SetCover& cover, const std::vector<Index>& chosen) {
  std::vector<char> hit(cover.rows, 0);
  for (Index j : chosen)
    for (Index r : cover.columns.at(j)) hit[r] = 1;
  return std::all_of(hit.begin(), hit.end(), [](char h) { return h != 0; });
}

namespace {

/// The samples strictly inside each dilated ball (sample indices, ascending).
std::vector<std::vector<Index>> samples_in_balls(const std::vector<Vec3>& samples, const Balls& balls,
                                                 double dilation) {
  const services::PointIndex index(samples);
  std::vector<std::vector<Index>> inside(balls.centres.size());
  for (std::size_t i = 0; i < balls.centres.size(); ++i) {
    const double reach = balls.radii[i] + dilation;
    for (const auto& [j, d] : index.within(balls.centres[i], reach))
      if (d < reach) inside[i].push_back(j);
    std::sort(inside[i].begin(), inside[i].end());
  }
  return inside;
}

}  // namespace

CoverageMatrix coverage_matrix(const std::vector<Vec3>& samples, const Balls& candidates, double dilation) {
  CoverageMatrix m;
  std::vector<std::vector<Index>> inside = samples_in_balls(samples, candidates, dilation);
  std::vector<Index> row_of(samples.size(), 0);
  std::vector<char> covered(samples.size(), 0);
  for (const auto& column : inside)
    for (Index j : column) covered[j] = 1;
  for (Index j = 0; j < samples.size(); ++j) {
    if (!covered[j]) {
      ++m.uncoverable;
      continue;
    }
    row_of[j] = static_cast<Index>(m.covered_samples.size());
    m.covered_samples.push_back(j);
  }
  m.cover.rows = m.covered_samples.size();
  for (auto& column : inside)
    for (Index& j : column) j = row_of[j];
  m.cover.columns = std::move(inside);
  return m;
}

}  // namespace medax::coverage_axis
