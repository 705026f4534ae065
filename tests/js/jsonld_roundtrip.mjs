// Independent round trip of `geotex annotate --jsonld` (called by tests/annotate_test.sh):
//   node jsonld_roundtrip.mjs ANNOTATIONS.jsonld ANNOTATION.ttl
// Both files must come from the same run. The JSON-LD is converted to RDF by the `jsonld`
// package in safe mode (a key or value that the context does not map is an error, not a
// silent drop), with an offline document loader: the W3C Web Annotation context comes from
// anno-context.jsonld beside this script (the whole context of the W3C Recommendation, so
// that every term geotex writes is read as Web Annotation clients read it), and any other
// URL is refused, so nothing is fetched. The Turtle is parsed by N3.js. Checks:
//   1. the page: one as:OrderedCollectionPage whose as:items list holds every annotation,
//      in the order of their numbers; it and its list nodes are the only triples that the
//      Turtle lacks, and the only blank nodes;
//   2. every other triple of the JSON-LD is in the Turtle (same IRIs, same literals);
//   3. the JSON-LD has exactly the oa:Annotation nodes of the Turtle (those of the textures by
//      number, then those of the texels by texel number), each with the same oa:hasBody,
//      oa:hasTarget and score (gtx:stability, gtx:agreement); every target with its
//      oa:hasSource, and its selector (a texel) or its gtx:hasTexel texels, each with its
//      oa:hasSource and selector (a texture).
// Prints a summary line "jsonld-roundtrip: OK: ..."; exit status 0 when every check passes,
// 1 when one fails, 2 on a usage or parse error.

import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import jsonld from 'jsonld';
import N3 from 'n3';

const RDF = 'http://www.w3.org/1999/02/22-rdf-syntax-ns#';
const OA = 'http://www.w3.org/ns/oa#';
const AS = 'http://www.w3.org/ns/activitystreams#';
const GTX = 'https://w3id.org/geotex/ns#';
const ANNO_CONTEXT = 'http://www.w3.org/ns/anno.jsonld';

const here = dirname(fileURLToPath(import.meta.url));
const annoContext = JSON.parse(readFileSync(join(here, 'anno-context.jsonld'), 'utf8'));

async function offlineLoader(url) {
    // The W3C serves the same context over https; either name maps to the fixture.
    if (url === ANNO_CONTEXT || url === ANNO_CONTEXT.replace('http:', 'https:'))
        return { contextUrl: null, documentUrl: url, document: annoContext };
    throw new Error(`offline document loader: refusing to fetch ${url}`);
}

function usage(message) {
    console.error(`jsonld_roundtrip: ${message}`);
    process.exit(2);
}

const XSD_DOUBLE = 'http://www.w3.org/2001/XMLSchema#double';

// One text per term, so that triples compare as strings. Language tags are compared in
// lower case: both jsonld and N3.js lower them, and RDF treats them case-insensitively. An
// xsd:double compares by its value: the jsonld package rewrites every xsd:double to its own
// form (toExponential(15): "9.4E-1" becomes "9.399999999999999E-1", the same double).
function termKey(t) {
    switch (t.termType) {
        case 'NamedNode': return `<${t.value}>`;
        case 'BlankNode': return `_:${t.value}`;
        case 'Literal':
            if (t.language) return `${JSON.stringify(t.value)}@${t.language.toLowerCase()}`;
            if (t.datatype.value === XSD_DOUBLE && Number.isFinite(Number(t.value)))
                return `${Number(t.value)}^^<${XSD_DOUBLE}>`;
            return `${JSON.stringify(t.value)}^^<${t.datatype.value}>`;
        default: return `?${t.termType}:${t.value}`;
    }
}
const tripleKey = (q) => `${termKey(q.subject)} ${termKey(q.predicate)} ${termKey(q.object)}`;

function objectsOf(quads, subject, predicate) {
    return new Set(quads.filter((q) => q.subject.value === subject && q.predicate.value === predicate)
        .map((q) => termKey(q.object)));
}

const sameSet = (a, b) => a.size === b.size && [...a].every((x) => b.has(x));
const show = (s) => `{${[...s].sort().join(', ')}}`;

