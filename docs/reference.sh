#!/usr/bin/env bash
# Writes the guide's command reference (docs/src/reference/gough.md and arm.md) from the binaries'
# own help, so that it cannot drift from them. CI writes the pages into a temporary directory with
# the debug binaries and fails if they differ from the committed ones: after changing a command's
# help, run
#   docs/reference.sh target/debug/gough target/debug/arm
# and commit the pages.
# Usage: docs/reference.sh [GOUGH_BINARY] [ARM_BINARY] [OUT_DIR (default docs/src/reference)]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
gough="${1:-gough}"
arm="${2:-arm}"
out="${3:-$here/src/reference}"

# The subcommands a binary lists under "Commands:" (without `help`).
subcommands() {
  "$1" --help | awk '/^Commands:/ { on = 1; next } on && /^$/ { exit } on && /^  [a-z]/ { print $1 }' |
    grep -vx help
}

# One page: the binary's own help, then each subcommand's, verbatim, trailing spaces removed.
page() {
  local bin="$1" name="$2" title="$3" out="$4"
  {
    echo "# \`$name\`: $title"
    echo
    echo "<!-- Written by docs/reference.sh from \`$name --help\` and \`$name help <command>\`: do not"
    echo "edit by hand; CI fails when this page differs from the binary's help. -->"
    echo
    echo "Every subcommand's help as \`$name help <command>\` prints it (\`-h\` prints a summary)."
    echo
    echo '```text'
    "$bin" --help | sed 's/[[:space:]]*$//'
    echo '```'
    for cmd in $(subcommands "$bin"); do
      echo
      echo "## \`$name $cmd\`"
      echo
      echo '```text'
      "$bin" help "$cmd" | sed 's/[[:space:]]*$//'
      echo '```'
    done
  } > "$out"
}

mkdir -p "$out"
page "$gough" gough "the Gough (Stewart) platform" "$out/gough.md"
page "$arm" arm "serial arms" "$out/arm.md"
