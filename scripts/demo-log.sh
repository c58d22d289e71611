#!/usr/bin/env bash
# The demo's `legwork`: runs the real CLI ($LEGWORK_BIN) after appending the
# command line to $OUT/commands.txt, paths shortened to the repo root, so that
# the gallery shows under every result the command that made it.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
line="legwork"
for a in "$@"; do
  a="${a//$root\//}"
  case "$a" in
    *[[:space:]\'\"\$\;\&\|\<\>\(\)\*\?]*) a="'${a//\'/\'\\\'\'}'" ;;
  esac
  line+=" $a"
done
log="${OUT:?OUT is the demo output folder}/commands.txt"
# The first line names the results folder as the commands write it, so the
# gallery matches each result to the command naming it exactly.
[ -s "$log" ] || echo "# results: ${OUT//$root\//}" > "$log"
echo "$line" >> "$log"
exec "${LEGWORK_BIN:?LEGWORK_BIN is the legwork CLI}" "$@"
