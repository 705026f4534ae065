// A SPARQL query in Oxigraph (a SPARQL 1.1 store in memory), for comparing its rows with
// `geotex query`'s (tests/query_engines.py):
//   node sparql_query.mjs QUERY.rq DATA.ttl [MORE.ttl|.nt|.nq|.rdf ...]
// The data is the union of the files as one default graph (N-Quads graphs ignored), as
// `geotex query` reads them. Prints the SPARQL 1.1 results JSON on stdout.
// Exit status: 0 answered, 2 a usage, parse or query error (message on stderr).

import { readFileSync } from 'node:fs';
import { extname } from 'node:path';
import { pathToFileURL } from 'node:url';

import oxigraph from 'oxigraph';

const formats = {
    '.ttl': 'text/turtle',
    '.nt': 'application/n-triples',
    '.nq': 'application/n-quads',
    '.rdf': 'application/rdf+xml',
};

function main() {
    const [queryFile, ...dataFiles] = process.argv.slice(2);
    if (!queryFile || dataFiles.length === 0) {
        console.error('usage: node sparql_query.mjs QUERY.rq DATA.ttl [MORE ...]');
        process.exit(2);
    }
    const store = new oxigraph.Store();
    for (const file of dataFiles) {
        const format = formats[extname(file).toLowerCase()];
        if (!format) {
            console.error(`oxigraph: ${file}: unknown RDF syntax`);
            process.exit(2);
        }
        try {
            const text = readFileSync(file, 'utf8');
            const base_iri = pathToFileURL(file).href;
            if (format === 'application/n-quads') {
                // Into the default graph one by one: the graphs of N-Quads are dropped.
                for (const q of oxigraph.parse(text, { format, base_iri }))
                    store.add(oxigraph.quad(q.subject, q.predicate, q.object, oxigraph.defaultGraph()));
            } else {
                // Triples go to the default graph; the store is a set.
                store.load(text, { format, base_iri });
            }
        } catch (e) {
            console.error(`oxigraph: ${file}: ${e.message ?? e}`);
            process.exit(2);
        }
    }
    try {
        const query = readFileSync(queryFile, 'utf8');
        process.stdout.write(store.query(query, { results_format: 'application/sparql-results+json' }));
    } catch (e) {
        console.error(`oxigraph: ${queryFile}: ${e.message ?? e}`);
        process.exit(2);
    }
}

main();
