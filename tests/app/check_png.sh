# check_png FILE: the file exists, is a PNG (its magic bytes) and is more than 10 kB (a figure
# with drawn data); exits 1 with a message otherwise. Sourced by the plot tests.
check_png() {
  local png=$1 magic size
  if [ ! -f "$png" ]; then
    echo "FAIL: $png was not written" >&2
    exit 1
  fi
  magic=$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')
  if [ "$magic" != "89504e470d0a1a0a" ]; then
    echo "FAIL: $png is not a PNG (magic bytes $magic)" >&2
    exit 1
  fi
  size=$(stat -c %s "$png")
  if [ "$size" -le 10240 ]; then
    echo "FAIL: $png is only $size bytes (expected > 10 kB)" >&2
    exit 1
  fi
}
