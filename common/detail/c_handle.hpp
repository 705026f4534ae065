#pragma once
// Owning handles for the objects of C libraries (Raptor, Rasqal, libcurl): a unique_ptr
// whose deleter calls the library's own free function, skipping null.

#include <memory>

namespace geotex::detail {

template <auto Free>
struct CDeleter {
    template <class T>
    void operator()(T* p) const {
        if (p) Free(p);
    }
};

template <class T, auto Free>
using CHandle = std::unique_ptr<T, CDeleter<Free>>;

}  // namespace geotex::detail
