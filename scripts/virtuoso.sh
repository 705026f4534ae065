#!/usr/bin/env bash
# A private Virtuoso Open Source 7 instance for tests and benchmarks, never the system
# service: its database, log and configuration live in DIR, it listens on loopback only.
#
#   scripts/virtuoso.sh start DIR PORT_SQL PORT_HTTP   create or reuse DIR, start, wait until ready
#   scripts/virtuoso.sh stop DIR                       stop the server started from DIR (its PID)
#   scripts/virtuoso.sh isql DIR SQL                   run SQL as dba; fails on "*** Error"
#   scripts/virtuoso.sh bulkload DIR FILE_OR_DIR [GRAPH]
#       load a file, or every file of a directory, with the bulk loader (ld_dir,
#       rdf_loader_run, checkpoint). N-Quads (.nq) keep their graphs; triples files go to
#       GRAPH (default: urn:geotex:bulkload). Fails when DB.DBA.load_list records an error.
#
# The ports are chosen by the caller (tests take free ones from the kernel). A new database
# always starts with the account dba/dba. Settings: VIRTUOSO_START_TIMEOUT (seconds, 90).
# Facts this follows: /work/shared/TOOLCHAIN.md, "Real peers to test against".
set -euo pipefail

die() { echo "virtuoso.sh: $*" >&2; exit 1; }
usage() { sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 1; }

template=/etc/virtuoso-opensource-7/virtuoso.ini
[ -r "$template" ] || template=/usr/share/virtuoso-opensource-7/virtuoso.ini

port_of() { cat "$1/ports" 2>/dev/null | sed -n "s/^$2=//p"; }

# isql-vt exits 0 even when a statement fails: its output is checked for "*** Error".
run_isql() {
    local dir=$1 sql=$2 port out
    port=$(port_of "$dir" sql)
    [ -n "$port" ] || die "$dir: no server started there (no $dir/ports)"
    if ! out=$(isql-vt "127.0.0.1:$port" dba dba exec="$sql" 2>&1); then
        printf '%s\n' "$out" >&2
        die "isql on port $port failed"
    fi
    printf '%s\n' "$out"
    if grep -q '\*\*\* Error' <<<"$out"; then
        die "isql on port $port: $(grep -m1 '\*\*\* Error' <<<"$out")"
    fi
}