async function main() {
    const [jsonldFile, turtleFile] = process.argv.slice(2);
    if (!jsonldFile || !turtleFile) usage('usage: node jsonld_roundtrip.mjs ANNOTATIONS.jsonld ANNOTATION.ttl');
    let doc, turtle;
    try {
        doc = JSON.parse(readFileSync(jsonldFile, 'utf8'));
        turtle = new N3.Parser({ format: 'text/turtle' }).parse(readFileSync(turtleFile, 'utf8'));
    } catch (e) {
        usage(`cannot read the inputs: ${e.message}`);
    }
    let quads;
    try {
        quads = await jsonld.toRDF(doc, { documentLoader: offlineLoader, safe: true });
    } catch (e) {
        console.error(`jsonld_roundtrip: ${jsonldFile}: JSON-LD to RDF failed: ${e.message}` +
                      (e.details ? ` ${JSON.stringify(e.details).slice(0, 500)}` : ''));
        process.exit(1);
    }
    const failures = [];
    const fail = (what) => failures.push(what);

    // 1. The page and its list.
    const pages = quads.filter((q) => q.predicate.value === `${RDF}type` &&
                                      q.object.value === `${AS}OrderedCollectionPage`);
    if (pages.length !== 1) fail(`expected one AnnotationPage, found ${pages.length}`);
    const page = pages.length ? pages[0].subject.value : '';
    const pageKeys = new Set();
    const listed = [];
    for (const q of quads) if (q.subject.value === page) pageKeys.add(tripleKey(q));
    const heads = quads.filter((q) => q.subject.value === page && q.predicate.value === `${AS}items`);
    if (heads.length !== 1) fail(`the page has ${heads.length} as:items, not 1`);
    let node = heads.length ? heads[0].object : null;
    const seen = new Set();
    while (node && node.termType === 'BlankNode' && !seen.has(node.value)) {
        seen.add(node.value);
        const from = quads.filter((q) => q.subject.termType === 'BlankNode' && q.subject.value === node.value);
        for (const q of from) pageKeys.add(tripleKey(q));
        const first = from.filter((q) => q.predicate.value === `${RDF}first`);
        const rest = from.filter((q) => q.predicate.value === `${RDF}rest`);
        if (first.length !== 1 || rest.length !== 1 || from.length !== 2) {
            fail(`list node _:${node.value} is not a list cell`);
            break;
        }
        listed.push(first[0].object.value);
        node = rest[0].object;
    }
    if (node && !(node.termType === 'NamedNode' && node.value === `${RDF}nil`))
        fail('the as:items list does not end in rdf:nil');

    // 2. Everything else is in the Turtle.
    const turtleKeys = new Set(turtle.map(tripleKey));
    const turtleSubjects = new Set(turtle.map((q) => q.subject.value));
    if (turtleSubjects.has(page)) fail(`the page IRI <${page}> names a node of the Turtle`);
    let common = 0;
    const missing = [];
    for (const q of quads) {
        const key = tripleKey(q);
        if (pageKeys.has(key)) continue;
        if (q.graph.termType !== 'DefaultGraph') fail(`a triple in a named graph: ${key}`);
        if (q.subject.termType === 'BlankNode' || q.object.termType === 'BlankNode')
            fail(`a blank node outside the page: ${key}`);
        if (turtleKeys.has(key)) ++common;
        else missing.push(key);
    }
    for (const key of missing.slice(0, 20)) fail(`not in the Turtle: ${key}`);
    if (missing.length > 20) fail(`... and ${missing.length - 20} more triples not in the Turtle`);

    // 3. The same annotations, bodies and targets.
    const annotationsOf = (qs) => qs.filter((q) => q.predicate.value === `${RDF}type` &&
                                                   q.object.value === `${OA}Annotation`)
        .map((q) => q.subject.value);
    const fromJsonld = annotationsOf(quads);
    const fromTurtle = annotationsOf(turtle);
    if (!sameSet(new Set(fromJsonld), new Set(fromTurtle)))
        fail(`annotations differ: JSON-LD ${show(new Set(fromJsonld))}, Turtle ${show(new Set(fromTurtle))}`);
    // B annotation/k first, by k, then B texel/i/annotation, by i.
    const order = (iri) => {
        const texel = /[/#]texel\/([0-9]+)\/annotation$/.exec(iri);
        if (texel) return [1, Number(texel[1])];
        return [0, Number(iri.slice(iri.lastIndexOf('/') + 1))];
    };
    const inOrder = [...fromTurtle].sort((a, b) => {
        const [x, y] = [order(a), order(b)];
        return x[0] - y[0] || x[1] - y[1];
    });
    if (listed.join(' ') !== inOrder.join(' '))
        fail(`the page lists ${listed.length} items, not the ${inOrder.length} annotations in order`);
    let bodies = 0, targets = 0, texels = 0;
    // The same objects in both, and exactly `count` of them when given.
    const same = (s, p, count) => {
        const j = objectsOf(quads, s, p), t = objectsOf(turtle, s, p);
        if (!sameSet(j, t) || (count !== undefined && j.size !== count))
            fail(`<${s}> <${p}>: JSON-LD ${show(j)}, Turtle ${show(t)}`);
        return t;
    };
    for (const a of fromTurtle) {
        for (const p of [`${OA}hasBody`, `${OA}motivatedBy`, `${GTX}stability`, `${GTX}agreement`]) same(a, p);
        bodies += objectsOf(turtle, a, `${OA}hasBody`).size;
        for (const target of same(a, `${OA}hasTarget`, 1)) {
            ++targets;
            const iri = target.slice(1, -1);
            same(iri, `${OA}hasSource`, 1);
            const parts = same(iri, `${GTX}hasTexel`);
            if (parts.size === 0) same(iri, `${OA}hasSelector`, 1);
            for (const part of parts) {
                ++texels;
                same(part.slice(1, -1), `${OA}hasSource`, 1);
                same(part.slice(1, -1), `${OA}hasSelector`, 1);
            }
        }
    }
    if (fromTurtle.length === 0) fail('no annotation in the Turtle: nothing was compared');

    if (failures.length) {
        for (const f of failures) console.error(`jsonld_roundtrip: FAILED: ${f}`);
        process.exit(1);
    }
    console.log(`jsonld-roundtrip: OK: ${quads.length} triples from the JSON-LD (${pageKeys.size} of the page), ` +
                `the other ${common} all in the Turtle (${turtle.length} triples); ${fromTurtle.length} annotations, ` +
                `${bodies} bodies, ${targets} targets (${texels} texels of textures) as in the Turtle`);
}

main().catch((e) => {
    console.error(`jsonld_roundtrip: ${e.stack || e}`);
    process.exit(2);
});
