// Independent check of geotex RDF (called by tests/rdf_peer_check.sh):
//   node validate.mjs DATA.ttl SHAPES.ttl [MORE_DATA.ttl ...]
// Parses every file as strict Turtle with N3.js (errors carry the line), prints the number
// of distinct triples of DATA.ttl as "n3-triples=<N>", then validates DATA.ttl (merged with
// MORE_DATA.ttl, e.g. ontology/geotex.ttl) against SHAPES.ttl with rdf-validate-shacl.
// Exit status: 0 conforms, 1 a violation, 2 a parse or usage error.

import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

import rdfDataset from '@rdfjs/dataset';
import N3 from 'n3';
import SHACLValidator from 'rdf-validate-shacl';

function parseTurtle(file) {
    let text;
    try {
        text = readFileSync(file, 'utf8');
    } catch (e) {
        console.error(`N3.js: ${file}: cannot read: ${e.message}`);
        process.exit(2);
    }
    // format 'text/turtle' makes N3.js strict: no N3 or TriG extensions.
    const parser = new N3.Parser({ format: 'text/turtle', baseIRI: pathToFileURL(file).href });
    try {
        return parser.parse(text);
    } catch (e) {
        console.error(`N3.js: ${file}: ${e.message}`);
        process.exit(2);
    }
}

function term(t) {
    if (!t) return '';
    if (t.termType === 'NamedNode') return `<${t.value}>`;
    if (t.termType === 'Literal') return JSON.stringify(t.value);
    return `_:${t.value}`;
}

async function main() {
    const [dataFile, shapesFile, ...moreFiles] = process.argv.slice(2);
    if (!dataFile || !shapesFile) {
        console.error('usage: node validate.mjs DATA.ttl SHAPES.ttl [MORE_DATA.ttl ...]');
        process.exit(2);
    }
    const data = parseTurtle(dataFile);
    const distinct = rdfDataset.dataset(data);
    const blank = data.filter((q) => q.subject.termType === 'BlankNode' || q.object.termType === 'BlankNode').length;
    console.log(`n3-triples=${distinct.size}`);
    if (distinct.size !== data.length)
        console.log(`N3.js: ${dataFile}: ${data.length - distinct.size} duplicate triples`);
    console.log(`N3.js: ${dataFile}: ${distinct.size} triples, ${blank} with a blank node`);

    const shapes = parseTurtle(shapesFile);
    console.log(`N3.js: ${shapesFile}: ${shapes.length} triples`);
    for (const file of moreFiles) {
        const extra = parseTurtle(file);
        for (const q of extra) distinct.add(q);
        console.log(`N3.js: ${file}: ${extra.length} triples (merged into the data graph)`);
    }

    const validator = new SHACLValidator(rdfDataset.dataset(shapes));
    const report = await validator.validate(distinct);
    if (report.conforms) {
        console.log(`rdf-validate-shacl: ${dataFile} conforms to ${shapesFile}`);
        return;
    }
    const results = report.results;
    console.error(`rdf-validate-shacl: ${dataFile} does not conform to ${shapesFile}: ${results.length} results`);
    for (const r of results.slice(0, 50)) {
        const messages = r.message.map((m) => m.value).join('; ');
        console.error(`  focus ${term(r.focusNode)} path ${term(r.path)} value ${term(r.value)}: ` +
                      `${messages} [${term(r.sourceConstraintComponent)}]`);
    }
    if (results.length > 50) console.error(`  ... and ${results.length - 50} more`);
    process.exit(1);
}

main().catch((e) => {
    console.error(`validate.mjs: ${e.stack || e}`);
    process.exit(2);
});
