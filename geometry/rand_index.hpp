#pragma once
/// Adjusted Rand index between two partitions, to compare a clustering with a reference.

#include <vector>

namespace geotex {

/// Adjusted Rand index of Hubert & Arabie ("Comparing partitions", J. Classification 2,
/// 1985) between the partitions given by `a` and `b` (one label per item, item i in both;
/// labels are arbitrary ints, possibly negative: only equality matters). At most 1, and 1
/// exactly when the partitions are identical up to renaming; about 0 for independent
/// partitions; negative when they agree less than chance.
/// When both partitions are a single group, or both are all singletons (this includes
/// fewer than 2 items), the index is 0/0; the partitions are then identical and the value
/// is defined as 1.
/// Throws InvalidInput when `a` and `b` differ in size.
double adjusted_rand_index(const std::vector<int>& a, const std::vector<int>& b);

}  // namespace geotex
