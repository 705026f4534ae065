#!/usr/bin/env bash
# Writes the seed corpora of the fuzz targets: small valid inputs of every kind each reader
# accepts, generated here rather than downloaded.
# Usage: fuzz/make_seeds.sh BUILD_DIR    (BUILD_DIR holds the geotex command; seeds go to
#        BUILD_DIR/corpus/<target>/, next to whatever the fuzzers have added there)
set -euo pipefail

build=${1:?usage: fuzz/make_seeds.sh BUILD_DIR}
here=$(cd "$(dirname "$0")/.." && pwd)
corpus=$build/corpus
for t in fuzz_mesh_ply fuzz_mesh_obj fuzz_mesh_off fuzz_mesh_stl fuzz_dictionary fuzz_rdf_strings fuzz_manifest fuzz_sparql; do
  mkdir -p "$corpus/$t"
done

# seed TARGET NAME: stdin into the target's corpus as seed-NAME.
seed() { cat >"$corpus/$1/seed-$2"; }

# Little-endian bytes of float32 and int32 values used below, as printf escapes.
f0='\x00\x00\x00\x00' f1='\x00\x00\x80\x3f'
i0='\x00\x00\x00\x00' i1='\x01\x00\x00\x00' i2='\x02\x00\x00\x00' i3='\x03\x00\x00\x00'

