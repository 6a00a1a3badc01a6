#!/usr/bin/env bash
# usage: bench/sigterm_latency.sh BIN SOURCE_DIR SECONDS — copies the interrupted run SOURCE_DIR, resumes
# it (`BIN run --resume COPY`), sends SIGTERM after SECONDS and prints the time from the signal to
# the process' exit (reaped by this shell: `wait`).
set -u
bin=$1; source=$2; after=$3
copy="$source.measure"
rm -rf "$copy"; cp -r "$source" "$copy"
"$bin" run --resume "$copy" --quiet > "$copy.stdout" 2> "$copy.stderr" &
pid=$!
sleep "$after"
sent=$(date +%s.%N)
kill -TERM "$pid"
wait "$pid"; code=$?
ended=$(date +%s.%N)
echo "after ${after} s: exit $code, SIGTERM to exit $(echo "$ended - $sent" | bc) s; $(grep -o '"status": "[a-z_]*"' "$copy/manifest.json"), $(grep -o '"steps": [0-9]*' "$copy/manifest.json"); $(grep -o 'solve [0-9.]*' "$copy.stdout") µs mean solve"
