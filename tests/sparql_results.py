"""SPARQL 1.1 JSON results made comparable across engines, shared by tests/query_engines.py
(geotex query against rdflib and Oxigraph) and tests/sparql_compare.py (against a triple
store).

Each cell is normalised: numbers of any XSD numeric type become floats (compared with a
tolerance the caller gives), a plain literal equals the same text typed xsd:string (the
datatype is dropped, the language tag kept in lower case), every blank node equals every
other, and a column named in `unordered` (column -> separator) becomes the sorted multiset
of its separated parts, for a GROUP_CONCAT whose order SPARQL leaves open.
"""
import json
import math
import subprocess

XSD = "http://www.w3.org/2001/XMLSchema#"
NUMERIC = {XSD + t for t in ("integer", "decimal", "double", "float", "int", "long", "short", "byte",
                             "nonNegativeInteger", "positiveInteger", "negativeInteger",
                             "nonPositiveInteger", "unsignedInt", "unsignedLong", "unsignedShort",
                             "unsignedByte")}


def cell(binding, column, unordered):
    """A comparable form of one cell."""
    if binding is None:
        return ("unbound",)
    kind = binding["type"]
    value = binding["value"]
    if kind == "uri":
        return ("uri", value)
    if kind == "bnode":
        return ("bnode",)
    datatype = binding.get("datatype", "")
    if datatype in NUMERIC:
        return ("number", float(value))
    if column in unordered:
        return ("parts", tuple(sorted(value.split(unordered[column]))) if value else ())
    return ("literal", value, binding.get("xml:lang", "").lower())


def rows_of(results, unordered):
    """(columns, rows) of a SELECT's or an ASK's results; rows are tuples of cells."""
    if "boolean" in results:
        return ["boolean"], [(("literal", str(results["boolean"]).lower(), ""),)]
    columns = results["head"]["vars"]
    return columns, [tuple(cell(b.get(c), c, unordered) for c in columns)
                     for b in results["results"]["bindings"]]


def same_row(a, b, rel_tol, abs_tol):
    """Whether two rows are equal, numbers within the tolerance."""
    def same(x, y):
        if x[0] == "number" and y[0] == "number":
            return math.isclose(x[1], y[1], rel_tol=rel_tol, abs_tol=abs_tol)
        return x == y
    return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))


def multiset_difference(first, second, rel_tol, abs_tol):
    """The rows of `first` that `second` lacks and those of `second` that `first` lacks,
    as multisets."""
    unmatched = list(second)
    extra = []
    for row in first:
        for i, other in enumerate(unmatched):
            if same_row(row, other, rel_tol, abs_tol):
                del unmatched[i]
                break
        else:
            extra.append(row)
    return extra, unmatched


def parse_unordered(options):
    """QUERY:COLUMN:SEP options as {query file name: {column: separator}}."""
    unordered = {}
    for u in options:
        name, column, sep = u.split(":", 2)
        unordered.setdefault(name, {})[column] = sep
    return unordered


def geotex_results(geotex, query_file, data):
    """The JSON results of `geotex query`."""
    out = subprocess.run([geotex, "query", query_file, *data, "--format", "json"], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)
