#pragma once
// Disjoint sets over 0..n-1 whose root is always the smallest index of its set, so that
// the sets (and anything numbered by root) do not depend on the order of the unions.

#include <algorithm>
#include <numeric>
#include <vector>

namespace geotex::detail {

struct UnionFind {
    std::vector<int> parent;

    explicit UnionFind(int n) : parent(static_cast<std::size_t>(n)) {
        std::iota(parent.begin(), parent.end(), 0);
    }

    int find(int x) {
        while (parent[x] != x) {
            parent[x] = parent[parent[x]];  // path halving
            x = parent[x];
        }
        return x;
    }

    /// Joins the sets of a and b; false when they were one set already.
    bool unite(int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent[std::max(a, b)] = std::min(a, b);
        return true;
    }
};

}  // namespace geotex::detail
