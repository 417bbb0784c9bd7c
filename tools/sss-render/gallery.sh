#!/usr/bin/env bash
# Regenerates docs/gallery.md and its images from the scenes in examples/scenes/gallery/ (the figures of
# Bell & Linnett) with sss-render. Usage: tools/sss-render/gallery.sh [path/to/sss-render] (default
# build/tools/sss-render). Run from anywhere; writes docs/gallery/<stem>.png and docs/gallery.md.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
render="$(realpath "${1:-$root/build/tools/sss-render}")"
out="$root/docs/gallery"
mkdir -p "$out"
md="$root/docs/gallery.md.tmp"
{
    echo "# Gallery: the figures of Bell & Linnett, from scene files"
    echo
    echo "Each image is rendered by \`sss-render\` from the scene below it (examples/scenes/gallery/). Regenerate"
    echo "every image and this page with \`tools/sss-render/gallery.sh\`. Port is on the left, starboard on the"
    echo "right, one row per ping, time going down."
} > "$md"
for scene in "$root"/examples/scenes/gallery/*.toml; do
    name="$(basename "$scene" .toml)"
    "$render" "$scene" -o "$out" > /dev/null 2> "$out/$name.log" || { cat "$out/$name.log" >&2; exit 1; }
    timing="$(grep -o '[0-9.]* ms/ping' "$out/$name.log" || true)"
    rm -f "$out/$name.log"
    {
        echo
        echo "## $name"
        echo
        sed -n '/^#/!q; s/^# \{0,1\}//p' "$scene" # the scene's opening comment: its caption
        echo
        echo "![$name](gallery/$name.png)"
        echo
        echo "<details><summary>scene ($timing on the machine that rendered it)</summary>"
        echo
        echo '```toml'
        cat "$scene"
        echo '```'
        echo
        echo "</details>"
    } >> "$md"
done
mv "$md" "$root/docs/gallery.md"
echo "docs/gallery.md and $(ls "$out"/*.png | wc -l) images written"
