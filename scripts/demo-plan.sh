#!/usr/bin/env bash
# What `make demo` is about to do on this machine, said before it starts: what it installs,
# what it builds, and roughly how long each step takes on a 2-core machine (measured on one:
# the wasm-bindgen CLI about 11 minutes, each WebAssembly module 2 - 4 minutes the first time).
# Usage: scripts/demo-plan.sh WASM_TARGET WASM_BINDGEN_VERSION WASM_DIR MODULE...
set -u
target=$1 bindgen=$2 wasm_dir=$3
shift 3
steps=()
minutes=0
add() { steps+=("$1"); minutes=$((minutes + $2)); }
rustup target list --installed 2>/dev/null | grep -qx "$target" || add "add the $target Rust target (about 1 minute)" 1
if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $bindgen" ]; then
  add "compile the wasm-bindgen CLI $bindgen with cargo install (about 11 minutes on 2 cores, once)" 11
fi
command -v wasm-opt >/dev/null || add "install Debian's binaryen for wasm-opt (about 1 minute)" 1
[ -f vendor/node_modules/.package-lock.json ] || add "install three.js from npm for the 3D view (under a minute)" 1
stale=0
for m in "$@"; do
  [ -f "$wasm_dir/$m.opt.wasm" ] || stale=$((stale + 1))
done
[ "$stale" -gt 0 ] && add "build $stale of the $# WebAssembly modules in release (2 - 4 minutes each)" $((stale * 3))
if [ ${#steps[@]} -eq 0 ]; then
  echo "make demo: everything is installed and built; rebuilding what changed, then serving"
  exit 0
fi
echo "make demo will, before it serves the demo:"
for s in "${steps[@]}"; do echo "  - $s"; done
echo "  about $minutes minutes in all on a 2-core machine; each step says when it starts."
