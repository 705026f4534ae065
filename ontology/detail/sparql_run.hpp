#pragma once
// run_sparql over data that comes from elsewhere than files (the fuzz target builds a small
// store in memory).

#include <functional>
#include <string>

#include "ontology/detail/query_deadline.hpp"
#include "ontology/detail/triple_store.hpp"
#include "ontology/sparql.hpp"

namespace geotex::detail {

/// Fills a store (and finishes it) for run_sparql_with; may throw.
using DataLoader = std::function<void(TripleStore& store, const Deadline& deadline)>;

/// run_sparql with the data from `load`, called once the query has passed its checks.
QueryResult run_sparql_with(const std::string& query, const DataLoader& load,
                            const QueryParams& params = {});

}  // namespace geotex::detail
