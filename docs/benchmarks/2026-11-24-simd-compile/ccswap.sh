#!/bin/bash
# cc that compiles $SWAP_SRC instead of the generated megakernel (the source that defines
# rill_run and is over 100 kB), to time variants of one kernel's C in the same program.
src="${@: -2:1}"
if [ -n "$SWAP_SRC" ] && [ $(stat -c %s "$src") -gt 100000 ]; then cp "$SWAP_SRC" "$src"; fi
exec /usr/bin/cc "$@" $RILL_EXTRA_FLAGS
