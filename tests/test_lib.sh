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
