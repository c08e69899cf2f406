# The start a CLI check shares, sourced with the check's arguments:
# RCBENCH is the binary ($1), the check runs in a scratch folder removed on
# exit, and fail() ends it with a message.
set -u
RCBENCH="$1"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
fail() { echo "FAIL $*"; exit 1; }
