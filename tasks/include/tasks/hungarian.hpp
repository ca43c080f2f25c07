#pragma once
// Min-cost assignment (Hungarian method with potentials, Kuhn-Munkres / Jonker-Volgenant
// shortest augmenting paths): O(n^2 m) for an n x m matrix with n <= m. Debian packages no
// C++ assignment solver (only python3-munkres and a Perl module), hence this one; it is
// tested against brute force.
#include <cstdint>
#include <vector>

namespace tasks {

// `cost` is row-major rows x cols. Returns the column of each row (-1 for the rows left
// over when rows > cols) such that every column is used at most once, as many rows as
// possible are matched, and the total cost is minimal.
std::vector<int> min_cost_assignment(int rows, int cols, const std::vector<int64_t>& cost);

}  // namespace tasks
