#!/usr/bin/env bash
# Every check obscura must pass, installing what is missing first. Run from anywhere:
#   host/check.sh
# It is what CI runs (.ci/run) and what the README calls the test command.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n==> %s\n' "$*"; }

THUMB_TARGETS=(thumbv7em-none-eabihf thumbv6m-none-eabi)

step "toolchain: rustfmt, clippy and the thumb targets"
installed_components=$(rustup component list --installed)
for component in rustfmt clippy; do
    grep -q "^$component" <<<"$installed_components" || rustup component add "$component"
done
installed_targets=$(rustup target list --installed)
for target in "${THUMB_TARGETS[@]}"; do
    grep -qx "$target" <<<"$installed_targets" || rustup target add "$target"
done

step "format"
cargo fmt --all -- --check

step "clippy, host"
cargo clippy --workspace --all-targets --locked -- -D warnings

step "clippy, core on a 32-bit target"
cargo clippy -p obscura --target thumbv6m-none-eabi --locked -- -D warnings

step "documentation"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --quiet

for target in "${THUMB_TARGETS[@]}"; do
    step "no_std core for $target"
    cargo build -p obscura --release --target "$target" --locked
done

step "tests"
cargo test --workspace --locked
