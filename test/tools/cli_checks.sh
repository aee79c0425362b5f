#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# What the TOOL_cli.sh tests share, sourced after they set TOOL_NAME and TOOL: a scratch folder
# $TMP removed on exit, a failure counter, and
#   expect CODE PATTERN ARGS...
# which runs "$TOOL" ARGS... and counts a failure unless it exits with CODE and its standard error
# (for code 0: its standard output) matches the extended regex PATTERN. The output stays in
# $TMP/out and $TMP/err for further checks.
TMP=$(mktemp -d "/tmp/ot_${TOOL_NAME}_XXXXXX")
trap 'rm -rf "$TMP"' EXIT
failures=0

expect() {
  local code=$1 pattern=$2 got
  shift 2
  "$TOOL" "$@" > "$TMP/out" 2> "$TMP/err"
  got=$?
  local text=$TMP/err
  [ "$code" -eq 0 ] && text=$TMP/out
  if [ "$got" -ne "$code" ] || ! grep -Eq -- "$pattern" "$text"; then
    echo "FAILED: $TOOL_NAME $*: exit $got (want $code), output does not match '$pattern':"
    cat "$TMP/out" "$TMP/err"
    failures=$((failures + 1))
  fi
}
