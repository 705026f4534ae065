# The start every shell test shares, sourced with the geotex binary as argument: $geotex,
# a private working directory (removed at exit) as the current one, and fail() counting
# into $failures. Usage: . "$(dirname "$(realpath "$0")")/shell_start.sh" "$1"
geotex=$(realpath "$1")
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
