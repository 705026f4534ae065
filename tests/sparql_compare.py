#!/usr/bin/env python3
"""Runs SPARQL queries in a triple store (SPARQL 1.1 protocol, JSON results) and in
`geotex query` over RDF files, and checks that both give the same rows:

    tests/sparql_compare.py --sparql URL [--graph IRI ...] [--unordered QUERY:COLUMN:SEP ...]
                            --query QUERY.rq [--query ...] GEOTEX DATA.ttl ...

--graph: the store's default graph is the merge of these graphs (default-graph-uri);
without, the store's own default graph. Rows are compared as multisets (ORDER BY ties may
come in any order). Each cell is normalised: numbers (any XSD numeric type, or a literal
that the other side has as a number) compare with a relative tolerance of 1e-5 because
Virtuoso prints doubles with 6 significant digits in every result format (it stores them
exactly); a plain literal equals the same text typed xsd:string; blank nodes match any
blank node. --unordered QUERY:COLUMN:SEP compares the SEP-separated parts of COLUMN of
the query file named QUERY as a multiset, for a GROUP_CONCAT whose order SPARQL leaves open.
Exit 0 when every query gives the same rows; else prints the differences and exits 1.
"""
import argparse
import json
import os
import sys
import urllib.parse
import urllib.request

from sparql_results import geotex_results, multiset_difference, parse_unordered, rows_of

# Virtuoso prints doubles with 6 significant digits in every result format.
REL_TOL, ABS_TOL = 1e-5, 1e-12

def store_results(url, query, graphs):
    fields = [("query", query)] + [("default-graph-uri", g) for g in graphs]
    request = urllib.request.Request(url, data=urllib.parse.urlencode(fields).encode(),
                                     headers={"Accept": "application/sparql-results+json"})
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            text = answer.read().decode("utf-8")
    except urllib.error.HTTPError as e:
        sys.exit(f"store: HTTP {e.code}: {e.read().decode('utf-8', 'replace')[:600]}")
    results = json.loads(text)
    # Virtuoso answers with the SPARQL 1.0 JSON form: "typed-literal" is a literal.
    for b in results.get("results", {}).get("bindings", []):
        for v in b.values():
            if v["type"] == "typed-literal":
                v["type"] = "literal"
    return results


def compare(a, query_file, unordered):
    query = open(query_file, encoding="utf-8").read()
    store_cols, store_rows = rows_of(store_results(a.sparql, query, a.graph), unordered)
    local_cols, local_rows = rows_of(geotex_results(a.geotex, query_file, a.data), unordered)

    problems = []
    if store_cols != local_cols:
        problems.append(f"columns differ: store {store_cols}, geotex {local_cols}")
    extra, unmatched = multiset_difference(store_rows, local_rows, REL_TOL, ABS_TOL)
    if extra or unmatched:
        problems.append(f"{len(store_rows)} rows in the store, {len(local_rows)} from geotex query")
        problems += [f"  only in the store: {r}" for r in extra[:10]]
        problems += [f"  only in geotex query: {r}" for r in unmatched[:10]]
    where = f"{os.path.basename(query_file)} on {' '.join(a.graph) or 'the default graph'}"
    if problems:
        print(f"{where}: results differ", *problems, sep="\n")
        return False
    print(f"{where}: {len(store_rows)} rows, the same")
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sparql", required=True)
    ap.add_argument("--graph", action="append", default=[])
    ap.add_argument("--unordered", action="append", default=[], metavar="QUERY:COLUMN:SEP")
    ap.add_argument("--query", action="append", required=True)
    ap.add_argument("geotex")
    ap.add_argument("data", nargs="+")
    a = ap.parse_args()
    unordered = parse_unordered(a.unordered)
    ok = True
    for q in a.query:
        ok = compare(a, q, unordered.get(os.path.basename(q), {})) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