running_pid() {
    local pid
    pid=$(cat "$1/virtuoso.pid" 2>/dev/null) || return 1
    [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null && echo "$pid"
}

cmd_start() {
    [ $# -eq 3 ] || usage
    local dir=$1 port_sql=$2 port_http=$3
    for p in "$port_sql" "$port_http"; do
        [[ $p =~ ^[0-9]+$ ]] && [ "$p" -gt 0 ] && [ "$p" -lt 65536 ] || die "bad port '$p'"
    done
    [ "$port_sql" != "$port_http" ] || die "the SQL and HTTP ports must differ"
    command -v virtuoso-t >/dev/null || die "virtuoso-t not found: apt-get install virtuoso-opensource"
    mkdir -p "$dir/load"
    dir=$(cd "$dir" && pwd)
    if pid=$(running_pid "$dir"); then die "$dir: a server is already running (PID $pid)"; fi

    # The packaged ini, with every path in DIR, both listeners on loopback, DIR readable by
    # the bulk loader and the 10,000-row cut of SPARQL results lifted.
    awk -v dir="$dir" -v psql="$port_sql" -v phttp="$port_http" '
        /^[[:space:]]*\[/ { section = $0; gsub(/[][[:space:]]/, "", section) }
        function set(key, value) { if ($0 ~ "^[[:space:]]*" key "[[:space:]]*=") { print key " = " value; return 1 } return 0 }
        section == "Database" && (set("DatabaseFile", dir "/virtuoso.db") || set("ErrorLogFile", dir "/virtuoso.log") ||
            set("LockFile", dir "/virtuoso.lck") || set("TransactionFile", dir "/virtuoso.trx") ||
            set("xa_persistent_file", dir "/virtuoso.pxa")) { next }
        section == "TempDatabase" && (set("DatabaseFile", dir "/virtuoso-temp.db") ||
            set("TransactionFile", dir "/virtuoso-temp.trx")) { next }
        section == "Parameters" && (set("ServerPort", "127.0.0.1:" psql) ||
            set("DirsAllowed", "., /usr/share/virtuoso-opensource-7/vad, " dir)) { next }
        section == "HTTPServer" && set("ServerPort", "127.0.0.1:" phttp) { next }
        section == "URIQA" && set("DefaultHost", "127.0.0.1:" phttp) { next }
        section == "SPARQL" && set("ResultSetMaxRows", "1000000") { next }
        { print }
    ' "$template" >"$dir/virtuoso.ini"
    grep -q "^ServerPort = 127.0.0.1:$port_http" "$dir/virtuoso.ini" &&
        grep -q "^ServerPort = 127.0.0.1:$port_sql" "$dir/virtuoso.ini" ||
        die "could not write the ports into $dir/virtuoso.ini (unexpected $template)"
    printf 'sql=%s\nhttp=%s\n' "$port_sql" "$port_http" >"$dir/ports"

    # Own output files, so that the caller's pipes (ctest's) are not held open by the server.
    (cd "$dir" && exec virtuoso-t +foreground +configfile "$dir/virtuoso.ini" \
        </dev/null >"$dir/virtuoso.out" 2>&1) &
    local pid=$!
    echo "$pid" >"$dir/virtuoso.pid"

    local timeout=${VIRTUOSO_START_TIMEOUT:-90} start=$SECONDS
    until isql-vt "127.0.0.1:$port_sql" dba dba exec="select 1;" >/dev/null 2>&1 &&
        curl -sf -o /dev/null --max-time 5 "http://127.0.0.1:$port_http/sparql?query=ASK%7B%7D"; do
        if ! kill -0 "$pid" 2>/dev/null; then
            tail -n 15 "$dir/virtuoso.log" "$dir/virtuoso.out" >&2 2>/dev/null || true
            rm -f "$dir/virtuoso.pid"
            die "the server exited during start-up (log above: $dir/virtuoso.log)"
        fi
        if [ $((SECONDS - start)) -ge "$timeout" ]; then
            tail -n 15 "$dir/virtuoso.log" >&2 2>/dev/null || true
            kill "$pid" 2>/dev/null || true
            die "not ready after ${timeout} s on ports $port_sql (SQL) and $port_http (HTTP); stopped it"
        fi
        sleep 0.5
    done
    # Unauthenticated SPARQL and Graph Store updates (loopback only).
    run_isql "$dir" 'GRANT SPARQL_UPDATE TO "SPARQL";' >/dev/null
    echo "virtuoso: PID $pid, SQL 127.0.0.1:$port_sql, HTTP http://127.0.0.1:$port_http/ ($((SECONDS - start)) s)"
}

cmd_stop() {
    [ $# -eq 1 ] || usage
    local dir=$1 pid
    pid=$(running_pid "$dir") || { rm -f "$dir/virtuoso.pid"; return 0; }
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 1 100); do
        kill -0 "$pid" 2>/dev/null || { rm -f "$dir/virtuoso.pid"; return 0; }
        sleep 0.2
    done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$dir/virtuoso.pid"
    echo "virtuoso.sh: PID $pid did not stop within 20 s; killed" >&2
}

sql_string() { printf "'%s'" "${1//\'/\'\'}"; }

cmd_bulkload() {
    [ $# -ge 2 ] && [ $# -le 3 ] || usage
    local dir=$1 src=$2 graph=${3:-urn:geotex:bulkload}
    dir=$(cd "$dir" && pwd)
    running_pid "$dir" >/dev/null || die "$dir: no running server"
    [ -e "$src" ] || die "$src: no such file or directory"
    # The loader reads only from DirsAllowed (DIR): each load gets a fresh directory there
    # holding links to the files, so load_list rows of earlier loads never shadow it.
    local n=1
    while [ -e "$dir/load/$n" ]; do n=$((n + 1)); done
    local into="$dir/load/$n"
    mkdir -p "$into"
    if [ -d "$src" ]; then
        local f found=0
        for f in "$src"/*; do
            [ -f "$f" ] || continue
            ln -s "$(realpath "$f")" "$into/$(basename "$f")"
            found=1
        done
        [ "$found" -eq 1 ] || die "$src: no file to load"
    else
        ln -s "$(realpath "$src")" "$into/$(basename "$src")"
    fi
    run_isql "$dir" "ld_dir($(sql_string "$into"), '%', $(sql_string "$graph")); rdf_loader_run(); checkpoint;" >/dev/null
    local errors
    errors=$(run_isql "$dir" "select ll_file, ll_error from DB.DBA.load_list where ll_file like $(sql_string "$into/%") and (ll_error is not null or ll_state <> 2);")
    if grep -q "$into/" <<<"$errors"; then
        printf '%s\n' "$errors" >&2
        die "bulk load of $src failed (DB.DBA.load_list above)"
    fi
}

[ $# -ge 1 ] || usage
command=$1
shift
case "$command" in
    start) cmd_start "$@" ;;
    stop) cmd_stop "$@" ;;
    isql) [ $# -eq 2 ] || usage; run_isql "$@" ;;
    bulkload) cmd_bulkload "$@" ;;
    *) usage ;;
esac
