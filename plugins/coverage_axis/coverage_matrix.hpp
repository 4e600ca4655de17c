#pragma once
// The set-cover instance of Coverage Axis: which dilated candidate ball covers which surface
// sample (Dou et al. 2022, the matrix D).
#include <medax/geometry.hpp>

#include <cstddef>
#include <vector>

namespace medax::coverage_axis {

/// Candidate inner balls: centres and undilated radii.
struct Balls {
  std::vector<Vec3> centres;
  std::vector<double> radii;
};

/// A set-cover instance: column j covers the rows listed in columns[j] (sorted, distinct).
struct SetCover {
  std::size_t rows = 0;
  std::vector<std::vector<Index>> columns;
};

/// For each row, the columns that cover it (ascending).
std::vector<std::vector<Index>> row_columns(const SetCover& cover);

/// True when the chosen columns cover every row.
bool covers_all(const SetCover& cover, const std::vector<Index>& chosen);

/// The coverage matrix with the uncoverable samples dropped.
struct CoverageMatrix {
  SetCover cover;                    ///< row k = sample covered_samples[k]; column i = candidate i
  std::vector<Index> covered_samples;  ///< samples some dilated ball covers, ascending
  std::size_t uncoverable = 0;       ///< samples no dilated ball covers (dropped)
};

/// Column i covers sample j iff ‖s_j − c_i‖ < r_i + dilation (strict, as the authors' code).
CoverageMatrix coverage_matrix(const std::vector<Vec3>& samples, const Balls& candidates, double dilation);

}  // namespace medax::coverage_axis
