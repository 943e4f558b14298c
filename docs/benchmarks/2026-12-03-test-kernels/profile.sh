#!/bin/bash
# Run from the repository root after a build: every test of build/ run alone, one after another,
# with empty caches (PoCL's and Mesa's in a new XDG_CACHE_HOME, build/kernel-cache moved aside
# and restored), logging per test: name, seconds, exit status, the kernel cache before and after.
# (log.tsv here keeps only the new entries: the fifth column.) Summaries: families.py, suites.py.
cd build
export XDG_CACHE_HOME=${PROF:-/tmp/prof}/xdg
rm -rf ${PROF:-/tmp/prof}/xdg kernel-cache.prof; mkdir -p ${PROF:-/tmp/prof}/xdg
mkdir -p ${PROF:-/tmp/prof}; mv kernel-cache kernel-cache.saved 2>/dev/null
ctest -N | sed -n 's/^ *Test *#[0-9]*: //p' > ${PROF:-/tmp/prof}/tests.txt
: > ${PROF:-/tmp/prof}/log.tsv
while read -r t; do
  before=$(ls kernel-cache 2>/dev/null | sed 's/-[0-9a-f]*\.rill//' | sort | uniq -c | tr '\n' ' ')
  s=$(date +%s.%N)
  ctest -R "^$(printf '%s' "$t" | sed 's/[][\\.^$*+?(){}|]/\\&/g')\$" --timeout 600 >/dev/null 2>&1; rc=$?
  e=$(date +%s.%N)
  after=$(ls kernel-cache 2>/dev/null | sed 's/-[0-9a-f]*\.rill//' | sort | uniq -c | tr '\n' ' ')
  printf '%s\t%.2f\t%s\t%s\t%s\n' "$t" "$(echo "$e - $s" | bc)" "$rc" "$before" "$after" >> ${PROF:-/tmp/prof}/log.tsv
done < ${PROF:-/tmp/prof}/tests.txt
echo done >> ${PROF:-/tmp/prof}/log.tsv
rm -rf kernel-cache; mv kernel-cache.saved kernel-cache 2>/dev/null
