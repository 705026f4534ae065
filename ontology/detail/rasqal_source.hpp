#pragma once
// Rasqal's triple patterns answered from a TripleStore (ontology/detail/triple_store.hpp)
// instead of Rasqal's own store, a list that every triple pattern scans from the start.
// Include only from .cpp files: it brings in rasqal.h.

#include <rasqal.h>

#include <string>
#include <unordered_map>
#include <vector>

#include "ontology/detail/triple_store.hpp"

namespace geotex::detail {

class RasqalTripleSource {
  public:
    /// `world` must be open and outlive this object; `store` must be finished and outlive it.
    RasqalTripleSource(rasqal_world* world, const TripleStore& store);
    ~RasqalTripleSource();
    RasqalTripleSource(const RasqalTripleSource&) = delete;
    RasqalTripleSource& operator=(const RasqalTripleSource&) = delete;

    /// Makes every query of the world match its triple patterns against the store. Returns
    /// false when Rasqal refuses the factory.
    bool attach();

    /// The term as a Rasqal literal (made once, owned here), or nullptr when out of memory.
    rasqal_literal* literal(TripleStore::TermId id);
    /// The store's id of a literal's term, or TripleStore::kAny when the data lacks it.
    TripleStore::TermId id_of(rasqal_literal* value) const;

    const TripleStore& store() const { return store_; }
    rasqal_world* world() const { return world_; }

  private:
    rasqal_world* world_;
    const TripleStore& store_;
    std::vector<rasqal_literal*> literals_;  // #terms, nullptr until asked for
    std::unordered_map<const rasqal_literal*, TripleStore::TermId> ids_;  // of literals_
    mutable std::string key_;                                            // scratch of id_of
};

}  // namespace geotex::detail
