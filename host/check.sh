#!/usr/bin/env bash
# Every check obscura must pass, installing what is missing first. Run from anywhere:
#   host/check.sh
# It is what CI runs (.ci/run) and what the README calls the test command.
set -euo pipefail
cd "$(dirname "$0")/.."

# Each step says when it starts, in seconds from the check's start.
step() { printf '\n==> [%4d s] %s\n' "$SECONDS" "$*"; }

M4F=thumbv7em-none-eabihf
M0=thumbv6m-none-eabi
M33=thumbv8m.main-none-eabihf
RV32=riscv32imac-unknown-none-elf
# The harness, built once for every step that runs it (with the preview's window, which one
# step needs: a second build without it would cost minutes).
OBSCURA=(cargo run --release --locked -p obscura-host --features window --)
# The firmware's configuration (obscura_scene::firmware): every scene, format and method.
EVERYTHING=(OBSCURA_SCENES=whitted,shapes OBSCURA_FORMATS=i16f16,i20f12,i32f32,f32-approx,f32
    OBSCURA_VARIANTS=each)

step "toolchain: rustfmt, clippy and the microcontrollers' targets"
installed_components=$(rustup component list --installed)
for component in rustfmt clippy; do
    grep -q "^$component" <<<"$installed_components" || rustup component add "$component"
done
installed_targets=$(rustup target list --installed)
for target in "$M4F" "$M0" "$M33" "$RV32"; do
    grep -qx "$target" <<<"$installed_targets" || rustup target add "$target"
done

