#!/usr/bin/env bash
# Draws every built-in scene and every example scene file (host/scenes/*.toml) at 240x240 into
# docs/images/gallery/, in the format (and pixels) `--format auto` picks for the Cortex-M0 at 35 dB, and
# prints the book's gallery: a Markdown table of the pictures, what each shows and the format.
# Run from the repository's root, with `obscura` on the PATH (as `obscura book` runs it).
set -euo pipefail

out=docs/images/gallery
mkdir -p "$out"
echo "| picture | scene | what it shows | drawn in |"
echo "|---|---|---|---|"

# Each scene and what it shows: a built-in's summary; a file's header up to its first colon or
# full stop, without what it says in parentheses.
scenes() {
    obscura scenes | grep -v '^(' | sed -E 's/^([^ ]+) +/\1\t/'
    for file in host/scenes/*.toml; do
        header=$(sed -n '/^#/!q; s/^# *//p' "$file" | tr '\n' ' ' | sed -E 's/ *\([^)]*\)//g')
        printf '%s\t%s\n' "$file" "${header%%[:.] *}"
    done
}

scenes | while IFS=$'\t' read -r scene shows; do
    name=$(basename "$scene" .toml)
    said=$(obscura render "$scene" --format auto --cost-on m0 --target-psnr 35 --size 240x240 \
        -o "$out/$name.png" 2>&1 >/dev/null)
    # auto says on standard error what it picked (a format, with adaptive pixels where it took
    # them), what it measured, and any rescaling.
    format=$(sed -nE 's/^--format auto: ([^ ]+)( with [^ ]+ pixels)? is the cheapest.*\(([0-9.]+) dB measured.*/`\1`\2, \3 dB/p' <<<"$said")
    rescaled=$(sed -nE 's/.* only rescaled by ([0-9.e-]+) .*/, rescaled ×\1/p' <<<"$said")
    echo "| ![$name](images/gallery/$name.png) | \`$scene\` | $shows | $format$rescaled |"
done