# ---- PLY ------------------------------------------------------------------------------------
seed fuzz_mesh_ply tetra-ascii <<'EOF'
ply
format ascii 1.0
comment a tetrahedron
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
0 0 1
3 0 2 1
3 0 1 3
3 0 3 2
3 1 2 3
EOF
seed fuzz_mesh_ply quad-props-ascii <<'EOF'
ply
format ascii 1.0
obj_info two quads with per-face properties
element vertex 6
property double x
property double y
property double z
property uchar red
element face 2
property list uchar uint vertex_index
property int texel
property float quality
element edge 0
property int vertex1
end_header
0 0 0 1
1 0 0 2
2 0 0 3
0 1 0 4
1 1 0 5
2 1 1e-3 6
4 0 1 4 3 7 0.5
4 1 2 5 4 -1 -2.5e2
EOF
{
  printf 'ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n'
  printf 'property float y\nproperty float z\nelement face 4\n'
  printf 'property list uchar int vertex_indices\nend_header\n'
  printf "$f0$f0$f0$f1$f0$f0$f0$f1$f0$f0$f0$f1"
  printf "\\x03$i0$i2$i1\\x03$i0$i1$i3\\x03$i0$i3$i2\\x03$i1$i2$i3"
} | seed fuzz_mesh_ply tetra-binary-le
{
  printf 'ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\n'
  printf 'property double y\nproperty double z\nelement face 1\n'
  printf 'property list ushort short vertex_indices\nproperty uchar texel\nend_header\n'
  d0='\x00\x00\x00\x00\x00\x00\x00\x00' d1='\x3f\xf0\x00\x00\x00\x00\x00\x00'
  printf "$d0$d0$d0$d1$d0$d0$d0$d1$d0"
  printf '\x00\x03\x00\x00\x00\x01\x00\x02\x05'
} | seed fuzz_mesh_ply triangle-binary-be
if [ -x "$build/geotex" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  "$build/geotex" synth -o "$tmp/s.ply" --level 0 --quiet --threads 1 >/dev/null
  cp "$tmp/s.ply" "$corpus/fuzz_mesh_ply/seed-synth-level0-binary"
  "$build/geotex" synth -o "$tmp/s.ply" --level 1 --quiet --threads 1 --ascii --big-discs 2 \
    --small-discs 2 --squares 1 --rectangles 1 >/dev/null
  cp "$tmp/s.ply" "$corpus/fuzz_mesh_ply/seed-synth-level1-ascii"
else
  echo "make_seeds: no $build/geotex; the synthetic PLY seeds are skipped" >&2
fi

# ---- OBJ ------------------------------------------------------------------------------------
seed fuzz_mesh_obj tetra <<'EOF'
# a tetrahedron
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
EOF
seed fuzz_mesh_obj forms <<'EOF'
mtllib none.mtl
o quads
v 0.0 0.0 0.0
v 1.0 0.0 0.0
v 1.0 1.0 0.0
v 0.0 1.0 0.0
v 2.0 0.5 1e-2
vt 0 0
vt 1 1
vn 0 0 1
g top
usemtl stone
s off
f 1/1/1 2/2/1 3/1/1 4/2/1
f	-4//1	-1//1	-3//1
l 1 2
f 2/1 5/2 3/1
EOF
seed fuzz_mesh_obj pentagon <<'EOF'
v 1 0 0
v 0.309 0.951 0
v -0.809 0.588 0
v -0.809 -0.588 0
v 0.309 -0.951 0
f 1 2 3 4 5
EOF

# ---- OFF ------------------------------------------------------------------------------------
seed fuzz_mesh_off tetra <<'EOF'
OFF
4 4 6
0 0 0
1 0 0
0 1 0
0 0 1
3 0 2 1
3 0 1 3
3 0 3 2
3 1 2 3
EOF
seed fuzz_mesh_off coff-comments <<'EOF'
# coloured, with comments
COFF
5 2 0
0 0 0 255 0 0 255
1 0 0 0 255 0 255
1 1 0 0 0 255 255
0 1 0 9 9 9 255
2 2 1 1 1 1 255
4 0 1 2 3 0.5 0.5 0.5
3 1 4 2
EOF
seed fuzz_mesh_off homogeneous <<'EOF'
4OFF
3 1 0
0 0 0 1
2 0 0 2
0 4 0 4
3 0 1 2
EOF
{
  printf 'OFF BINARY\n'
  printf '\x00\x00\x00\x04\x00\x00\x00\x04\x00\x00\x00\x00'
  printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00'
  printf '\x3f\x80\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00'
  printf '\x00\x00\x00\x00\x3f\x80\x00\x00\x00\x00\x00\x00'
  printf '\x00\x00\x00\x00\x00\x00\x00\x00\x3f\x80\x00\x00'
  printf '\x00\x00\x00\x03\x00\x00\x00\x00\x00\x00\x00\x02\x00\x00\x00\x01'
  printf '\x00\x00\x00\x03\x00\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x03'
  printf '\x00\x00\x00\x03\x00\x00\x00\x00\x00\x00\x00\x03\x00\x00\x00\x02'
  printf '\x00\x00\x00\x03\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00\x03'
} | seed fuzz_mesh_off tetra-binary  # faces without Geomview's colour count, as CGAL reads them

# ---- STL ------------------------------------------------------------------------------------
facet() {  # facet NX NY NZ "x y z" "x y z" "x y z"
  printf '  facet normal %s %s %s\n    outer loop\n' "$1" "$2" "$3"
  printf '      vertex %s\n      vertex %s\n      vertex %s\n' "$4" "$5" "$6"
  printf '    endloop\n  endfacet\n'
}
{
  echo "solid tetra"
  facet 0 0 -1 "0 0 0" "0 1 0" "1 0 0"
  facet 0 -1 0 "0 0 0" "1 0 0" "0 0 1"
  facet -1 0 0 "0 0 0" "0 0 1" "0 1 0"
  facet 0.577 0.577 0.577 "1 0 0" "0 1 0" "0 0 1"
  echo "endsolid tetra"
} | seed fuzz_mesh_stl tetra-ascii
{
  printf 'binary tetrahedron%62s' ''
  printf '\x04\x00\x00\x00'
  v0="$f0$f0$f0" vx="$f1$f0$f0" vy="$f0$f1$f0" vz="$f0$f0$f1"
  printf "$f0$f0$f0$v0$vy$vx\\x00\\x00"
  printf "$f0$f0$f0$v0$vx$vz\\x00\\x00"
  printf "$f0$f0$f0$v0$vz$vy\\x00\\x00"
  printf "$f0$f0$f0$vx$vy$vz\\x00\\x00"
} | seed fuzz_mesh_stl tetra-binary
{
  printf 'solid but binary%64s' ''
  printf '\x01\x00\x00\x00'
  printf "$f0$f0$f1$f0$f0$f0$f1$f0$f0$f0$f1$f0\\x00\\x00"
} | seed fuzz_mesh_stl solid-header-binary

# ---- dictionaries ---------------------------------------------------------------------------
cp "$here/dictionaries/default.yaml" "$corpus/fuzz_dictionary/seed-default"
seed fuzz_dictionary small <<'EOF'
scheme:
  id: small
  version: "0.1"
  namespace: "https://example.org/dict#"
  languages: [en, pt-BR]
  title: {en: A small dictionary, pt-BR: "Um pequeno dicionário"}
features:
  contour_sphericity:
    - id: circular-shape
      interval: [0, 0.05]
      labels: {en: circular shape, pt-BR: forma circular}
      definition:
        en: |
          The contour stays at the same distance
          from the region's centre.
      source: 'paper, Table 3'
    - id: close-to-circular-shape
      interval: [0.05, .inf]
      labels:
        en: "close to \"circular\" shape"
        pt-BR: forma quase circular
  area:
    - {id: tiny, interval: [-.inf, 1e-3], labels: {en: tiny, pt-BR: minúsculo}}
EOF
seed fuzz_dictionary problems <<'EOF'
scheme:
  id: bad id
  version: 1.0
  namespace: example.org/dict
  languages: [en, en]
  title: {en: "unterminated
features:
  area:
    - id: a
      interval: [0.5, 0.1]
      lables: {en: x}
    - id: a
      interval: [0.2, nan]
      labels: {en: y}
      labels: {en: z}
  no_such_feature: []
EOF
seed fuzz_dictionary anchors <<'EOF'
%YAML 1.2
---
scheme: &s
  id: anchors
  version: !!str 2
  namespace: "urn:x:dict/"
  languages: [en]
  title: {en: *s}
features:
  area: [{id: x, interval: [0, 1], labels: &l {en: x}}, {id: y, interval: [1, 2], labels: *l}]
...
---
extra: document
EOF

# ---- RDF strings: a syntax byte, then fields separated by 0xFF ------------------------------
# mesh file, base IRI, label, language, concept id, namespace, text
rdf() {  # rdf NAME SYNTAX-BYTE FIELD...
  local name=$1 syntax=$2 out
  shift 2
  out=$(printf '%s\xff' "$@")
  printf '%s%s' "$syntax" "${out%$'\xff'}" | seed fuzz_rdf_strings "$name"
}
rdf plain-turtle 'T' vase.ply https://example.org/objects/vase-42/ "circular shape" en \
  circular-shape https://example.org/dict# "plain text"
rdf hostile-turtle 'T' $'a "quoted" > file\nwith\r\tstuff \\ \xc3\xa9 \xe6\xbc\xa2.ply' \
  $'https://example.org/objets/vase-\xc3\xa9t\xc3\xa9/' $'"""triple""" \'\'\'quotes\'\'\' \\' \
  fr-CA $'a b/c?d#e>f"%20\xc3\xa9' 'https://example.org/d%C3%A9mo/dict#' $'line\nbreak\r\n\t.'
rdf hostile-ntriples 'R' $'x> <y> "z" .\n_:b <p> <o> .' 'urn:sha256:abc/' $'label\\u0022' \
  zh-Hant-TW '..' 'tag:museum.example,2026:d/' $'\xf0\x9f\x98\x80 emoji'
rdf hostile-rdfxml 'S' $'<a attr="&amp;">]]>' 'http://x/?a=1&b=2/' $'&lt; <![CDATA[x]]>' \
  en-GB-oxendict . 'http://x/#' $'text & <tags>\r'

# ---- batch manifests ------------------------------------------------------------------------
seed fuzz_manifest plain <<'EOF'
id,mesh,object,mesh_unit
vase-1,meshes/vase-1.ply,https://museum.example.org/object/1,mm
vase-2,/data/vase-2.obj,,cm
EOF
seed fuzz_manifest mesh-only <<'EOF'
mesh
a.ply
b/c.off
EOF
printf 'ID ,Mesh,notes\r\n"\xc3\xa9t\xc3\xa9 6","with, comma.ply","quoted ""x"""\r\n../evil,x.ply,\r\n,y.stl,\r\nshort\r\ndup,a.ply,\r\ndup,b.ply,\r\n' |
  seed fuzz_manifest hostile
printf '\xef\xbb\xbfmesh,id\n"never closed\n' | seed fuzz_manifest bom-open-quote
printf 'id,mesh,object,mesh_unit\nx\x01y,a.ply,not an iri,furlong\n.hidden,a.ply,,\n' | seed fuzz_manifest bad-cells

# ---- SPARQL queries ---------------------------------------------------------------------------
# The documented queries, and short ones over the target's graph (ex: <http://ex.org/>).
for q in "$here"/ontology/queries/*.rq; do cp "$q" "$corpus/fuzz_sparql/seed-$(basename "$q" .rq)"; done
printf 'SELECT * WHERE { ?s ?p ?o }' | seed fuzz_sparql all
printf 'PREFIX ex: <http://ex.org/>\nSELECT ?x (COUNT(?y) AS ?n) WHERE { ?x ex:p/ex:p ?y OPTIONAL { ?x ex:q ?l FILTER(LANG(?l) = "en") } } GROUP BY ?x ORDER BY DESC(?n) LIMIT 2' | seed fuzz_sparql paths
printf 'ASK { <http://ex.org/a> ^<http://ex.org/p> ?z }' | seed fuzz_sparql ask
printf 'SELECT (GROUP_CONCAT(?o; SEPARATOR="|") AS ?all) WHERE { ?s <http://ex.org/q> ?o }' | seed fuzz_sparql concat
