#!/usr/bin/env bash
# Width of a caustic line in an image: the full width at half maximum (pixels, interpolated) of
# the brightest peak in one pixel column, above the column's darkest tenth (the background).
# usage: bench/caustic_width.sh IMAGE.exr X Y0 HEIGHT          (a column: x = X, y from Y0)
#        bench/caustic_width.sh --row IMAGE.exr Y X0 WIDTH    (a row: y = Y, x from X0)
# (needs oiiotool, Debian openimageio-tools). "peak y" is then the peak's x.
set -euo pipefail
if [ "$1" = --row ]; then
  img=$2 y=$3 y0=$4 w=$5
  cut="${w}x1+${y0}+${y}"
else
  img=$1 x=$2 y0=$3 h=$4
  cut="1x${h}+${x}+${y0}"
fi
tmp=$(mktemp --suffix=.exr)
trap 'rm -f "$tmp"' EXIT
oiiotool "$img" --cut "$cut" -o "$tmp"
oiiotool --dumpdata "$tmp" | awk -v y0="$y0" '
  /Pixel/ { v[n++] = ($(NF-2) + $(NF-1) + $NF) / 3 }
  END {
    for (i = 0; i < n; ++i) {  # insertion sort (mawk has no asort)
      s[i] = v[i]
      for (j = i; j > 0 && s[j - 1] > s[j]; --j) { t = s[j]; s[j] = s[j - 1]; s[j - 1] = t }
    }
    bg = s[int(n / 10)]
    p = 0; for (i = 1; i < n; ++i) if (v[i] > v[p]) p = i
    half = bg + (v[p] - bg) / 2
    lo = p; while (lo > 0 && v[lo - 1] > half) --lo
    hi = p; while (hi < n - 1 && v[hi + 1] > half) ++hi
    # Interpolate where the profile crosses half on either side.
    left = lo > 0 ? lo - (v[lo] - half) / (v[lo] - v[lo - 1]) : lo
    right = hi < n - 1 ? hi + (v[hi] - half) / (v[hi] - v[hi + 1]) : hi
    printf "peak y %d, peak %.4g, background %.4g, FWHM %.2f px\n", y0 + p, v[p], bg, right - left
  }'
