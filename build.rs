//! Hands the firmware its memory map (memory.x). The library and the host never link against
//! one, so nothing happens unless the `firmware` feature is on and the target is a Cortex-M.

use std::env;
use std::fs;
use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    if env::var_os("CARGO_FEATURE_FIRMWARE").is_none() {
        return;
    }
    let target = env::var("TARGET").unwrap_or_default();
    if !target.starts_with("thumbv") {
        return;
    }
    // Copied next to the build's other outputs, so the map is found even where the linker
    // does not run in this directory (a dependent workspace).
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x is readable");
    println!("cargo:rustc-link-search={}", out.display());
    if target.starts_with("thumbv6m") {
        // memory.x switches to the nRF51 map of the micro:bit.
        println!("cargo:rustc-link-arg-bins=--defsym=__nrf51=1");
    }
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
}
