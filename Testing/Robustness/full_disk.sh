#!/bin/bash
# A full disk (a 16 KiB tmpfs, as root) under shockfilter writing a PNG: one
# line on stderr ("... Ran out of disk space ... (libpng: Write Error)": libpng's
# own lines folded into it), exit code 2, no file left behind. Skipped (77)
# where a tmpfs cannot be mounted (not root, a container without the right).
#   full_disk.sh SHOCKFILTER WORKDIR
set -u
program=$1
work=$2
rm -rf "$work" && mkdir -p "$work/full" || exit 1
if ! mount -t tmpfs -o size=16k tmpfs "$work/full" 2>/dev/null; then
  echo "SKIP: cannot mount a tmpfs here"
  exit 77
fi
trap 'umount "$work/full"' EXIT
# An image whose PNG (about 60 KB of noise) cannot fit.
"$program" demo "$work/demo" >/dev/null 2>&1 || { echo "FAIL: demo"; exit 1; }
input=$(ls "$work"/demo/*.png | head -1)
"$program" image "$input" "$work/full/out.png" --time 1 >"$work/stdout" 2>"$work/stderr"
code=$?
lines=$(wc -l <"$work/stderr")
if [ "$code" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -q "out.png: .*disk space" "$work/stderr"; then
  echo "FAIL: exit $code, $lines line(s) on stderr:"
  cat "$work/stderr"
  exit 1
fi
if [ -n "$(ls -A "$work/full")" ]; then
  echo "FAIL: files left on the full disk: $(ls -A "$work/full")"
  exit 1
fi
echo "OK: $(cat "$work/stderr")"
