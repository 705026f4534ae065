# The preamble of the shell tests, sourced first:
#   . "$(dirname "$(realpath "$0")")/test_lib.sh" "$@"
# with the test's arguments GEOTEX [SOURCE_DIR]. Sets $geotex and $src (absolute), makes a
# scratch directory $work the current directory (removed at exit, read-only files and all),
# and gives fail (count a failure with its message) and finish NAME (report and exit 1 when
# anything failed).
geotex=$(realpath "$1")
src=${2:+$(realpath "$2")}
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
finish() {
    [ "$failures" -eq 0 ] && echo "$1 tests passed" && exit 0
    echo "$failures $1 test(s) failed"
    exit 1
}
# expect_error CODE PATTERN cmd...: the command exits with CODE and writes exactly one
# 'geotex: error:' line, which matches PATTERN (grep); each miss is a failure.
expect_error() {
    local code=$1 pattern=$2 rc=0
    shift 2
    "$@" >expect.out 2>expect.err || rc=$?
    if [ "$rc" != "$code" ]; then
        fail "'$*' exited $rc, expected $code"; cat expect.err
    elif [ "$(grep -c '^geotex: error:' expect.err)" != 1 ]; then
        fail "'$*': not exactly one error line"; cat expect.err
    elif ! grep -q -- "$pattern" expect.err; then
        fail "'$*': the error does not say '$pattern'"; cat expect.err
    fi
}
