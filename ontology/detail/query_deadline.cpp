#include "ontology/detail/query_deadline.hpp"

#include <cstdio>
#include <string>

#include "ontology/sparql.hpp"

namespace geotex::detail {

void Deadline::throw_timeout() const {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", seconds_);
    throw QueryTimeout(std::string("the query ran out of time: its limit of ") + seconds +
                       " s passed before it finished; no result is written");
}

}  // namespace geotex::detail
