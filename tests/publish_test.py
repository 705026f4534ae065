#!/usr/bin/env python3
"""`geotex publish` against a fake Graph Store (no triple store needed): retries, no retry
on 4xx, timeouts, a store that is down, chunked uploads, authentication, skipping on rerun,
the CSV report, published.json after every case (also after a kill), bad input, N-Quads.

    tests/publish_test.py GEOTEX SOURCE_DIR

The fake store (http.server on a free loopback port) keeps each graph as a set of
N-Triples lines (Turtle bodies are converted with rapper) and answers from a script of
actions: "ok", an HTTP status, or ("hang", seconds).
"""
import collections
import csv
import http.server
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

GEOTEX = os.path.realpath(sys.argv[1])
SOURCE = os.path.realpath(sys.argv[2])
MAKE_OUTDIR = os.path.join(SOURCE, "tests", "make_outdir.py")
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return condition


def ntriples_of_turtle(data):
    """The triples of Turtle bytes as a set of N-Triples lines (rapper, raptor2-utils)."""
    out = subprocess.run(["rapper", "-q", "-i", "turtle", "-o", "ntriples", "-", "urn:base:"],
                         input=data, capture_output=True, check=True).stdout.decode()
    return {line for line in out.splitlines() if line.strip()}


class FakeStore:
    def __init__(self):
        self.requests = []  # (method, graph, content type, body bytes, answer)
        self.graphs = collections.defaultdict(set)
        self.script = collections.deque()
        self.credentials = None  # "user:password" for Basic authentication, or None
        self.lock = threading.Lock()
        store = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def log_message(self, *args):
                pass

            def answer(self, status, text=""):
                body = text.encode()
                self.send_response(status)
                self.send_header("Content-Type", "text/plain; charset=utf-8")
                self.send_header("Content-Length", str(len(body)))
                if status == 401:
                    self.send_header("WWW-Authenticate", 'Basic realm="fake"')
                self.end_headers()
                self.wfile.write(body)

            def update(self):
                length = int(self.headers.get("Content-Length", "0"))
                body = self.rfile.read(length)
                query = urllib.parse.parse_qs(urllib.parse.urlparse(self.path).query)
                graph = query.get("graph", [None])[0]
                ctype = self.headers.get("Content-Type", "")
                if store.credentials is not None:
                    import base64
                    expected = "Basic " + base64.b64encode(store.credentials.encode()).decode()
                    if self.headers.get("Authorization") != expected:
                        with store.lock:
                            store.requests.append((self.command, graph, ctype, body, 401))
                        return self.answer(401, "authentication needed")
                with store.lock:
                    action = store.script.popleft() if store.script else "ok"
                    store.requests.append((self.command, graph, ctype, body, action))
                if isinstance(action, tuple) and action[0] == "echo":
                    # A careless store (or proxy) that echoes the request, credentials and all.
                    return self.answer(action[1], "you sent:\n" + str(self.headers) +
                                       "\nchecked user alice with s3cret against the base")
                if isinstance(action, tuple) and action[0] == "hang":
                    time.sleep(action[1])
                    try:
                        return self.answer(500, "too late")
                    except OSError:
                        return None  # the client gave up long ago
                if action != "ok":
                    return self.answer(action, f"scripted answer {action}: <b>no</b>")
                if graph is None:
                    return self.answer(400, "no graph parameter")
                if ctype.startswith("text/turtle"):
                    triples = ntriples_of_turtle(body)
                elif ctype.startswith("application/n-triples"):
                    triples = {l for l in body.decode().splitlines() if l.strip()}
                else:
                    return self.answer(415, "unsupported type " + ctype)
                with store.lock:
                    if self.command == "PUT":
                        created = graph not in store.graphs
                        store.graphs[graph] = set(triples)
                        return self.answer(201 if created else 204)
                    store.graphs[graph] |= triples
                return self.answer(200)

            do_PUT = update
            do_POST = update

        class Server(http.server.ThreadingHTTPServer):
            def handle_error(self, request, client_address):
                pass  # a client that timed out and left: expected here

        self.server = Server(("127.0.0.1", 0), Handler)
        self.server.daemon_threads = True
        self.port = self.server.server_address[1]
        self.url = f"http://127.0.0.1:{self.port}/sparql-graph-crud"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def reset(self, script=(), clear_graphs=False):
        with self.lock:
            self.requests.clear()
            self.script = collections.deque(script)
            if clear_graphs:
                self.graphs.clear()


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def publish(outdir, *args, env=None, timeout=120):
    cmd = [GEOTEX, "publish", outdir, *args]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                       env=dict(os.environ, **(env or {})))
    return r


