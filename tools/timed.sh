#!/bin/sh
# Runs a command and says how long it took (the Makefile's steps):
#   tools/timed.sh "what it does" command [args...]
# The command's exit status is passed on.
what=$1
shift
start=$(date +%s)
"$@"
rc=$?
s=$(($(date +%s) - start))
if [ "$rc" -eq 0 ]; then
    printf 'penumbra: %s: %d min %02d s\n' "$what" $((s / 60)) $((s % 60))
else
    printf 'penumbra: %s: failed after %d min %02d s\n' "$what" $((s / 60)) $((s % 60)) >&2
fi
exit "$rc"
