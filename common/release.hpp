#pragma once
/// Giving a container's memory back before a step that needs it elsewhere.

namespace geotex {

/// Empties `c` and frees its memory. `c = {}` does not do that for a std::vector: it is the
/// initializer-list assignment, which keeps the capacity, so a large scan's array released that
/// way stays held.
template <class Container>
void release(Container& c) {
    Container().swap(c);
}

}  // namespace geotex