def report(outdir):
    with open(os.path.join(outdir, "publish-report.csv"), newline="", encoding="utf-8") as f:
        return {row["id"]: row for row in csv.DictReader(f)}


def objects(outdir):
    """id -> (graph, annotation.ttl path, recorded digest) of the complete objects."""
    out = {}
    for object_id in sorted(os.listdir(os.path.join(outdir, "objects"))):
        d = os.path.join(outdir, "objects", object_id)
        if os.path.exists(os.path.join(d, "run.json")):
            run = json.load(open(os.path.join(d, "run.json"), encoding="utf-8"))
            out[object_id] = (run["graph"], os.path.join(d, "annotation.ttl"), run["outputs"]["annotation.ttl"])
    return out


def check_record(outdir, store, endpoint, what, graph_per_object=True):
    """published.json is valid and tells the truth: every object it has as sent is in the
    fake store exactly (per object graph) or contained (one graph for all)."""
    path = os.path.join(outdir, "published.json")
    if not os.path.exists(path):
        return True
    try:
        record = json.load(open(path, encoding="utf-8"))
    except ValueError as e:
        return check(False, f"{what}: published.json is not JSON: {e}")
    ok = check(record["geotex"]["document"] == "published", f"{what}: published.json stamp")
    objs = objects(outdir)
    for graph, entries in record["endpoints"].get(endpoint, {}).items():
        for object_id, entry in entries.items():
            if entry["state"] != "sent" or object_id not in objs:
                continue
            g, ttl, digest = objs[object_id]
            if entry["annotation_sha256"] != digest:
                continue  # changed since: the record does not claim the new version
            triples = ntriples_of_turtle(open(ttl, "rb").read())
            have = store.graphs.get(graph, set())
            good = have == triples if graph_per_object else triples <= have
            ok = check(good, f"{what}: published.json has '{object_id}' as sent to <{graph}>, "
                             f"but the store holds {len(have)} triples there, the file {len(triples)}") and ok
            ok = check(entry["triples"] == len(triples), f"{what}: recorded triple count of '{object_id}'") and ok
    return ok


def restamp(outdir, *ids):
    subprocess.run([sys.executable, MAKE_OUTDIR, "--restamp", outdir, *ids], check=True)


def main():
    work = tempfile.mkdtemp(prefix="geotex-publish-test-")
    try:
        os.chdir(work)
        run_cases(work)
    finally:
        os.chdir("/")
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print(f"{len(failures)} publish test(s) failed")
        return 1
    print("publish tests passed")
    return 0