step "QEMU, for Arm and for RISC-V"
for qemu in qemu-system-arm:qemu-system-arm qemu-system-riscv32:qemu-system-misc; do
    binary=${qemu%%:*} package=${qemu##*:}
    if ! command -v "$binary" >/dev/null; then
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
            apt-get update -qq
            DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$package"
        else
            echo "$binary is missing; install it with: sudo apt-get install $package" >&2
            exit 1
        fi
    fi
    "$binary" --version | head -n 1
done

step "Node.js and the RP2040 emulator (rp2040js, pinned by host/rp2040/package-lock.json)"
if ! command -v npm >/dev/null; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nodejs npm
    else
        echo "Node.js is missing; install it with: sudo apt-get install nodejs npm" >&2
        exit 1
    fi
fi
node --version
npm ci --prefix host/rp2040 --no-audit --no-fund --silent
# The ROM stand-in is built from its source where an assembler is at hand.
if command -v llvm-mc >/dev/null && command -v llvm-objcopy >/dev/null; then
    rom=$(mktemp -d)
    llvm-mc -triple=thumbv6m-none-eabi -filetype=obj host/rp2040/rom.s -o "$rom/rom.o"
    llvm-objcopy -O binary -j .text "$rom/rom.o" "$rom/rom.bin"
    cmp "$rom/rom.bin" host/rp2040/rom.bin
fi

step "SDL2, for obscura preview's window"
if ! dpkg -s libsdl2-dev >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends libsdl2-dev
    else
        echo "libsdl2-dev is missing; install it with: sudo apt-get install libsdl2-dev" >&2
        exit 1
    fi
fi

step "format (the workspace and the firmware template)"
cargo fmt --all -- --check
cargo fmt --manifest-path templates/pico/Cargo.toml -- --check

step "clippy, host (the core and the harness, with and without the preview's window)"
cargo clippy --all-targets --locked -- -D warnings
cargo clippy -p obscura-host --all-targets --features window --locked -- -D warnings

step "clippy, core on a 32-bit target"
cargo clippy -p obscura --target "$M0" --locked -- -D warnings

step "clippy, the firmware on the Arm targets and RISC-V, and the three boards (the Pico 2's on both of its architectures)"
for target in "$M4F" "$M0" "$RV32"; do
    env "${EVERYTHING[@]}" cargo clippy --release -p obscura-firmware -p obscura-qemu --target "$target" --locked -- -D warnings
done
cargo clippy --release -p obscura-black-pill --target "$M4F" --locked -- -D warnings
cargo clippy --release -p obscura-pico --target "$M0" --locked -- -D warnings
for target in "$M33" "$RV32"; do
    cargo clippy --release -p obscura-pico2 --target "$target" --locked -- -D warnings
done

step "documentation, private items too (their links are checked as the public ones)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --locked --quiet --document-private-items
# The core as a user's `cargo doc` shows it: without the workspace's feature `instrument`, every
# link of its public documentation resolves to a public item.
RUSTDOCFLAGS="-D warnings" cargo doc -p obscura --no-deps --locked --quiet

step "the core and the scene crate as crates.io would take them: cargo package"
# Its verification unpacks the packaged crates into a local registry's sources (a directory
# named by a hash of this checkout's path) and, where one of the same version is there already,
# keeps the one unpacked before: remove them, so that it verifies these sources.
rm -rf "${CARGO_HOME:-$HOME/.cargo}"/registry/src/-*/obscura-*
cargo package -p obscura -p obscura-scene --locked --quiet

step "the library's dependencies: none of the firmware's"
if cargo tree -p obscura -e normal --locked --prefix none | grep -E "cortex-m|stm32|mipidsi|obscura-"; then
    echo "the obscura library depends on a firmware crate (above)" >&2
    exit 1
fi

step "the firmware's build graph: the core and the scene crate, no desktop crate"
for board in obscura-qemu obscura-black-pill obscura-pico obscura-pico2; do
    if cargo tree -p "$board" --target all -e normal,build --locked --prefix none \
        | grep -E "^(obscura-host|clap|plotters|rayon|image|indicatif) "; then
        echo "the firmware's build ($board) depends on a desktop crate (above)" >&2
        exit 1
    fi
done

step "firmware for the ST7789 on an STM32F411 Black Pill, a Raspberry Pi Pico and a Pico 2 (both architectures), from a scene file, as the README builds them"
OBSCURA_SCENES=host/scenes/pyramid.toml OBSCURA_FORMATS=f32 cargo build --release -p obscura-black-pill --target "$M4F" --locked
OBSCURA_SCENES=host/scenes/pyramid.toml OBSCURA_FORMATS=i16f16 cargo build --release -p obscura-pico --target "$M0" --locked
OBSCURA_SCENES=host/scenes/pyramid.toml OBSCURA_SAMPLES=16 OBSCURA_ADAPTIVE_SAMPLES=true \
    cargo build --release -p obscura-pico --target "$M0" --locked
OBSCURA_SCENES=host/scenes/pyramid.toml OBSCURA_FORMATS=f32 cargo build --release -p obscura-pico2 --target "$M33" --locked
OBSCURA_SCENES=host/scenes/orbit.toml OBSCURA_FORMATS=f32 cargo build --release -p obscura-pico2 --target "$M33" --locked
OBSCURA_SCENES=host/scenes/pyramid.toml OBSCURA_FORMATS=i16f16 cargo build --release -p obscura-pico2 --target "$RV32" --locked

step "the firmware template, copied outside the workspace as a stranger would, builds within 48 KiB of flash"
template=$(mktemp -d)/my-pico
cp -r templates/pico "$template"
rm -rf "$template/target"
sed -i "s|path = \"\.\./\.\.|path = \"$PWD|" "$template/Cargo.toml"
# Its own manifest and lock file, outside the workspace; the workspace's build cache (the same
# dependencies, built once).
shared="$PWD/target"
(cd "$template" && CARGO_TARGET_DIR="$shared" cargo build --release --locked --quiet)
read -r text data _ < <(size "target/$M0/release/my-obscura-pico" | tail -n 1)
echo "templates/pico: $((text + data)) bytes of flash"
if [ $((text + data)) -gt $((48 * 1024)) ]; then
    echo "the template's image is over 48 KiB of flash" >&2
    exit 1
fi

step "a scene the format cannot hold fails the firmware's build, at its line and column"
if OBSCURA_SCENES=host/scenes/hostile/low-light.toml OBSCURA_FORMATS=i16f16 \
    cargo build --release -p obscura-firmware --target "$M4F" --locked 2>target/refused.log; then
    echo "the firmware built a scene i16f16 cannot hold" >&2
    exit 1
fi
grep -F "low-light.toml:14:1: the scene cannot be built in i16f16" target/refused.log

for target in m4f m0; do
    step "firmware under QEMU ($target), bit for bit against the host, within its budget: two runs at once, each its own image"
    "${OBSCURA[@]}" firmware --target "$target" --out-dir "target/at-once/$target-a" \
        --scene whitted,shapes --format i16f16 --budget &
    first=$!
    "${OBSCURA[@]}" firmware --target "$target" --out-dir "target/at-once/$target-b" \
        --scene host/scenes/pyramid.toml --format auto --budget --profile
    wait "$first"
done

step "the Pico's own image and the template's in an RP2040 emulator (one core): what reaches the ST7789, bit for bit against the host"
"${OBSCURA[@]}" emulate whitted --format i16f16
# A core 1 that never answers: the image still draws the whole frame, on core 0.
"${OBSCURA[@]}" emulate host/scenes/ball.toml --format i16f16 --core1 silent --out-dir target/emulate-silent
# The template's image, as the stranger's copy above built it.
"${OBSCURA[@]}" emulate "$template/scene.toml" --format i16f16 \
    --image "target/$M0/release/my-obscura-pico" --out-dir target/emulate-template

step "firmware under QEMU (m33 and rv32, the Pico 2's cores), bit for bit against the host, within its budget"
"${OBSCURA[@]}" firmware --target m33 \
    --scene whitted,shapes --format i16f16,f32 --budget
"${OBSCURA[@]}" firmware --target rv32 \
    --scene whitted,shapes --format i16f16 --budget

step "one scene in one format, under QEMU: within 32 KiB of flash, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m0 --scene whitted \
    --format i16f16 --max-flash 32768
for scene in whitted host/scenes/marbles.toml; do
    "${OBSCURA[@]}" firmware --target m4f --scene "$scene" \
        --format f32 --max-flash 32768
done

step "a camera path's every frame under QEMU (m0, and m4f with adaptive pixels), bit for bit against the host"
"${OBSCURA[@]}" firmware --target m0 --scene host/scenes/orbit.toml --format i16f16
"${OBSCURA[@]}" firmware --target m4f --scene host/scenes/orbit.toml --format i16f16 \
    --pixels adaptive:4

step "firmware under QEMU (m4f), the other formats, methods, row order and dither, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene whitted,shapes \
    --format i16f16,i20f12 --sphere stable --triangle watertight --sqrt approx --rays stepped --bias exclude \
    --order progressive --dither ordered
"${OBSCURA[@]}" firmware --target m4f --scene whitted,shapes \
    --format i32f32,f32-approx,f32 --triangle moller-trumbore

step "firmware under QEMU (m4f), four rays per pixel, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene whitted,shapes \
    --format i16f16,f32 --samples 4

step "firmware under QEMU, adaptive anti-aliasing (corner rows on the stack), bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene whitted \
    --format i16f16,f32 --samples 16 --adaptive-samples true
"${OBSCURA[@]}" firmware --target m0 --scene whitted \
    --format i16f16 --samples 4 --adaptive-samples true

step "firmware under QEMU, a mesh through its hierarchy in flash, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene host/scenes/teapot.toml \
    --format f32
"${OBSCURA[@]}" firmware --target m0 --scene host/scenes/teapot.toml \
    --format i10f22

step "firmware under QEMU (m4f), soft shadows from a disc light, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene soft --format i16f16

step "firmware under QEMU (m4f), depth of field through a lens, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene focus --format i16f16

step "firmware under QEMU, the 32-bit splits that hold a 240x240 scene, bit for bit against the host"
"${OBSCURA[@]}" firmware --target m4f --scene whitted,shapes \
    --format i12f20,i14f18,i18f14
"${OBSCURA[@]}" firmware --target m0 --scene whitted \
    --format i12f20 --sqrt approx --bias exclude
for target in m4f m0; do
    "${OBSCURA[@]}" firmware --target "$target" \
        --scene host/scenes/tabletop.toml --format i10f22
done

step "the preview, headless, against the firmware's frame under QEMU, byte for byte"
"${OBSCURA[@]}" firmware --target m4f \
    --scene host/scenes/pyramid.toml --format i16f16 --order progressive --dither ordered
"${OBSCURA[@]}" preview \
    host/scenes/pyramid.toml --format i16f16 --order progressive --dither ordered --headless \
    -o target/preview.png
cmp target/preview.png out/firmware/m4f/pyramid-i16f16-lecture.png

step "the book: every figure of the README and docs/ that takes seconds is what its command prints"
"${OBSCURA[@]}" book --check --quick

step "fuzz: random scenes for 150 s from a fixed seed, held to every promise"
"${OBSCURA[@]}" fuzz --seconds 150 --seed 1 --out-dir target/fuzz

step "tests"
cargo test --locked
