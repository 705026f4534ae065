#!/usr/bin/env python3
"""A small `geotex batch` output directory (docs/collections.md) made with `geotex synth`
and `geotex annotate`, for the tests of `geotex publish` until `geotex batch` exists:

    tests/make_outdir.py GEOTEX OUTDIR ID:LEVEL[:SEED] ...

For each object: meshes/ID.ply (synthetic sphere of icosphere LEVEL, layout seed SEED), and
objects/ID/{annotation.ttl, report.json, segmentation.ply, run.json} with the base IRI
https://example.org/object/ID/ (the graph too). run.json is written last, as batch does.
Options: --scale F (default 0.08), --base-template T ({id} is replaced by the
percent-encoded id), --large N (the annotation.ttl of the first object gets N extra
triples, to test chunked uploads).

    tests/make_outdir.py --restamp OUTDIR ID ...

records the current digests of the objects' files in their run.json (after a test edited
one), keeping its other fields.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import urllib.parse


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def write_json_atomically(path, value):
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(value, f, indent=2, ensure_ascii=False)
        f.write("\n")
    os.replace(tmp, path)


def stamp(outdir, object_id, mesh, base, options):
    """Writes objects/ID/run.json for the files present in the object's directory."""
    d = os.path.join(outdir, "objects", object_id)
    outputs = {name: sha256_file(os.path.join(d, name))
               for name in sorted(os.listdir(d)) if name != "run.json" and not name.startswith(".")}
    report = json.load(open(os.path.join(d, "report.json"), encoding="utf-8"))
    run = {
        "geotex": {"version": "0.1.0", "document": "batch-object", "schema": 1},
        "id": object_id,
        "mesh": os.path.relpath(mesh, outdir),
        "mesh_sha256": sha256_file(mesh),
        # The built-in dictionary: no file to hash; a stand-in that batch will replace.
        "dictionary_sha256": hashlib.sha256(b"built-in default dictionary").hexdigest(),
        "options_sha256": hashlib.sha256(options.encode()).hexdigest(),
        "base": base,
        "graph": base,
        "texels": len(report.get("texels", [])),
        "textures": len(report.get("textures", [])),
        "outputs": outputs,
    }
    write_json_atomically(os.path.join(d, "run.json"), run)


def restamp(outdir, ids):
    for object_id in ids:
        d = os.path.join(outdir, "objects", object_id)
        run = json.load(open(os.path.join(d, "run.json"), encoding="utf-8"))
        run["outputs"] = {name: sha256_file(os.path.join(d, name)) for name in run["outputs"]}
        write_json_atomically(os.path.join(d, "run.json"), run)
    return 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--restamp":
        if len(sys.argv) < 4:
            sys.exit("usage: make_outdir.py --restamp OUTDIR ID ...")
        return restamp(sys.argv[2], sys.argv[3:])
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("geotex")
    ap.add_argument("outdir")
    ap.add_argument("objects", nargs="+", metavar="ID:LEVEL[:SEED]")
    ap.add_argument("--scale", default="0.08")
    ap.add_argument("--base-template", default="https://example.org/object/{id}/")
    ap.add_argument("--large", type=int, default=0)
    a = ap.parse_args()

    os.makedirs(os.path.join(a.outdir, "meshes"), exist_ok=True)
    for i, spec in enumerate(a.objects):
        parts = spec.split(":")
        object_id, level = parts[0], parts[1] if len(parts) > 1 else "4"
        seed = parts[2] if len(parts) > 2 else str(i + 1)
        mesh = os.path.join(a.outdir, "meshes", object_id + ".ply")
        d = os.path.join(a.outdir, "objects", object_id)
        os.makedirs(d, exist_ok=True)
        base = a.base_template.replace("{id}", urllib.parse.quote(object_id, safe=""))
        run = lambda *args: subprocess.run([a.geotex, *args, "--quiet"], check=True, stdout=subprocess.DEVNULL)
        run("synth", "-o", mesh, "--level", level, "--layout-seed", seed)
        options = f"--scale {a.scale} --base {base}"
        run("annotate", mesh, "--scale", a.scale, "--base", base, "-o", os.path.join(d, "annotation.ttl"),
            "--json", os.path.join(d, "report.json"), "--segmentation", os.path.join(d, "segmentation.ply"))
        if i == 0 and a.large > 0:
            with open(os.path.join(d, "annotation.ttl"), "a", encoding="utf-8") as f:
                f.write("\n# extra triples for the chunked-upload test\n")
                for k in range(a.large):
                    f.write(f"<{base}extra/{k}> <https://w3id.org/geotex/ns#faceCount> {k} .\n")
        stamp(a.outdir, object_id, mesh, base, options)
    return 0


if __name__ == "__main__":
    sys.exit(main())