def run_cases(work):
    store = FakeStore()
    ep = store.url
    out = "out"
    subprocess.run([sys.executable, MAKE_OUTDIR, GEOTEX, out, "a:3:1", "b:3:2", "c d:3:3"], check=True)
    ids = ["a", "b", "c d"]
    objs = objects(out)
    quiet = ["--retry-delay", "0.05"]

    # --- first publish: one PUT per object, the file's Turtle, into its graph -----------------
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    check(r.returncode == 0, f"first publish: exit {r.returncode}: {r.stderr}")
    check([(m, g) for m, g, *_ in store.requests] == [("PUT", objs[i][0]) for i in ids],
          f"first publish: requests {[(m, g) for m, g, *_ in store.requests]}")
    check(all(c == "text/turtle" for _, _, c, *_ in store.requests), "content type text/turtle")
    check([b for _, _, _, b, _ in store.requests] == [open(objs[i][1], "rb").read() for i in ids],
          "bodies are the annotation.ttl files")
    rep = report(out)
    check([rep[i]["status"] for i in ids] == ["sent"] * 3, f"report: {rep}")
    check(all(int(rep[i]["triples"]) > 1000 and int(rep[i]["requests"]) == 1 for i in ids), "report counts")
    check(sum(1 for l in r.stdout.splitlines() if l.startswith("sent ")) == 3, f"stdout: {r.stdout}")
    check(rep["c d"]["graph"] == "https://example.org/object/c%20d/", "graph of an id with a space")
    check_record(out, store, ep, "first publish")
    record_after_first = open(os.path.join(out, "published.json"), "rb").read()

    # --- rerun: nothing sent -----------------------------------------------------------------
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    check(r.returncode == 0 and not store.requests, f"rerun sent {len(store.requests)} requests")
    check([report(out)[i]["status"] for i in ids] == ["unchanged"] * 3, "rerun: report says unchanged")
    check(open(os.path.join(out, "published.json"), "rb").read() == record_after_first,
          "rerun: published.json unchanged")

    # --- a changed object: only it is sent, and it replaces its graph --------------------------
    ttl_b = objs["b"][1]
    original_b = open(ttl_b, "rb").read()
    with open(ttl_b, "wb") as f:
        f.write(original_b.replace(b'"geotex"', b'"geotex, changed"'))
    restamp(out, "b")
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    check([(m, g) for m, g, *_ in store.requests] == [("PUT", objs["b"][0])], "changed object: one PUT")
    check(len(store.graphs[objs["b"][0]]) == len(ntriples_of_turtle(original_b)),
          "changed object: its graph replaced, same triple count")
    check([report(out)[i]["status"] for i in ids] == ["unchanged", "sent", "unchanged"], "changed: report")
    check_record(out, store, ep, "changed object")

    # --- --force and --dry-run ---------------------------------------------------------------
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", *quiet)
    check(len(store.requests) == 3 and r.returncode == 0, "--force resends all")
    store.reset()
    before = open(os.path.join(out, "publish-report.csv"), "rb").read()
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--dry-run")
    check(r.returncode == 0 and not store.requests, "--dry-run sends nothing")
    check(r.stdout.count("would-send") == 3 and "PUT text/turtle to " + ep + "?graph=" in r.stdout,
          f"--dry-run shows what: {r.stdout}")
    check(open(os.path.join(out, "publish-report.csv"), "rb").read() == before, "--dry-run writes no report")

    # --- 500 then 200: retried ---------------------------------------------------------------
    store.reset([500, 503, "ok"])
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", *quiet)
    check(r.returncode == 0, f"500, 503, then ok: exit {r.returncode}: {r.stderr}")
    check(len(store.requests) == 5, f"500, 503, then ok: {len(store.requests)} requests, expected 3 + 2")
    check(r.stderr.count("retrying") == 2, f"retries reported: {r.stderr}")
    check_record(out, store, ep, "retries")

    # --- 500 every time: fails after the retries, the others still sent ------------------------
    store.reset([500] * 3)
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--retries", "2", *quiet)
    check(r.returncode == 3, f"500 always: exit {r.returncode}, expected 3")
    check(len(store.requests) == 5, f"500 always: {len(store.requests)} requests, expected 3 + 2")
    rep = report(out)
    check([rep[i]["status"] for i in ids] == ["failed", "sent", "sent"], f"500 always: report {rep}")
    check("HTTP 500" in rep["a"]["reason"] and "3 attempts" in rep["a"]["reason"], f"reason: {rep['a']['reason']}")
    errors = [l for l in r.stderr.splitlines() if l.startswith("geotex: error:")]
    check(len(errors) == 1 and ep in errors[0] and "'a'" in errors[0] and "HTTP 500" in errors[0],
          f"500 always: one error naming endpoint, object, status: {errors}")
    check_record(out, store, ep, "500 always")
    rec = json.load(open(os.path.join(out, "published.json")))
    check(rec["endpoints"][ep][objs["a"][0]]["a"]["state"] == "sending",
          "a failed object stays 'sending' (the graph's content is unknown)")
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    check([g for _, g, *_ in store.requests] == [objs["a"][0]], "the failed object is sent again on rerun")

    # --- 400: not retried ----------------------------------------------------------------------
    store.reset([400])
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", *quiet)
    check(r.returncode == 3 and len(store.requests) == 3, f"400: exit {r.returncode}, {len(store.requests)} requests")
    check("HTTP 400" in report(out)["a"]["reason"], "400 in the report")
    check("scripted answer 400: no" in report(out)["a"]["reason"], f"answer text, markup dropped: {report(out)['a']}")
    check_record(out, store, ep, "400")

    # --- 501 (Virtuoso's answer on a path that is no Graph Store): no retry, the run stops ------
    store.reset([501])
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", *quiet)
    errors = [l for l in r.stderr.splitlines() if l.startswith("geotex: error:")]
    check(r.returncode == 3 and len(store.requests) == 1, f"501: exit {r.returncode}, {len(store.requests)} requests")
    check(len(errors) == 1 and "HTTP 501" in errors[0] and "stopped, 2 more objects not sent" in errors[0],
          f"501: one error, stopped: {errors}")
    check_record(out, store, ep, "501")

    # --- a store that hangs: timeout, retried, then the run stops -------------------------------
    store.reset([("hang", 3), ("hang", 3)])
    t = time.time()
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--timeout", "0.5", "--retries", "1", *quiet)
    elapsed = time.time() - t
    check(r.returncode == 3 and len(store.requests) == 2, f"hang: exit {r.returncode}, {len(store.requests)} requests")
    check(elapsed < 3, f"hang: took {elapsed:.1f} s with --timeout 0.5")
    errors = [l for l in r.stderr.splitlines() if l.startswith("geotex: error:")]
    check(len(errors) == 1 and "timed out" in errors[0].lower() and "stopped" in errors[0], f"hang: {errors}")
    rep = report(out)
    check([rep[i]["status"] for i in ids] == ["failed"] * 3 and "not attempted" in rep["b"]["reason"], f"hang: {rep}")
    time.sleep(3)  # let the hanging handlers finish before the next case counts requests
    check_record(out, store, ep, "hang")

    # --- a store that is down: one clear error ---------------------------------------------------
    down = f"http://127.0.0.1:{free_port()}/sparql-graph-crud"
    r = publish(out, "--endpoint", down, "--graph-per-object", "--retries", "1", *quiet)
    errors = [l for l in r.stderr.splitlines() if l.startswith("geotex: error:")]
    check(r.returncode == 3, f"down: exit {r.returncode}")
    check(len(errors) == 1 and down in errors[0] and "connect" in errors[0].lower(), f"down: {errors}")
    check([report(out)[i]["status"] for i in ids] == ["failed"] * 3, "down: report")
    rec = json.load(open(os.path.join(out, "published.json")))
    check(down in rec["endpoints"] and rec["endpoints"][down][objs["a"][0]]["a"]["state"] == "sending",
          "down: the object tried is 'sending', nothing claimed as sent")
    check(all(e["state"] == "sending" for g in rec["endpoints"][down].values() for e in g.values()), "down: record")

    # --- authentication ---------------------------------------------------------------------------
    store.reset()
    store.credentials = "alice:s3cret"
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--user", "alice", *quiet,
                env={"GEOTEX_STORE_PASSWORD": "s3cret"})
    check(r.returncode == 0 and [a for *_, a in store.requests].count("ok") == 3,
          f"basic auth, password from the environment: {r.stderr}")
    check_record(out, store, ep, "basic auth")
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--user", "alice", "--password", "wrong", *quiet)
    errors = [l for l in r.stderr.splitlines() if l.startswith("geotex: error:")]
    check(r.returncode == 3 and len(errors) == 1 and "401" in errors[0] and "stopped" in errors[0],
          f"wrong password: one error, stopped: {errors}")
    check("s3cret" not in r.stderr + r.stdout and "wrong" not in r.stderr, "no password in messages")
    store.credentials = None
    # A store echoing the request (Authorization header included) into its error answer: the
    # report keeps the status and the text, never the credentials in any form.
    import base64
    token = base64.b64encode(b"alice:s3cret").decode()
    store.reset([("echo", 400)])
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--user", "alice",
                "--auth", "basic", *quiet, env={"GEOTEX_STORE_PASSWORD": "s3cret"})
    check(r.returncode == 3, f"echoing store: exit {r.returncode}: {r.stderr}")
    reason = report(out)["a"]["reason"]
    written = open(os.path.join(out, "publish-report.csv"), encoding="utf-8").read() + \
        open(os.path.join(out, "published.json"), encoding="utf-8").read()
    check("HTTP 400" in reason and "you sent" in reason and "[removed]" in reason, f"echoing store: reason {reason!r}")
    check("s3cret" not in written and token not in written and token[:8] not in written,
          f"echoing store: credentials written to disk: {reason!r}")
    check("s3cret" not in r.stderr + r.stdout and token[:8] not in r.stderr + r.stdout,
          f"echoing store: credentials in messages: {r.stderr}")

    # --- one graph for the collection: PUT then POST; adding, changing ---------------------------
    coll = "urn:geotex:test:collection"
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph", coll, *quiet)
    check([(m, g) for m, g, *_ in store.requests] == [("PUT", coll), ("POST", coll), ("POST", coll)],
          f"--graph: {[(m, g) for m, g, *_ in store.requests]}")
    all_triples = set().union(*(ntriples_of_turtle(open(objs[i][1], "rb").read()) for i in ids))
    check(store.graphs[coll] == all_triples, "--graph: the graph holds the union")
    check_record(out, store, ep, "--graph", graph_per_object=False)
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph", coll, *quiet)
    check(not store.requests, "--graph rerun: nothing sent")
    subprocess.run([sys.executable, MAKE_OUTDIR, GEOTEX, "more", "e:3:5"], check=True)
    shutil.copytree("more/objects/e", os.path.join(out, "objects", "e"))
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph", coll, *quiet)
    check([(m, g) for m, g, *_ in store.requests] == [("POST", coll)], f"--graph, a new object: only it, POST")
    with open(ttl_b, "wb") as f:
        f.write(original_b)
    restamp(out, "b")
    store.reset([400])  # the rewrite's first PUT fails: the next object must PUT instead
    r = publish(out, "--endpoint", ep, "--graph", coll, *quiet)
    check([m for m, *_ in store.requests] == ["PUT", "PUT", "POST", "POST"],
          f"--graph, a changed object: the graph rewritten, PUT until one succeeds: {[m for m, *_ in store.requests]}")
    check(r.returncode == 3, "--graph rewrite with a failure: exit 3")
    check_record(out, store, ep, "--graph rewrite", graph_per_object=False)
    # The failed object's PUT changed nothing and the next PUT replaced the graph: the
    # failed object is simply missing and is added now.
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph", coll, *quiet)
    check([(m, g) for m, g, *_ in store.requests] == [("POST", coll)],
          f"--graph: the object that failed is added: {[m for m, *_ in store.requests]}")
    all_triples = set().union(*(ntriples_of_turtle(open(o[1], "rb").read()) for o in objects(out).values()))
    check(store.graphs[coll] == all_triples, "--graph: the rewritten graph holds the union, nothing stale")
    shutil.rmtree(os.path.join(out, "objects", "e"))

    # --- chunked uploads --------------------------------------------------------------------------
    store.reset(clear_graphs=True)
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--force", "--chunk-triples", "500", *quiet)
    check(r.returncode == 0, f"--chunk-triples 500: {r.stderr}")
    for i in ids:
        reqs = [(m, c, b) for m, g, c, b, _ in store.requests if g == objs[i][0]]
        triples = ntriples_of_turtle(open(objs[i][1], "rb").read())
        check([m for m, *_ in reqs] == ["PUT"] + ["POST"] * (len(reqs) - 1) and len(reqs) == -(-len(triples) // 500),
              f"chunks of '{i}': {[m for m, *_ in reqs]} for {len(triples)} triples")
        check(all(c == "application/n-triples" for _, c, _ in reqs), "chunks are N-Triples")
        check(all(len(b.decode().splitlines()) <= 500 for *_, b in reqs), "at most 500 triples per chunk")
        check(store.graphs[objs[i][0]] == triples, f"chunks of '{i}': their union is the file")
    check(int(report(out)["a"]["requests"]) > 1, "report counts the requests")
    big = "big"
    subprocess.run([sys.executable, MAKE_OUTDIR, GEOTEX, big, "huge:3:1", "--large", "120000"], check=True)
    store.reset()
    r = publish(big, "--endpoint", ep, "--graph-per-object", *quiet)
    huge = objects(big)["huge"]
    triples = ntriples_of_turtle(open(huge[1], "rb").read())
    check(len(triples) > 120000, "the big file")
    check([m for m, *_ in store.requests] == ["PUT", "POST"], f"120k triples: sent in 2 requests by default")
    check(store.graphs[huge[0]] == triples, "120k triples: the union of the chunks is the file")
    check_record(big, store, ep, "big")

    # --- killed while sending: published.json consistent, the object resent -----------------------
    store.reset([("hang", 30)], clear_graphs=True)
    os.remove(os.path.join(out, "published.json"))
    p = subprocess.Popen([GEOTEX, "publish", out, "--endpoint", ep, "--graph-per-object", "--quiet"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(100):
        if store.requests:
            break
        time.sleep(0.05)
    p.send_signal(signal.SIGKILL)
    p.wait()
    check_record(out, store, ep, "killed")
    rec = json.load(open(os.path.join(out, "published.json")))
    check(rec["endpoints"][ep][objs["a"][0]]["a"]["state"] == "sending", "killed: the object in flight is 'sending'")
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    check(r.returncode == 0 and len(store.requests) == 3, "after the kill, everything is sent")
    check_record(out, store, ep, "after the kill")

    # --- incomplete objects: skipped with a warning --------------------------------------------------
    shutil.copytree(os.path.join(out, "objects", "a"), os.path.join(out, "objects", "a2"))
    run = json.load(open(os.path.join(out, "objects", "a2", "run.json")))
    run["id"] = "a2"
    json.dump(run, open(os.path.join(out, "objects", "a2", "run.json"), "w"))
    with open(os.path.join(out, "objects", "a2", "annotation.ttl"), "ab") as f:
        f.write(b"\n<urn:x> <urn:y> <urn:z> .\n")
    os.makedirs(os.path.join(out, "objects", "a3"))
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    check(r.returncode == 0 and not store.requests, f"incomplete objects: exit {r.returncode}, {len(store.requests)} requests")
    check("objects/a2: skipped: annotation.ttl does not have the SHA-256" in r.stderr, f"digest warning: {r.stderr}")
    check("objects/a3: skipped: no run.json" in r.stderr, "no run.json warning")
    rep = report(out)
    check(rep["a2"]["status"] == "skipped" and rep["a3"]["status"] == "skipped", "skipped in the report")
    shutil.rmtree(os.path.join(out, "objects", "a2"))
    shutil.rmtree(os.path.join(out, "objects", "a3"))

    # --- two objects naming the same graph: the second fails, in a graph of its own ----------------
    shutil.copytree(os.path.join(out, "objects", "a"), os.path.join(out, "objects", "a-copy"))
    run = json.load(open(os.path.join(out, "objects", "a-copy", "run.json")))
    run["id"] = "a-copy"
    json.dump(run, open(os.path.join(out, "objects", "a-copy", "run.json"), "w"))
    store.reset()
    r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
    errors = [l for l in r.stderr.splitlines() if l.startswith("geotex: error:")]
    check(r.returncode == 3 and not store.requests, f"same graph twice: exit {r.returncode}, {len(store.requests)} requests")
    check(len(errors) == 1 and "a-copy" in errors[0] and "also the graph of object 'a'" in errors[0], f"same graph: {errors}")
    check(report(out)["a-copy"]["status"] == "failed" and report(out)["a"]["status"] == "unchanged", "same graph: report")
    r = publish(out, "--endpoint", ep, "--graph-per-object", "--dry-run")
    check(r.returncode == 3 and "0 would be sent, 3 unchanged, 1 failed" in r.stdout, f"same graph, dry run: {r.stdout}")
    shutil.rmtree(os.path.join(out, "objects", "a-copy"))

    # --- N-Quads ----------------------------------------------------------------------------------
    r1 = publish(out, "--nquads", "all.nq")
    first = open("all.nq", "rb").read()
    r2 = publish(out, "--nquads", "all.nq", "--quiet")
    check(r1.returncode == 0 and r2.returncode == 0 and open("all.nq", "rb").read() == first, "N-Quads deterministic")
    quads = first.decode().splitlines()
    check(len(quads) == sum(len(ntriples_of_turtle(open(objs[i][1], "rb").read())) for i in ids), "N-Quads count")
    for i in ids:
        check(sum(1 for q in quads if q.endswith(f"<{objs[i][0]}> .")) ==
              len(ntriples_of_turtle(open(objs[i][1], "rb").read())), f"N-Quads of '{i}' in its graph")
    rr = subprocess.run(["rapper", "-q", "-i", "nquads", "-c", "all.nq"], capture_output=True)
    check(rr.returncode == 0, "rapper reads the N-Quads")
    r = publish(out, "--nquads", "one.nq", "--graph", coll)
    check(all(q.endswith(f"<{coll}> .") for q in open("one.nq").read().splitlines()), "--nquads with --graph")

    # --- bad input and options: one line, the STYLE exit codes, nothing written ---------------------
    os.makedirs("not-batch")
    os.makedirs("badrun/objects/x")
    open("badrun/objects/x/run.json", "w").write("{ not json")
    os.makedirs("newer/objects/x")
    json.dump({"geotex": {"document": "batch-object", "schema": 9}}, open("newer/objects/x/run.json", "w"))
    cases = [
        (["missing", "--endpoint", ep, "--graph-per-object"], 2, "no such directory"),
        (["not-batch", "--endpoint", ep, "--graph-per-object"], 2, "not a geotex batch directory"),
        (["badrun", "--endpoint", ep, "--graph-per-object"], 2, "run.json: not valid JSON"),
        (["newer", "--nquads", "x.nq"], 2, "newer geotex"),
        ([out, "--endpoint", "ftp://x/y", "--graph-per-object"], 1, "http or https"),
        ([out, "--endpoint", "not a url", "--graph-per-object"], 1, "--endpoint"),
        ([out, "--endpoint", "http://u:p@127.0.0.1/x", "--graph-per-object"], 1, "credentials"),
        ([out, "--endpoint", ep, "--graph-per-object", "--graph", coll], 1, "exclude each other"),
        ([out, "--endpoint", ep], 1, "--graph-per-object"),
        ([out], 1, "nothing to do"),
        ([out, "--endpoint", ep, "--graph", "not an iri"], 1, "graph IRI"),
        ([out, "--nquads", "no-such-dir/x.nq"], 4, "no-such-dir"),
        # An output never replaces an input: the objects' files are publish's inputs.
        ([out, "--nquads", os.path.join(out, "objects", "a", "annotation.ttl")], 1,
         "is the same file as the input of object 'a'"),
        ([out, "--nquads", os.path.join(out, "objects", "b", "run.json")], 1, "of object 'b'"),
        ([out, "--endpoint", ep, "--graph-per-object", "--retries", "-1"], 1, "retries"),
    ]
    for args, code, text in cases:
        store.reset()
        r = subprocess.run([GEOTEX, "publish", *args], capture_output=True, text=True)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == code, f"{args}: exit {r.returncode}, expected {code}: {r.stderr.strip()}")
        check(len(lines) == 1 and lines[0].startswith("geotex: error: ") and text in lines[0],
              f"{args}: one error line with '{text}': {lines}")
        check(not store.requests, f"{args}: nothing sent")
    check(not os.path.exists("x.nq") and not os.path.exists("badrun/published.json"), "nothing written on bad input")
    check(objects(out)["a"][2] == __import__("hashlib").sha256(open(objs["a"][1], "rb").read()).hexdigest(),
          "--nquads naming an annotation.ttl: the file is intact")
    # A link planted at OUTDIR/published.json or publish-report.csv is refused, not followed.
    for name in ["published.json", "publish-report.csv"]:
        path = os.path.join(out, name)
        if os.path.exists(path):
            os.remove(path)
        open("victim.txt", "w").write("precious")
        os.symlink(os.path.abspath("victim.txt"), path)
        store.reset()
        r = publish(out, "--endpoint", ep, "--graph-per-object", *quiet)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 4 and len(lines) == 1 and f"{name}: is a symbolic link" in lines[0],
              f"planted {name}: exit {r.returncode}: {lines}")
        check(open("victim.txt").read() == "precious" and os.path.islink(path) and not store.requests,
              f"planted {name}: nothing sent, nothing written through the link")
        if name == "published.json":  # a dry run reads the record but writes nothing
            r = publish(out, "--endpoint", ep, "--graph-per-object", "--dry-run", *quiet)
            lines = r.stderr.strip().splitlines()
            check(r.returncode == 4 and len(lines) == 1 and "published.json: is a symbolic link" in lines[0],
                  f"planted published.json, dry run: exit {r.returncode}: {lines}")
        os.remove(path)
    # Links planted inside OUTDIR are not followed when reading either: an object directory
    # or an object file that is a link is skipped (it could make publish send another
    # user's file to the store).
    shutil.copytree(out, "planted", symlinks=True)
    os.symlink("a", os.path.join("planted", "objects", "zz"))
    ttl = os.path.join("planted", "objects", "b", "annotation.ttl")
    os.rename(ttl, "b-elsewhere.ttl")
    os.symlink(os.path.abspath("b-elsewhere.ttl"), ttl)
    r = publish("planted", "--nquads", "planted.nq")
    check(r.returncode == 0, f"planted links: exit {r.returncode}: {r.stderr}")
    check("objects/zz: skipped: objects/zz is a symbolic link" in r.stderr, f"planted directory link: {r.stderr}")
    check("objects/b: skipped: run.json lists 'annotation.ttl', which is a symbolic link" in r.stderr,
          f"planted file link: {r.stderr}")
    check(f"<{objs['b'][0]}> ." not in open("planted.nq").read() and "2 objects" in r.stdout,
          f"planted links: their triples are not published: {r.stdout}")
    r = subprocess.run([GEOTEX, "publish", "--help"], capture_output=True, text=True)
    check(r.returncode == 0 and "--graph-per-object" in r.stdout and "published.json" in r.stdout, "--help")


if __name__ == "__main__":
    sys.exit(main())
