#!/usr/bin/python3
"""Runs SPARQL queries in `geotex query` and in two independent SPARQL 1.1 engines over the
same RDF files, and checks that all give the same rows:

    tests/query_engines.py [--engine rdflib|oxigraph ...] [--unordered QUERY:COLUMN:SEP ...]
                           --query QUERY.rq [--query ...] GEOTEX DATA.ttl ...

rdflib is Debian's python3-rdflib (this script runs under /usr/bin/python3 to see it);
Oxigraph is the npm package pinned in tests/js (tests/js/sparql_query.mjs; `npm ci` in
tests/js first). The data is the union of the files as a set, as `geotex query` reads it.

Rows compare in order when the query has ORDER BY (the shipped queries order by unique
keys), else as multisets. Cells: numbers of any XSD numeric type compare as numbers, with
a relative tolerance of 1e-12 (an AVG sums in another order: a few units in the last place);
a plain literal equals the same text typed xsd:string; blank nodes match any blank node.
--unordered QUERY:COLUMN:SEP compares the SEP-separated parts of COLUMN as a multiset, for
a GROUP_CONCAT whose order SPARQL leaves open. Exit 0 when every engine gives the rows of
`geotex query` for every query; else prints the differences and exits 1.
"""
import argparse
import json
import os
import subprocess
import sys

from sparql_results import geotex_results, multiset_difference, parse_unordered, rows_of, same_row

# An AVG sums in another order in each engine: a few units in the last place.
REL_TOL, ABS_TOL = 1e-12, 1e-300

HERE = os.path.dirname(os.path.abspath(__file__))
FORMATS = {".ttl": "turtle", ".nt": "nt", ".nq": "nquads", ".rdf": "xml"}


def rdflib_results(query_file, data):
    import rdflib  # Debian's python3-rdflib, seen by /usr/bin/python3
    graph = rdflib.Graph()
    for f in data:
        graph.parse(f, format=FORMATS[os.path.splitext(f)[1].lower()])
    result = graph.query(open(query_file, encoding="utf-8").read())
    return json.loads(result.serialize(format="json"))


def oxigraph_results(query_file, data):
    out = subprocess.run(["node", os.path.join(HERE, "js", "sparql_query.mjs"), query_file, *data],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


ENGINES = {"rdflib": rdflib_results, "oxigraph": oxigraph_results}


def rdflib_empty_group(engine, query_text, local_rows, other_rows):
    """rdflib 6.1.1 answers a GROUP BY over no solution with one row whose keys are unbound
    (SPARQL: no row; Oxigraph and `geotex query`: no row)."""
    return (engine == "rdflib" and "GROUP BY" in query_text.upper() and not local_rows and
            len(other_rows) == 1 and all(c[0] in ("unbound", "number") for c in other_rows[0]))


def compare(engine, query_file, local, other, unordered):
    query_text = open(query_file, encoding="utf-8").read()
    ordered = "ORDER BY" in query_text.upper()
    local_cols, local_rows = rows_of(local, unordered)
    other_cols, other_rows = rows_of(other, unordered)
    name = os.path.basename(query_file)
    if rdflib_empty_group(engine, query_text, local_rows, other_rows):
        print(f"{name}: rdflib: one row of unbound keys for a GROUP BY over nothing (its bug "
              "in 6.1.1), where geotex query has no row, the same")
        return True
    problems = []
    if local_cols != other_cols:
        problems.append(f"columns differ: {engine} {other_cols}, geotex {local_cols}")
    if ordered:
        if len(local_rows) != len(other_rows) or not all(
                same_row(a, b, REL_TOL, ABS_TOL) for a, b in zip(local_rows, other_rows)):
            problems.append(f"{len(other_rows)} rows in {engine}, {len(local_rows)} from geotex query (in order)")
            for i, (a, b) in enumerate(zip(local_rows, other_rows)):
                if not same_row(a, b, REL_TOL, ABS_TOL):
                    problems += [f"  first difference at row {i + 1}:", f"    {engine}: {b}", f"    geotex: {a}"]
                    break
    else:
        extra, unmatched = multiset_difference(other_rows, local_rows, REL_TOL, ABS_TOL)
        if extra or unmatched:
            problems.append(f"{len(other_rows)} rows in {engine}, {len(local_rows)} from geotex query")
            problems += [f"  only in {engine}: {r}" for r in extra[:10]]
            problems += [f"  only in geotex query: {r}" for r in unmatched[:10]]
    if problems:
        print(f"{name}: {engine} differs", *problems, sep="\n")
        return False
    print(f"{name}: {engine}: {len(other_rows)} rows, the same")
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--engine", action="append", choices=sorted(ENGINES))
    ap.add_argument("--unordered", action="append", default=[], metavar="QUERY:COLUMN:SEP")
    ap.add_argument("--query", action="append", required=True)
    ap.add_argument("geotex")
    ap.add_argument("data", nargs="+")
    a = ap.parse_args()
    unordered = parse_unordered(a.unordered)
    ok = True
    for q in a.query:
        local = geotex_results(a.geotex, q, a.data)
        for engine in a.engine or sorted(ENGINES):
            try:
                other = ENGINES[engine](q, a.data)
            except Exception as e:  # a parse or query error in the engine is a difference
                print(f"{os.path.basename(q)}: {engine} failed: {e}")
                ok = False
                continue
            ok = compare(engine, q, local, other, unordered.get(os.path.basename(q), {})) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
