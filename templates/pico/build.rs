//! Proves `scene.toml` in i16f16 for the display's 240×240 pixels on this computer, and writes
//! its words for `main.rs` to include; links with cortex-m-rt's `link.x` and this `memory.x`.

use obscura_scene::Format;
use obscura_scene::build::Proof;
use std::path::PathBuf;
use std::{env, fs};

fn main() {
    // i16f16 suits the Pico's Cortex-M0+, which has no FPU. `obscura firmware --target m0 --scene
    // scene.toml --format auto` names the cheapest format that holds your scene on that core.
    Proof::new("scene.toml", Format::I16f16, (240, 240)).write("scene.rs");

    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x is readable");
    println!("cargo::rustc-link-search={}", out.display());
    println!("cargo::rerun-if-changed=memory.x");
    println!("cargo::rustc-link-arg-bins=-Tlink.x");
}
